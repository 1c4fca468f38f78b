// Probe, built only on request (`ninja -C build/native gaitlab_mirror_log`): is a character's
// gait mirror-symmetric? The body and the controller have no preferred side, so a gait file and
// its mirror image (every left leg's parameters given to the right leg and the other way round,
// the leg frames' yaw and roll graphs negated), started at the same gait phase with mirrored
// goals, should move as mirror images of each other (docs/controller-notes.md, "Left and right").
//
//   build/native/gaitlab_mirror_log GAIT_FILE SPEED PHASE STEPS [TURN] [air] > log.txt
//
// Both walks run side by side; every 12 fixed steps (0.1 s), and at each of the first 12, a line:
// the step, the time, the largest distance between a segment and its partner's mirrored position
// (m) and that segment's name. Over the first three steps also each walk's gait phase, gait period,
// desired velocity (heading frame, m/s) and every leg's role (S stance, w swing) with its progress
// and leg phase, and the joint torques that differ from their mirror by more than 1 mN·m. With
// `air` both start 2 m above the ground, so that contacts (solved in Bullet's constraint order,
// which is not mirror-symmetric) play no part: what differs then, differs in the controller.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "gait/params_io.h"
#include "sim/simulation.h"

using namespace gaitlab;

namespace {

// Left and right swapped in a parameter's leg (frontLeft.stepTrigger ↔ frontRight.stepTrigger,
// left.dutyFactor ↔ right.dutyFactor).
std::string mirroredName(const std::string& name) {
  const size_t dot = name.find('.');
  std::string leg = name.substr(0, dot);
  for (auto [from, to] : {std::pair{"Left", "Right"}, {"Right", "Left"}, {"left", "right"}, {"right", "left"}}) {
    const size_t at = leg.find(from);
    if (at != std::string::npos) {
      leg.replace(at, std::string(from).size(), to);
      break;
    }
  }
  return dot == std::string::npos ? leg : leg + name.substr(dot);
}

nlohmann::json mirroredParams(const nlohmann::json& params) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : params.items()) {
    nlohmann::json v = value;
    const size_t dot = name.rfind('.');
    const std::string field = dot == std::string::npos ? name : name.substr(dot + 1);
    const bool lateral = field == "yaw" || field == "roll";
    if (lateral && v.is_array())
      for (auto& knot : v) knot = -knot.get<double>();
    else if (lateral && v.is_number())
      v = -v.get<double>();
    out[mirroredName(name)] = v;
  }
  return out;
}

// The position of segment j of `c`, mirrored in the x = 0 plane (the walks start at the origin
// facing +z, so x is sideways).
Eigen::Vector3d mirrored(const physics::Character& c, int j) {
  Eigen::Vector3d p = c.segmentState(j).position;
  p.x() = -p.x();
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: gaitlab_mirror_log GAIT_FILE SPEED PHASE STEPS [TURN] [air]\n");
    return 2;
  }
  std::ifstream in(argv[1]);
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json mirror = nlohmann::json::parse(text.str());
  mirror["params"] = mirroredParams(mirror["params"]);
  if (mirror.contains("keys"))
    for (auto& key : mirror["keys"]) key["params"] = mirroredParams(key["params"]);
  gait::GaitFile a, b;
  if (auto e = gait::parseGaitFile(text.str(), std::nullopt, &a)) {
    std::fprintf(stderr, "gaitlab_mirror_log: %s: %s\n", argv[1], e->message.c_str());
    return 2;
  }
  if (auto e = gait::parseGaitFile(mirror.dump(), std::nullopt, &b)) {
    std::fprintf(stderr, "gaitlab_mirror_log: its mirror: %s\n", e->message.c_str());
    return 2;
  }
  const double speed = std::atof(argv[2]), phase = std::atof(argv[3]);
  const int steps = std::atoi(argv[4]);
  const double turn = argc > 5 ? std::atof(argv[5]) : 0.0;
  const bool air = argc > 6 && std::string(argv[6]) == "air";

  sim::Simulation sa(1, 1), sb(1, 1);
  sa.spawn(a.character, 0, 0, 0);
  sb.spawn(b.character, 0, 0, 0);
  sa.controller(0).setGait(a.gait);
  sb.controller(0).setGait(b.gait);
  sa.setGoal(0, {speed, turn});
  sb.setGoal(0, {speed, -turn});
  sa.controller(0).setPhase(phase);
  sb.controller(0).setPhase(phase);
  if (air)
    for (sim::Simulation* s : {&sa, &sb})
      for (int i = 0; i < s->character(0).segmentCount(); ++i) {
        btRigidBody* body = s->character(0).body(i);
        btTransform t = body->getWorldTransform();
        t.getOrigin() += btVector3(0, 2, 0);
        body->setWorldTransform(t);
      }
  const physics::Character& ca = sa.character(0);
  const physics::Character& cb = sb.character(0);
  const body::Morphology& m = ca.morphology();
  // Each segment's partner: the one whose rest centre is its own mirrored (itself on the midline).
  std::vector<int> partner(m.segments.size(), 0);
  for (size_t i = 0; i < m.segments.size(); ++i) {
    double best = INFINITY;
    for (size_t j = 0; j < m.segments.size(); ++j) {
      Eigen::Vector3d c = m.segments[j].center;
      c.x() = -c.x();
      const double d = (m.segments[i].center - c).norm();
      if (d < best) best = d, partner[i] = static_cast<int>(j);
    }
  }
  for (int step = 0; step <= steps; ++step) {
    double worst = 0;
    int at = 0;
    for (int i = 0; i < ca.segmentCount(); ++i) {
      const double d = (ca.segmentState(i).position - mirrored(cb, partner[i])).norm();
      if (d > worst) worst = d, at = i;
    }
    if (step % 12 == 0 || step < 12)
      std::printf("step %d t=%.3f largest %.3g m at %s\n", step, sa.time(), worst, m.segments[at].name.c_str());
    sa.step(1);
    sb.step(1);
    if (step >= 3) continue;
    for (const sim::Simulation* s : {&sa, &sb}) {
      const gait::Controller& c = s->controller(0);
      const gait::GaitPlayer& player = c.player();
      std::printf("  %s: phase %.4f period %.4f v_d %.5f %.5f:", s == &sa ? "gait  " : "mirror", player.phase(),
                  c.params().period, c.desiredVelocity().x(), c.desiredVelocity().z());
      for (int l = 0; l < player.legCount(); ++l)
        std::printf(" %c%.3f/%.3f", player.leg(l).stance ? 'S' : 'w', player.leg(l).progress, player.leg(l).legPhase);
      std::printf("\n");
    }
    const auto& ta = sa.lastTorques(0);
    const auto& tb = sb.lastTorques(0);
    for (int i = 0; i < ca.segmentCount(); ++i) {
      // A torque is an axial vector: mirrored in x = 0, its x part stays and the others turn.
      Eigen::Vector3d t = tb[partner[i]];
      t.y() = -t.y();
      t.z() = -t.z();
      if ((ta[i] - t).norm() > 1e-3)
        std::printf("  torque %s: %.4f %.4f %.4f, mirror's %.4f %.4f %.4f\n", m.segments[i].name.c_str(), ta[i].x(),
                    ta[i].y(), ta[i].z(), t.x(), t.y(), t.z());
    }
  }
}
