#include "peers/reference_scene.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "gait/pd.h"
#include "physics/fnv1a.h"
#include "sim/scene_layout.h"

namespace gaitlab::peers {

namespace {

// The holding gains (N·m/rad, N·m·s/rad), pinned: the joint gains the shipped presets held a
// stance with when the peer benchmark was first measured (the biped's preset tuned at 1.4 m/s,
// the quadruped's trot). They are constants of the benchmark, not read from the presets, so that
// retuning a gait neither moves the comparison nor loosens the pose the engines hold. Both hold
// the pose as explicit torques at 120 Hz with the morphology's armature, but for one change: the
// biped's knee damping, 15.06 in that preset, is halved. Applied once per 1/120 s step on Bullet's
// hinge, a knee damping above about 13 N·m·s/rad (12.5 holds, 14 does not) makes the knee
// oscillate with growing amplitude from about 0.2 s, and the biped fell within 1 s, inside the
// timed window, while Jolt's implicit motors held it (docs/peers.md, "The reference scene's
// bipeds"). At 7.5 the biped stands as still as with 5 or 10 through the window.
struct HoldingGains {
  Motor hip, knee, ankle, spine;
};
constexpr HoldingGains kBipedHolding{{704.2, 15.67}, {255.9, 7.5}, {203.5, 3.888}, {0, 0}};
// The quadruped's paws are free in stance (its stance ankle gain is 0): the foot is held with the
// swing ankle's gains.
constexpr HoldingGains kQuadrupedHolding{{52.85, 4.178}, {37.55, 5.0}, {3.681, 0.08353}, {629.8, 1.444}};

}  // namespace

std::vector<Motor> holdingMotors(gait::Character character) {
  const body::Morphology m = character == gait::Character::Biped ? body::makeBiped() : body::makeQuadruped();
  const HoldingGains& g = character == gait::Character::Biped ? kBipedHolding : kQuadrupedHolding;
  std::vector<Motor> motors(m.segments.size());
  for (const body::Leg& leg : m.legs) {
    motors[leg.upper] = g.hip;
    motors[leg.lower] = g.knee;
    motors[leg.foot] = g.ankle;
  }
  for (int s : m.spine)
    if (m.segments[s].parent >= 0) motors[s] = g.spine;
  for (int s : m.legFrames)
    if (m.segments[s].parent >= 0) motors[s] = g.spine;
  return motors;
}

ReferenceScene::ReferenceScene(gait::Character character, int characters, int threads, int shards,
                               double spacing)
    : morphology_(character == gait::Character::Biped ? body::makeBiped() : body::makeQuadruped()),
      pool_(threads < 1 ? 1 : threads) {
  const int worlds = shards > 0 ? shards : pool_.size();
  motors_ = holdingMotors(character);
  const int pool = worlds == 1 ? physics::World::kDefaultContactPool
                               : std::max(256, physics::World::kDefaultContactPool / worlds);
  for (int w = 0; w < worlds; ++w) worlds_.push_back(std::make_unique<physics::World>(pool));
  byWorld_.resize(worlds);
  for (int i = 0; i < characters; ++i) {
    // Contiguous chunks of the grid per world, as the crowd benchmark's shards (thesis §4.3).
    int w = 0;
    while (w + 1 < worlds && i >= sim::ThreadPool::chunk(characters, worlds, w).end) ++w;
    const sim::Place p = sim::benchmarkPlace(i, characters, spacing);
    ragdolls_.push_back({std::make_unique<physics::Character>(*worlds_[w], morphology_,
                                                              Eigen::Vector3d(p.x, 0, p.z), p.heading),
                         w});
    byWorld_[w].push_back(i);
  }
  for (auto& world : worlds_) world->reserve();
}

ReferenceScene::~ReferenceScene() {
  ragdolls_.clear();  // constraints and bodies leave the worlds before they are destroyed
}

void ReferenceScene::holdPose(const Ragdoll& r, std::vector<gait::BodyState>* state,
                              std::vector<Eigen::Vector3d>* torques) const {
  r.body->readState(state->data());
  const int n = static_cast<int>(morphology_.segments.size());
  for (int s = 0; s < n; ++s) {
    const int parent = morphology_.segments[s].parent;
    if (parent < 0) {
      (*torques)[s].setZero();
      continue;
    }
    // The rest pose has every segment unrotated (body/morphology.h): the target of each joint is
    // the identity relative rotation.
    const gait::BodyState& a = (*state)[parent];
    const gait::BodyState& b = (*state)[s];
    (*torques)[s] = gait::jointPd(motors_[s].kp, motors_[s].kd, a.orientation, b.orientation,
                                  Eigen::Quaterniond::Identity(), a.angularVelocity, b.angularVelocity);
  }
  r.body->applyJointTorques(torques->data());
}

void ReferenceScene::step(int steps) {
  for (int k = 0; k < steps; ++k) {
    // One world per thread; its characters' motors, then its sub-steps, all on that thread.
    pool_.forEach(static_cast<int>(worlds_.size()), [&](int w) {
      std::vector<gait::BodyState> state(morphology_.segments.size());
      std::vector<Eigen::Vector3d> torques(morphology_.segments.size());
      for (int i : byWorld_[w]) holdPose(ragdolls_[i], &state, &torques);
      worlds_[w]->step();
    });
  }
}

double ReferenceScene::meanRootHeight() const {
  if (ragdolls_.empty()) return 0;
  double sum = 0;
  for (const Ragdoll& r : ragdolls_) sum += r.body->segmentState(morphology_.legFrames[0]).position.y();
  return sum / ragdolls_.size();
}

double ReferenceScene::largestPoseError() const {
  double largest = 0;
  for (const Ragdoll& r : ragdolls_) {
    for (int s = 0; s < r.body->segmentCount(); ++s) {
      const int parent = morphology_.segments[s].parent;
      if (parent < 0) continue;
      const Eigen::Quaterniond a = r.body->segmentState(parent).orientation, b = r.body->segmentState(s).orientation;
      largest = std::max(largest, gait::rotationVector(a.conjugate() * b).norm());
    }
  }
  return largest;
}

uint64_t ReferenceScene::hash() const {
  Fnv1a h;
  for (const Ragdoll& r : ragdolls_) {
    for (int s = 0; s < r.body->segmentCount(); ++s) {
      const btRigidBody* b = r.body->body(s);
      const btTransform& t = b->getCenterOfMassTransform();
      const btQuaternion q = t.getRotation();
      const btScalar v[] = {t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z(), q.x(), q.y(), q.z(), q.w(),
                            b->getLinearVelocity().x(), b->getLinearVelocity().y(), b->getLinearVelocity().z(),
                            b->getAngularVelocity().x(), b->getAngularVelocity().y(), b->getAngularVelocity().z()};
      h.bytes(v, sizeof(v));
    }
  }
  return h.h;
}

}  // namespace gaitlab::peers
