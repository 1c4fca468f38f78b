// The faster setup of the joints' rows (physics/joint_rows.h) computes bit for bit what Bullet's
// own convertJoints computes: the scenes of same_as_bullet.h end in the same state hash with
// either setup, and with the two alternating every step, in every mode and with either sweep.
#include <gtest/gtest.h>

#include <string>

#include "same_as_bullet.h"
#include "sim/simulation.h"

using gaitlab::sim::Crowd;
using gaitlab::sim::Mode;
using gaitlab::sim::Simulation;
namespace t = gaitlab::test;

namespace {
const auto fastRows = [](Simulation& sim, bool on) { sim.setFastJointRows(on); };
}  // namespace

TEST(FastJointRows, WalkingBipedsAsBullet) {
  t::expectSameAsBullet("bipeds", 1, 480, fastRows, t::walkingBipeds);
}

TEST(FastJointRows, FallingAndLyingQuadrupedsAsBullet) {
  t::expectSameAsBullet("quadrupeds", 1, 480, fastRows, t::fallingQuadrupeds(8.0));
}

TEST(FastJointRows, PropsOnCharactersAndSeveralShardsAsBullet) {
  t::expectSameAsBullet("demo scene, props", 1, 300, fastRows, t::demoSceneWithProps);
  t::expectSameAsBullet("mixed crowd, thrown boxes, 3 shards", 3, 240, fastRows, t::mixedCrowdWithThrownBoxes);
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
