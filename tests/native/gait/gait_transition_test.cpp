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
// Lateral sequence: BL, FL, BR, FR, every foot down 0.6 of the cycle (a walk: more than half).
GaitParams walk(double fl, double fr, double bl, double br) {
  GaitParams p = quadruped(fl, fr, bl, br);
  for (int i = 0; i < 4; ++i) p.legs[i].dutyFactor = 0.6;
  return p;
}
const GaitParams kWalk = walk(0.25, 0.75, 0.0, 0.5);

// The same schedules with left and right legs swapped (front left ↔ front right, back left ↔
// back right): the gait's mirror image.
GaitParams mirrored(const GaitParams& p) {
  GaitParams m = p;
  for (int i = 0; i < 4; ++i) m.legs[i] = p.legs[i ^ 1];
  return m;
}

bool sameBits(const GaitParams& a, const GaitParams& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

}  // namespace

TEST(GaitTransition, WalkAndTrotDifferInFootfallButATrotTunedApartDoesNot) {
  EXPECT_TRUE(footfallDiffers(kWalk.legs, kTrot.legs, 4));
  EXPECT_TRUE(footfallDiffers(kTrot.legs, quadruped(0.0, 0.0, 0.5, 0.5).legs, 4));  // bound: the front pair, then the back
  // The shipped trot's keys differ by up to 0.12 of a cycle, and a whole pattern moved is the same.
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

// A walk and a trot: an eighth of a cycle apart at the best shift (each diagonal pair's feet moved
// by an eighth towards each other), and different gaits by the walk's longer stance.
TEST(GaitTransition, AWalkDiffersFromATrotByItsStanceAsWellAsItsTriggers) {
  EXPECT_NEAR(footfallDistance(kWalk.legs, kTrot.legs, 4), 0.125, 1e-12);
  EXPECT_TRUE(footfallDiffers(kWalk.legs, kTrot.legs, 4));
  // The walk's triggers with the trot's stance: a trot whose pairs lift apart, not another gait.
  GaitParams splitTrot = kWalk;
  for (int i = 0; i < 4; ++i) splitTrot.legs[i].dutyFactor = kTrot.legs[i].dutyFactor;
  EXPECT_FALSE(footfallDiffers(splitTrot.legs, kTrot.legs, 4));
  // A walk's own keys, tuned apart, are one gait.
  EXPECT_FALSE(footfallDiffers(kWalk.legs, walk(0.3, 0.8, 0.02, 0.55).legs, 4));
  // One pair of legs: a walk and a run keep their pattern and blend.
  GaitParams biped = defaultParams(Character::Biped);
  GaitParams run = biped;
  for (int i = 0; i < 2; ++i) biped.legs[i].dutyFactor = 0.6, run.legs[i].dutyFactor = 0.35;
  EXPECT_FALSE(footfallDiffers(biped.legs, run.legs, 2));
}

TEST(GaitTransition, FootfallDistanceIsTheFarthestLegAtTheBestShift) {
  // A whole pattern moved, across the cycle's start too, is the same pattern.
  EXPECT_NEAR(footfallDistance(kTrot.legs, quadruped(0.9, 0.4, 0.4, 0.9).legs, 4), 0.0, 1e-12);
  // Moves of 0.07, 0.05, −0.07 and 0.1: the best shift is 0.015, and the farthest legs 0.085 off.
  EXPECT_NEAR(footfallDistance(kTrot.legs, quadruped(0.07, 0.55, 0.43, 0.1).legs, 4), 0.085, 1e-12);
  // A bound and a pace are a quarter of a cycle from the trot.
  EXPECT_NEAR(footfallDistance(kTrot.legs, quadruped(0.0, 0.0, 0.5, 0.5).legs, 4), 0.25, 1e-12);
  EXPECT_NEAR(footfallDistance(kTrot.legs, quadruped(0.0, 0.5, 0.0, 0.5).legs, 4), 0.25, 1e-12);
  // Any order of the legs gives the same distance.
  const GaitParams a = quadruped(0.1, 0.62, 0.47, 0.05), b = quadruped(0.33, 0.9, 0.02, 0.4);
  const int orders[3][4] = {{1, 0, 3, 2}, {3, 2, 1, 0}, {2, 3, 0, 1}};
  for (const auto& order : orders) {
    GaitParams pa = a, pb = b;
    for (int i = 0; i < 4; ++i) pa.legs[i] = a.legs[order[i]], pb.legs[i] = b.legs[order[i]];
    EXPECT_DOUBLE_EQ(footfallDistance(pa.legs, pb.legs, 4), footfallDistance(a.legs, b.legs, 4));
  }
}

// The shipped quadruped's keys and their mirror image change footfall pattern between the same
// neighbours: its walk keys and the trot, and the trot and the canter; judged from the first leg,
// the mirror image had blended its walk into its trot and changed pattern inside the trot.
TEST(GaitTransition, AGaitAndItsMirrorImageChangePatternBetweenTheSameKeys) {
  const Gait& g = defaultGait(Character::Quadruped);
  int changes = 0;
  for (size_t k = 1; k < g.keys.size(); ++k) {
    const GaitParams& a = g.keys[k - 1].params;
    const GaitParams& b = g.keys[k].params;
    const bool differs = footfallDiffers(a.legs, b.legs, 4);
    EXPECT_EQ(differs, footfallDiffers(mirrored(a).legs, mirrored(b).legs, 4)) << g.keys[k].speed;
    changes += differs;
  }
  EXPECT_EQ(changes, 3);  // walk keys ↔ trot twice, trot ↔ canter once
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
