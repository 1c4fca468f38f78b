// The fast constraint sweep (physics/solver.h) computes bit for bit what Bullet's own sweep
// computes: the same scenes, stepped once with each, end in the same state hash. The scenes are
// chosen so that the fast sweep really runs (it falls back to Bullet's for what it does not
// reproduce) and meets what the crowd meets: walking bipeds, quadrupeds falling and lying on the
// ground with many contacts, props landing on characters (islands of several bodies), one and
// several physics shards, and the switch thrown in the middle of a run.
#include <gtest/gtest.h>

#include <string>

#include "same_as_bullet.h"
#include "sim/simulation.h"

using gaitlab::sim::Crowd;
using gaitlab::sim::Mode;
using gaitlab::sim::Simulation;
namespace t = gaitlab::test;

namespace {

const auto fastSweep = [](Simulation& sim, bool on) { sim.setFastSolver(on); };

// The same state as Bullet's sweep, and every batch of the fast run took the fast sweep: nothing
// in these scenes needs Bullet's.
template <typename Scene>
void expectSameAsBullet(const char* what, int shards, int steps, Scene scene) {
  const t::SameAsBulletRuns runs = t::expectSameAsBullet(what, shards, steps, fastSweep, scene);
  EXPECT_EQ(runs.bullet.fast, 0) << what;
  EXPECT_GT(runs.bullet.batches, 0) << what;
  EXPECT_EQ(runs.fast.fast, runs.fast.batches) << what;
}

}  // namespace

TEST(FastSolver, WalkingBipedsAsBullet) { expectSameAsBullet("bipeds", 1, 480, t::walkingBipeds); }

TEST(FastSolver, FallingAndLyingQuadrupedsAsBullet) {
  expectSameAsBullet("quadrupeds", 1, 360, t::fallingQuadrupeds(3.0));
}

TEST(FastSolver, PropsOnCharactersAndSeveralShardsAsBullet) {
  expectSameAsBullet("demo scene, props", 1, 300, t::demoSceneWithProps);
  expectSameAsBullet("mixed crowd, thrown boxes, 3 shards", 3, 240, t::mixedCrowdWithThrownBoxes);
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
