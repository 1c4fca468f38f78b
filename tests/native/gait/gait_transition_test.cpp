// Gait transitions (gait/gait_transition.h): keys of different footfall patterns are not blended;
// the gait changes at the middle speed, and the gait phase moves so each leg's phase moves least.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "gait/defaults.h"
#include "gait/gait_transition.h"
#include "gait/speed_keys.h"

using namespace gaitlab::gait;

namespace {

// Step triggers front left, front right, back left, back right.
GaitParams quadruped(double fl, double fr, double bl, double br) {
  GaitParams p = defaultParams(Character::Quadruped);
  const double t[4] = {fl, fr, bl, br};
  for (int i = 0; i < 4; ++i) p.legs[i].stepTrigger = t[i];
  return p;
}
const GaitParams kTrot = quadruped(0.0, 0.5, 0.5, 0.0);
const GaitParams kWalk = quadruped(0.25, 0.75, 0.0, 0.5);  // lateral sequence: BL, FL, BR, FR

bool sameBits(const GaitParams& a, const GaitParams& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

}  // namespace

TEST(GaitTransition, WalkAndTrotDifferInFootfallButATrotTunedApartDoesNot) {
  EXPECT_TRUE(footfallDiffers(kWalk.legs, kTrot.legs, 4));
  EXPECT_TRUE(footfallDiffers(kTrot.legs, quadruped(0.0, 0.0, 0.5, 0.5).legs, 4));  // bound: the front pair, then the back
  // The shipped trot's keys differ by up to 0.1 of a cycle, and a whole pattern moved is the same.
  EXPECT_FALSE(footfallDiffers(kTrot.legs, quadruped(0.07, 0.55, 0.43, 0.1).legs, 4));
  EXPECT_FALSE(footfallDiffers(kTrot.legs, quadruped(0.3, 0.8, 0.8, 0.3).legs, 4));
  // Across the wrap: 0.95 and 0.02 are 0.07 apart.
  EXPECT_FALSE(footfallDiffers(kTrot.legs, quadruped(0.95, 0.45, 0.45, 0.02).legs, 4));
  // Only the legs the character has count.
  const GaitParams biped = defaultParams(Character::Biped);
  GaitParams other = biped;
  other.legs[2].stepTrigger = biped.legs[2].stepTrigger + 0.4;
  EXPECT_FALSE(footfallDiffers(biped.legs, other.legs, 2));
}

TEST(GaitTransition, ThePhaseShiftIsTheMeanTriggerMove) {
  // Every trigger moved by 0.3: the phase follows and no leg's ψ moves.
  EXPECT_NEAR(transitionPhaseShift(kTrot.legs, quadruped(0.3, 0.8, 0.8, 0.3).legs, 4), 0.3, 1e-12);
  // The short way round: moves of −0.1 (0.05 → 0.95) average to −0.1, not 0.9.
  EXPECT_NEAR(transitionPhaseShift(quadruped(0.05, 0.55, 0.55, 0.05).legs,
                                   quadruped(0.95, 0.45, 0.45, 0.95).legs, 4), -0.1, 1e-12);
  // Walk to trot: moves −0.25, −0.25, +0.5 and −0.5 (half a cycle either way is one move):
  // the mean is −0.375, and every leg's ψ moves by an eighth of a cycle, none by more.
  const double shift = transitionPhaseShift(kWalk.legs, kTrot.legs, 4);
  EXPECT_NEAR(shift, -0.375, 1e-12);
  for (int i = 0; i < 4; ++i)
    EXPECT_NEAR(std::abs(std::remainder(shift - (kTrot.legs[i].stepTrigger - kWalk.legs[i].stepTrigger), 1.0)), 0.125, 1e-12) << i;
}

// Between a walk key and a trot key nothing is blended: the lower key's parameters below the
// middle speed, the upper's from it. Between keys of one pattern the blend is linear, as before.
TEST(GaitTransition, KeysOfDifferentFootfallAreNotBlended) {
  Gait g = Gait::single(kWalk, 0.2);
  GaitParams trot = kTrot;
  trot.period = 0.45;
  g.keys.push_back({0.6, trot});
  GaitParams p;
  for (double s : {0.0, 0.2, 0.3, 0.399}) {
    paramsAtSpeed(Character::Quadruped, g, s, &p);
    EXPECT_TRUE(sameBits(p, kWalk)) << s;
  }
  for (double s : {0.4, 0.5, 0.6, 2.0}) {
    paramsAtSpeed(Character::Quadruped, g, s, &p);
    EXPECT_TRUE(sameBits(p, trot)) << s;
  }
  GaitParams fastTrot = kTrot;
  fastTrot.period = 0.65;
  g.keys[0].params = fastTrot;
  paramsAtSpeed(Character::Quadruped, g, 0.3, &p);
  EXPECT_NEAR(p.period, 0.6, 1e-12);
}

// Where a change of gait is taken up (GaitParams::transitionPhase): the step in which the gait
// phase reaches it, the wrap at 1 for 0 (the cycle's start), and not again until the phase comes
// round.
TEST(GaitTransition, APhaseIsReachedInTheStepThatPassesIt) {
  EXPECT_TRUE(phaseReached(0.44, 0.46, 0.45));
  EXPECT_TRUE(phaseReached(0.44, 0.45, 0.45));
  EXPECT_FALSE(phaseReached(0.45, 0.46, 0.45));  // passed in the step before
  EXPECT_FALSE(phaseReached(0.40, 0.44, 0.45));
  EXPECT_TRUE(phaseReached(0.99, 0.01, 0.0));    // the cycle's start: the wrap
  EXPECT_TRUE(phaseReached(0.99, 0.01, 1.0));    // 1 is the cycle's start too
  EXPECT_FALSE(phaseReached(0.5, 0.6, 1.0));
  EXPECT_FALSE(phaseReached(0.0, 0.02, 0.0));
  EXPECT_FALSE(phaseReached(0.5, 0.5, 0.0));     // a phase held (standing) reaches nothing
  EXPECT_TRUE(phaseReached(0.98, 0.02, 0.99));   // across the wrap
  EXPECT_TRUE(phaseReached(0.98, 0.02, 0.01));
  EXPECT_FALSE(phaseReached(0.98, 0.02, 0.5));
}
