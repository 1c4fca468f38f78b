// The faster setup of the joints' rows (physics/joint_rows.h) computes bit for bit what Bullet's
// own convertJoints computes: the same scenes, stepped with each, end in the same state hash. The
// scenes are what the crowd meets: walking bipeds (hinge knees, 6-DOF hips and ankles), quadrupeds
// falling and lying on the ground with joints pressed against their limits (the rows that exist
// only near a limit, physics/joint.h), props landing on characters, several physics shards, and
// the switch thrown in the middle of a run.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "sim/simulation.h"

using gaitlab::sim::Crowd;
using gaitlab::sim::Mode;
using gaitlab::sim::Simulation;

namespace {

// `fast`: 0 Bullet's setup throughout, 1 the fast one throughout, 2 alternating every step.
template <typename Scene>
std::string run(int shards, int steps, int fast, Scene scene) {
  Simulation sim(1, 5, shards);
  scene(sim);
  for (int s = 0; s < steps; ++s) {
    sim.setFastJointRows(fast == 1 || (fast == 2 && s % 2 == 0));
    sim.step(1);
  }
  return sim.stateHash();
}

template <typename Scene>
void expectSameAsBullet(const char* what, int shards, int steps, Scene scene) {
  const std::string bullet = run(shards, steps, 0, scene);
  EXPECT_EQ(run(shards, steps, 1, scene), bullet) << what;
  EXPECT_EQ(run(shards, steps, 2, scene), bullet) << what << ", switched every step";
}

}  // namespace

TEST(FastJointRows, WalkingBipedsAsBullet) {
  expectSameAsBullet("bipeds", 1, 480, [](Simulation& sim) { sim.crowdScene(Crowd::Bipeds, 6, 4.0); });
}

TEST(FastJointRows, FallingAndLyingQuadrupedsAsBullet) {
  // Asked for 8 m/s, far beyond any of their gaits, and pushed, the quadrupeds fall and then lie
  // with their joints at their limits and many contacts.
  expectSameAsBullet("quadrupeds", 1, 480, [](Simulation& sim) {
    sim.crowdScene(Crowd::Quadrupeds, 5, 4.0);
    sim.setGoal(-1, {8.0, 0.0});
  });
}

TEST(FastJointRows, PropsOnCharactersAndSeveralShardsAsBullet) {
  expectSameAsBullet("demo scene, props", 1, 300, [](Simulation& sim) { sim.demoScene(6); });
  expectSameAsBullet("mixed crowd, thrown boxes, 3 shards", 3, 240, [](Simulation& sim) {
    sim.crowdScene(Crowd::Mixed, 7, 2.5);
    sim.spawnBox(1.0, 0.5, 0.3);
    sim.throwBox(Eigen::Vector3d(-3, 1.2, 0), Eigen::Vector3d(8, 0, 0), 0.12);
    sim.throwBox(Eigen::Vector3d(0, 1.0, -3), Eigen::Vector3d(0, 0, 9), 0.15);
  });
}

TEST(FastJointRows, SameInEveryModeAndWithEitherSweep) {
  std::string reference;
  for (Mode mode : {Mode::Serial, Mode::Full}) {
    for (int variant = 0; variant < 4; ++variant) {
      Simulation sim(2, 9, 3);
      sim.crowdScene(Crowd::Mixed, 7, 2.5);
      sim.setMode(mode);
      sim.setFastJointRows(variant & 1);
      sim.setFastSolver(variant & 2);
      sim.step(120);
      if (reference.empty()) reference = sim.stateHash();
      EXPECT_EQ(sim.stateHash(), reference) << gaitlab::sim::modeName(mode) << " variant " << variant;
    }
  }
}
