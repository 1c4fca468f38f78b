#include "peers/morphology_json.h"

#include <nlohmann/json.hpp>

#include "peers/reference_scene.h"

namespace gaitlab::peers {

namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

const char* typeName(body::JointType t) {
  switch (t) {
    case body::JointType::Root: return "root";
    case body::JointType::Hinge: return "hinge";
    case body::JointType::Universal: return "universal";
    case body::JointType::Ball: return "ball";
  }
  return "root";
}

}  // namespace

std::string morphologyJson(gait::Character character) {
  const body::Morphology m = character == gait::Character::Biped ? body::makeBiped() : body::makeQuadruped();
  const std::vector<Motor> motors = holdingMotors(character);
  nlohmann::json segments = nlohmann::json::array();
  for (int i = 0; i < static_cast<int>(m.segments.size()); ++i) {
    const body::Segment& s = m.segments[i];
    nlohmann::json axes = nlohmann::json::array(), lower = nlohmann::json::array(),
                   upper = nlohmann::json::array();
    for (int d = 0; d < body::dofCount(s.joint.type); ++d) {
      axes.push_back(vec(s.joint.axes[d]));
      lower.push_back(s.joint.lower[d]);
      upper.push_back(s.joint.upper[d]);
    }
    segments.push_back({{"name", s.name},
                        {"halfExtents", vec(s.halfExtents)},
                        {"mass", s.mass},
                        {"center", vec(s.center)},
                        {"parent", s.parent},
                        {"motor", {{"kp", motors[i].kp}, {"kd", motors[i].kd}}},
                        {"joint", {{"type", typeName(s.joint.type)}, {"pivot", vec(s.joint.pivot)},
                                   {"axes", axes}, {"lower", lower}, {"upper", upper}}}});
  }
  return nlohmann::json{{"name", m.name},
                        {"armature", m.armature},
                        {"segments", segments}}
      .dump();
}

}  // namespace gaitlab::peers
