// The fast constraint sweep (physics/solver.h) computes bit for bit what Bullet's own sweep
// computes: the same scenes, stepped once with each, end in the same state hash. The scenes are
// chosen so that the fast sweep really runs (it falls back to Bullet's for what it does not
// reproduce) and meets what the crowd meets: walking bipeds, quadrupeds falling and lying on the
// ground with many contacts, props landing on characters (islands of several bodies), one and
// several physics shards, and the switch thrown in the middle of a run.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "sim/simulation.h"

using gaitlab::sim::Crowd;
using gaitlab::gait::Character;
using gaitlab::sim::Mode;
using gaitlab::sim::Simulation;

namespace {

struct Run {
  std::string hash;
  long batches = 0, fast = 0;
};

// `fast`: 0 Bullet's sweep throughout, 1 the fast sweep throughout, 2 alternating every step.
template <typename Scene>
Run run(int shards, int steps, int fast, Scene scene) {
  Simulation sim(1, 5, shards);
  scene(sim);
  for (int s = 0; s < steps; ++s) {
    sim.setFastSolver(fast == 1 || (fast == 2 && s % 2 == 0));
    sim.step(1);
  }
  const auto b = sim.solverBatches();
  return {sim.stateHash(), b.first, b.second};
}

template <typename Scene>
void expectSameAsBullet(const char* what, int shards, int steps, Scene scene) {
  const Run bullet = run(shards, steps, 0, scene);
  const Run fast = run(shards, steps, 1, scene);
  const Run mixed = run(shards, steps, 2, scene);
  EXPECT_EQ(bullet.fast, 0) << what;
  EXPECT_GT(bullet.batches, 0) << what;
  // Every batch took the fast sweep: nothing here needs Bullet's.
  EXPECT_EQ(fast.fast, fast.batches) << what;
  EXPECT_EQ(fast.hash, bullet.hash) << what;
  EXPECT_EQ(mixed.hash, bullet.hash) << what << ", switched every step";
}

}  // namespace

TEST(FastSolver, WalkingBipedsAsBullet) {
  expectSameAsBullet("bipeds", 1, 480, [](Simulation& sim) { sim.crowdScene(Crowd::Bipeds, 6, 4.0); });
}

TEST(FastSolver, FallingAndLyingQuadrupedsAsBullet) {
  // Asked for 3 m/s, far beyond their gait, the quadrupeds fall within 3 s and then lie with
  // many contacts (all 5 do: checked when this was written).
  expectSameAsBullet("quadrupeds", 1, 360, [](Simulation& sim) {
    sim.crowdScene(Crowd::Quadrupeds, 5, 4.0);
    sim.setGoal(-1, {3.0, 0.0});
  });
}

TEST(FastSolver, PropsOnCharactersAndSeveralShardsAsBullet) {
  expectSameAsBullet("demo scene, props", 1, 300, [](Simulation& sim) { sim.demoScene(6); });
  expectSameAsBullet("mixed crowd, thrown boxes, 3 shards", 3, 240, [](Simulation& sim) {
    sim.crowdScene(Crowd::Mixed, 7, 2.5);
    sim.spawnBox(1.0, 0.5, 0.3);
    // Boxes thrown into a character: it shares an island with them while they touch.
    sim.throwBox(Eigen::Vector3d(-3, 1.2, 0), Eigen::Vector3d(8, 0, 0), 0.12);
    sim.throwBox(Eigen::Vector3d(0, 1.0, -3), Eigen::Vector3d(0, 0, 9), 0.15);
  });
}

TEST(FastSolver, SameInEveryMode) {
  std::string reference;
  for (Mode mode : {Mode::Serial, Mode::Full}) {
    for (bool fast : {false, true}) {
      Simulation sim(2, 9, 3);
      sim.crowdScene(Crowd::Mixed, 7, 2.5);
      sim.setMode(mode);
      sim.setFastSolver(fast);
      sim.step(120);
      if (reference.empty()) reference = sim.stateHash();
      EXPECT_EQ(sim.stateHash(), reference) << gaitlab::sim::modeName(mode) << (fast ? " fast" : " bullet");
    }
  }
}
