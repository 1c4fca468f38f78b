// For the physics paths that compute bit for bit what Bullet's own code computes, faster (the
// constraint sweep, physics/solver.h; the joint row setup, physics/joint_rows.h): a scene is
// stepped three times, with Bullet's path throughout, with the fast one throughout, and with the
// two alternating every step, and the three must end in the same state hash. The scenes are what
// the crowd meets: walking bipeds (hinge knees, 6-DOF hips and ankles), quadrupeds falling and
// lying with many contacts and their joints at their limits (the rows that exist only near a
// limit, physics/joint.h), props landing on characters (islands of several bodies), and several
// physics shards.
#pragma once
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "sim/simulation.h"

namespace gaitlab::test {

struct SameAsBulletRun {
  std::string hash;
  long batches = 0, fast = 0;  // solver batches, and how many the fast sweep solved
};

// `setFast(sim, on)` throws the switch under test. `fast`: 0 Bullet's path throughout, 1 the fast
// one throughout, 2 alternating every step.
template <typename Switch, typename Scene>
SameAsBulletRun runScene(int shards, int steps, int fast, Switch setFast, Scene scene) {
  sim::Simulation sim(1, 5, shards);
  scene(sim);
  for (int s = 0; s < steps; ++s) {
    setFast(sim, fast == 1 || (fast == 2 && s % 2 == 0));
    sim.step(1);
  }
  const auto b = sim.solverBatches();
  return {sim.stateHash(), b.first, b.second};
}

// The three runs; returns Bullet's and the fast one's, for the caller's own checks.
struct SameAsBulletRuns {
  SameAsBulletRun bullet, fast;
};
template <typename Switch, typename Scene>
SameAsBulletRuns expectSameAsBullet(const char* what, int shards, int steps, Switch setFast, Scene scene) {
  const SameAsBulletRun bullet = runScene(shards, steps, 0, setFast, scene);
  const SameAsBulletRun fast = runScene(shards, steps, 1, setFast, scene);
  const SameAsBulletRun mixed = runScene(shards, steps, 2, setFast, scene);
  EXPECT_EQ(fast.hash, bullet.hash) << what;
  EXPECT_EQ(mixed.hash, bullet.hash) << what << ", switched every step";
  return {bullet, fast};
}

// ---- the scenes ----
inline void walkingBipeds(sim::Simulation& sim) { sim.crowdScene(sim::Crowd::Bipeds, 6, 4.0); }

// Asked for `goal` m/s, far beyond any of their gaits, the quadrupeds fall and then lie with many
// contacts and joints at their limits.
inline auto fallingQuadrupeds(double goal) {
  return [goal](sim::Simulation& sim) {
    sim.crowdScene(sim::Crowd::Quadrupeds, 5, 4.0);
    sim.setGoal(-1, {goal, 0.0});
  };
}

inline void demoSceneWithProps(sim::Simulation& sim) { sim.demoScene(6); }

// Boxes dropped and thrown into characters: a character shares an island with them while they
// touch. Run with 3 shards.
inline void mixedCrowdWithThrownBoxes(sim::Simulation& sim) {
  sim.crowdScene(sim::Crowd::Mixed, 7, 2.5);
  sim.spawnBox(1.0, 0.5, 0.3);
  sim.throwBox(Eigen::Vector3d(-3, 1.2, 0), Eigen::Vector3d(8, 0, 0), 0.12);
  sim.throwBox(Eigen::Vector3d(0, 1.0, -3), Eigen::Vector3d(0, 0, 9), 0.15);
}

}  // namespace gaitlab::test
