// The biped's body flexes its hips 2 rad, as a person's do; its gaits, all searched on a hip that
// stopped at 0.7 rad, keep that stop as the gait's (gait::GaitParams::hipForwardStop), which the
// simulation sets on the body's hips as a joint limit (sim::Agent,
// physics::Character::setHipForwardStop; docs/controller-notes.md §76, §78). Walking with the
// preset, no thigh swings past it; the same gait without it swings them further.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gait/defaults.h"
#include "sim/simulation.h"
#include "sim/walk_trial.h"

namespace {

using namespace gaitlab;

// The furthest any thigh swung forwards of the torso's down axis (rad) over `seconds` at `speed`.
double furthestForward(const gait::Gait& gait, double speed, double seconds) {
  sim::WalkOptions o;
  o.character = gait::Character::Biped;
  o.gait = &gait;
  o.speed = speed;
  sim::Simulation sim(1, o.seed);
  sim::setUpWalk(sim, o);
  const body::Morphology& m = sim.character(0).morphology();
  double furthest = 0;
  for (int k = 0; k < static_cast<int>(std::lround(seconds / physics::kFixedStep)); ++k) {
    sim.step(1);
    for (const body::Leg& leg : m.legs) {
      const Eigen::Quaterniond torso = sim.character(0).segmentState(leg.legFrame).orientation;
      const Eigen::Quaterniond thigh = sim.character(0).segmentState(leg.upper).orientation;
      const Eigen::Vector3d down = torso.conjugate() * (thigh * -Eigen::Vector3d::UnitY());
      furthest = std::max(furthest, std::atan2(down.z(), -down.y()));
    }
  }
  return furthest;
}

}  // namespace

TEST(HipStop, TheBipedsThighsSwingForwardsAsFarAsTheirGaitsStop) {
  const gait::Gait& preset = gait::defaultGait(gait::Character::Biped);
  for (const gait::SpeedKey& key : preset.keys) ASSERT_EQ(key.params.hipForwardStop, 0.7);
  gait::Gait free = preset;
  for (gait::SpeedKey& key : free.keys) key.params.hipForwardStop = gait::kNoHipForwardStop;
  for (double speed : {0.5, 1.0}) {
    SCOPED_TRACE(speed);
    const double held = furthestForward(preset, speed, 10), unheld = furthestForward(free, speed, 10);
    EXPECT_LT(held, 0.8) << held;  // 0.7, and what the limit row lets through within a step
    EXPECT_GT(unheld, 0.9) << unheld;
  }
}
