// Gait player (thesis §3.1.1): phase wrapping, duty factors, early and late foot strikes.
// The schedule the tests compare with is computed here from the definitions (lift-off at the
// step trigger, stance for the last D of the leg's cycle), with time counted in whole steps.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gait/gait_player.h"

namespace gaitlab::gait {
namespace {

// Is the leg in stance at time t by the schedule alone? (Lift-off at Φ = trigger, swing for
// (1 − D)·T, then stance for D·T.)
bool scheduledStanceAt(double t, double period, double trigger, double duty) {
  double psi = std::fmod(t / period - trigger, 1.0);
  if (psi < 0) psi += 1.0;
  return psi >= 1.0 - duty;
}

TEST(GaitPlayer, PhaseAdvancesByDtOverPeriodAndWraps) {
  GaitPlayer g;
  const LegSchedule legs[2] = {{0.0, 0.6}, {0.5, 0.6}};
  g.configure(2, legs, 1.6);
  const double dt = 1.0 / 120.0;
  double expected = 0.0;
  for (int step = 1; step <= 1000; ++step) {
    g.update(dt, nullptr);
    expected += dt / 1.6;
    expected -= std::floor(expected);
    ASSERT_GE(g.phase(), 0.0);
    ASSERT_LT(g.phase(), 1.0);
    const double diff = std::fabs(g.phase() - expected);
    EXPECT_LT(std::fmin(diff, 1.0 - diff), 1e-9) << "step " << step;
  }
  // A coarse step wraps too.
  g.reset(0.9);
  g.update(0.32, nullptr);  // + 0.2
  EXPECT_NEAR(g.phase(), 0.1, 1e-12);
}

TEST(GaitPlayer, StanceFractionEqualsDutyFactor) {
  // dt = T/1024 keeps the gait phase exact in binary, so the test's own schedule and the
  // player's agree to the step and the feet land exactly on time.
  const double period = 1.0, dt = 1.0 / 1024.0;
  const double triggers[] = {0.0, 0.25, 0.5, 0.9};
  const double duties[] = {0.3, 0.5, 0.62, 0.8};
  for (double trig : triggers) {
    for (double duty : duties) {
      GaitPlayer g;
      const LegSchedule leg{trig, duty};
      g.configure(1, &leg, period);
      const int cycles = 5;
      const int steps = cycles * 1024;
      int stanceSteps = 0, mismatches = 0;
      for (int s = 1; s <= steps; ++s) {
        // The foot is down exactly when the schedule says so (an ideal terrain).
        const bool contact = scheduledStanceAt((s % 1024) * dt, period, trig, duty);
        g.update(dt, &contact);
        stanceSteps += g.leg(0).stance ? 1 : 0;
        mismatches += g.leg(0).stance != contact ? 1 : 0;
        EXPECT_GE(g.leg(0).progress, 0.0);
        EXPECT_LE(g.leg(0).progress, 1.0);
      }
      EXPECT_EQ(mismatches, 0) << trig << " " << duty;
      // Whole steps: the fraction is D to within one step per cycle.
      EXPECT_NEAR(static_cast<double>(stanceSteps) / steps, duty, 1.0 / 1024.0)
          << trig << " " << duty;
      EXPECT_NEAR(g.measuredDutyFactor(0), duty, 1.0 / 1024.0);
      // One lift-off per cycle at the trigger, plus the start-up one if the leg starts in swing.
      const bool startsInSwing = GaitPlayer::legPhase(0.0, trig) < 1.0 - duty;
      EXPECT_EQ(g.leg(0).liftOffs, cycles + (startsInSwing ? 1 : 0));
      EXPECT_EQ(g.leg(0).touchDowns, cycles);
      EXPECT_EQ(g.leg(0).earlyStrikes, 0);
      EXPECT_EQ(g.leg(0).lateStrikes, 0);
    }
  }
}

TEST(GaitPlayer, LegsStartingInSwingReportTheirLiftOffOnTheFirstUpdate) {
  // Biped at Φ = 0 (the original implementation's step triggers): the left leg's lift-off is now, the right stands.
  GaitPlayer g;
  const LegSchedule legs[2] = {{0.0, 0.62}, {0.5, 0.62}};
  g.configure(2, legs, 2.0);
  EXPECT_FALSE(g.leg(0).stance);
  EXPECT_TRUE(g.leg(1).stance);
  const bool down[2] = {true, true};
  g.update(1.0 / 120.0, down);
  EXPECT_TRUE(g.leg(0).events & kLiftOff);
  EXPECT_EQ(g.leg(0).liftOffs, 1);
  EXPECT_EQ(g.leg(1).events, 0u);
  g.update(1.0 / 120.0, down);
  EXPECT_EQ(g.leg(0).events, 0u);  // reported once
  EXPECT_EQ(g.leg(0).liftOffs, 1);
}

TEST(GaitPlayer, SwingProgressIsLegPhaseOverSwingDuration) {
  GaitPlayer g;
  const LegSchedule leg{0.2, 0.6};
  g.configure(1, &leg, 1.0, 0.2);  // at the lift-off phase
  EXPECT_FALSE(g.leg(0).stance);
  EXPECT_NEAR(g.leg(0).progress, 0.0, 1e-12);
  g.update(0.1, nullptr);  // ψ = 0.1 of a 0.4 swing
  EXPECT_FALSE(g.leg(0).stance);
  EXPECT_NEAR(g.leg(0).progress, 0.25, 1e-12);
  EXPECT_NEAR(g.leg(0).legPhase, 0.1, 1e-12);
  const bool down = true;
  g.update(0.4, &down);  // ψ = 0.5: scheduled stance, foot down, stance progress 0.1/0.6
  EXPECT_TRUE(g.leg(0).stance);
  EXPECT_NEAR(g.leg(0).progress, 0.1 / 0.6, 1e-12);
  EXPECT_TRUE(g.leg(0).events & kTouchDown);
}

TEST(GaitPlayer, EarlyStrikeOnlyAfterEightyPercentOfSwing) {
  GaitPlayer g;
  const LegSchedule leg{0.0, 0.5};  // swing ψ ∈ [0, 0.5)
  const double dt = 0.001;           // T = 1: ϕ advances 0.002 per step
  g.configure(1, &leg, 1.0, 0.0);
  const bool down = true, up = false;
  // The foot is on the ground through the whole swing.
  bool switched = false;
  double switchProgress = -1.0;
  for (int s = 1; s < 500 && !switched; ++s) {
    g.update(dt, &down);
    const double swingProgress = g.leg(0).legPhase / 0.5;
    if (g.leg(0).stance) {
      switched = true;
      switchProgress = swingProgress;
      EXPECT_TRUE(g.leg(0).events & kTouchDown);
      EXPECT_TRUE(g.leg(0).events & kEarlyStrike);
      EXPECT_TRUE(g.leg(0).early);
      EXPECT_FALSE(g.leg(0).scheduledStance);
    } else {
      EXPECT_LE(swingProgress, 0.8 + 1e-9);  // contact ignored up to ϕ = 0.8
    }
  }
  ASSERT_TRUE(switched);
  EXPECT_GT(switchProgress, 0.8);
  EXPECT_LT(switchProgress, 0.8 + 0.0021);
  EXPECT_EQ(g.leg(0).earlyStrikes, 1);
  // It stays in stance, foot up or down, until its next scheduled lift-off.
  for (int s = 0; s < 2000; ++s) {
    g.update(dt, (s % 2) ? &up : &down);
    if (g.leg(0).events & kLiftOff) break;
    ASSERT_TRUE(g.leg(0).stance) << "psi " << g.leg(0).legPhase;
  }
  EXPECT_TRUE(g.leg(0).events & kLiftOff);
  EXPECT_FALSE(g.leg(0).stance);
  EXPECT_FALSE(g.leg(0).early);
}

TEST(GaitPlayer, ContactEarlyInSwingDoesNotEndIt) {
  GaitPlayer g;
  const LegSchedule leg{0.0, 0.5};
  g.configure(1, &leg, 1.0, 0.0);
  const bool down = true, up = false;
  g.update(0.3, &down);  // ϕ = 0.6
  EXPECT_FALSE(g.leg(0).stance);
  g.update(0.09, &down);  // ϕ = 0.78
  EXPECT_FALSE(g.leg(0).stance);
  g.update(0.02, &up);  // ϕ = 0.82, no contact
  EXPECT_FALSE(g.leg(0).stance);
  g.update(0.001, &down);  // ϕ = 0.822, contact
  EXPECT_TRUE(g.leg(0).stance);
  EXPECT_TRUE(g.leg(0).events & kEarlyStrike);
}

TEST(GaitPlayer, LateStrikeOffsetGrowsBoundedThenResetsOnContact) {
  GaitPlayer g;
  const LegSchedule leg{0.0, 0.5};
  g.configure(1, &leg, 1.0, 0.0);
  LateStrikeParams late;
  late.rate = 0.5;
  late.maxOffset = 0.04;
  g.setLateStrike(late);
  const bool up = false, down = true;
  const double dt = 1.0 / 128.0;  // exact in binary: ψ = steps/128 exactly
  for (int s = 0; s < 63; ++s) g.update(dt, &up);  // ψ = 63/128: still swing
  EXPECT_FALSE(g.leg(0).stance);
  EXPECT_EQ(g.leg(0).lateStrikeOffset, 0.0);
  g.update(dt, &up);  // ψ = 0.5: scheduled stance, foot in the air → late
  EXPECT_FALSE(g.leg(0).stance);
  EXPECT_TRUE(g.leg(0).late);
  EXPECT_TRUE(g.leg(0).events & kLateStrike);
  EXPECT_DOUBLE_EQ(g.leg(0).progress, 1.0);  // holds the end of the swing trajectory
  EXPECT_NEAR(g.leg(0).lateStrikeOffset, late.rate * dt, 1e-15);
  double prev = g.leg(0).lateStrikeOffset;
  for (int s = 0; s < 20; ++s) {
    g.update(dt, &up);
    EXPECT_FALSE(g.leg(0).stance);
    EXPECT_GE(g.leg(0).lateStrikeOffset, prev);
    EXPECT_LE(g.leg(0).lateStrikeOffset, late.maxOffset);
    if (s < 8) {
      EXPECT_NEAR(g.leg(0).lateStrikeOffset - prev, late.rate * dt, 1e-15);
    }
    EXPECT_FALSE(g.leg(0).events & kLateStrike);  // one late strike, reported once
    prev = g.leg(0).lateStrikeOffset;
  }
  EXPECT_DOUBLE_EQ(g.leg(0).lateStrikeOffset, late.maxOffset);  // 21 × 3.9 mm, bounded at 4 cm
  g.update(dt, &down);  // touch-down
  EXPECT_TRUE(g.leg(0).stance);
  EXPECT_FALSE(g.leg(0).late);
  EXPECT_EQ(g.leg(0).lateStrikeOffset, 0.0);
  EXPECT_TRUE(g.leg(0).events & kTouchDown);
  EXPECT_EQ(g.leg(0).lateStrikes, 1);
  EXPECT_EQ(g.leg(0).touchDowns, 1);
}

TEST(GaitPlayer, AFootThatNeverLandsStartsTheNextSwingAtItsTrigger) {
  GaitPlayer g;
  const LegSchedule leg{0.0, 0.5};
  g.configure(1, &leg, 1.0, 0.0);
  const bool up = false;
  const double dt = 1.0 / 128.0;
  for (int s = 0; s < 127; ++s) g.update(dt, &up);
  EXPECT_TRUE(g.leg(0).late);
  EXPECT_GT(g.leg(0).lateStrikeOffset, 0.0);
  g.update(dt, &up);  // Φ wraps to 0: the trigger
  EXPECT_TRUE(g.leg(0).events & kLiftOff);
  EXPECT_FALSE(g.leg(0).late);
  EXPECT_EQ(g.leg(0).lateStrikeOffset, 0.0);
  EXPECT_NEAR(g.leg(0).progress, 0.0, 1e-12);
}

TEST(GaitPlayer, BipedTriggersAlternate) {
  // The original implementation's biped: L 0 / R 0.5, D = 0.62: both feet down around each switch.
  GaitPlayer g;
  const LegSchedule legs[2] = {{0.0, 0.62}, {0.5, 0.62}};
  g.configure(2, legs, 2.0);
  const double dt = 1.0 / 120.0;
  int doubleSupport = 0, flight = 0;
  const int steps = 240 * 3;
  for (int s = 1; s <= steps; ++s) {
    bool c[2] = {scheduledStanceAt(s * dt, 2.0, 0.0, 0.62),
                 scheduledStanceAt(s * dt, 2.0, 0.5, 0.62)};
    g.update(dt, c);
    doubleSupport += g.leg(0).stance && g.leg(1).stance;
    flight += !g.leg(0).stance && !g.leg(1).stance;
  }
  EXPECT_EQ(flight, 0);
  // Double support: |A ∩ B| = D + D − 1 = 0.24 of the cycle.
  EXPECT_NEAR(static_cast<double>(doubleSupport) / steps, 0.24, 0.01);
}

TEST(GaitPlayer, DutyFactorIsClampedAndCapacityFixed) {
  GaitPlayer g;
  LegSchedule legs[GaitPlayer::kMaxLegs + 2];
  legs[0].dutyFactor = 1.0;
  legs[1].dutyFactor = 0.0;
  g.configure(GaitPlayer::kMaxLegs + 2, legs, 1.0);
  EXPECT_EQ(g.legCount(), GaitPlayer::kMaxLegs);
  EXPECT_DOUBLE_EQ(g.schedule(0).dutyFactor, GaitPlayer::kMaxDutyFactor);
  EXPECT_DOUBLE_EQ(g.schedule(1).dutyFactor, GaitPlayer::kMinDutyFactor);
  const bool c[GaitPlayer::kMaxLegs] = {};
  for (int s = 0; s < 300; ++s) {
    g.update(1.0 / 120.0, c);
    for (int i = 0; i < g.legCount(); ++i) {
      ASSERT_TRUE(std::isfinite(g.leg(i).progress));
      ASSERT_GE(g.leg(i).progress, 0.0);
      ASSERT_LE(g.leg(i).progress, 1.0);
    }
  }
}

}  // namespace
// shiftPhase moves Φ and every ψ with it: a leg whose ψ moves back past its trigger starts a new
// swing (as with an edited trigger); a leg whose ψ moves forwards within its cycle keeps its role.
TEST(GaitPlayer, AShiftedPhaseMovesEveryLegsPhase) {
  GaitPlayer g;
  const LegSchedule legs[2] = {{0.0, 0.6}, {0.5, 0.6}};
  g.configure(2, legs, 1.0, 0.45);  // ψ = 0.45 and 0.95: both in stance
  g.update(0.01, nullptr);
  g.shiftPhase(0.04);  // ψ 0.46 → 0.51 and 0.96 → 0.01 (after the next update's advance)
  g.update(0.01, nullptr);
  EXPECT_NEAR(g.phase(), 0.51, 1e-9);
  EXPECT_TRUE(g.leg(0).stance);
  EXPECT_EQ(g.leg(0).liftOffs, 0);
  EXPECT_FALSE(g.leg(1).stance);
  EXPECT_EQ(g.leg(1).liftOffs, 1);
  g.shiftPhase(std::numeric_limits<double>::quiet_NaN());  // ignored
  EXPECT_NEAR(g.phase(), 0.51, 1e-9);
}

}  // namespace gaitlab::gait

namespace gaitlab::gait {
namespace {

// Coming to a stand (GaitPlayer::hold): no stance leg lifts off, a swinging leg finishes its
// swing and stays down, and the clock stops once every foot is down; release(leg) starts the
// clock just before that leg's trigger, so it lifts off first.
TEST(GaitPlayerHold, HeldLegsStayDownAndTheClockStopsOnceAllAreDown) {
  GaitPlayer g;
  const LegSchedule legs[2] = {{0.0, 0.4}, {0.5, 0.4}};  // a run: never both feet down
  g.configure(2, legs, 1.0, 0.1);  // leg 0 swinging (ψ 0.1 < 0.6), leg 1 in stance (ψ 0.6)
  ASSERT_FALSE(g.leg(0).stance);
  ASSERT_TRUE(g.leg(1).stance);
  g.hold();
  const double dt = 1.0 / 120;
  const bool down[2] = {true, true};
  const bool air[2] = {false, true};
  // Leg 1 reaches its trigger (Φ = 0.5) while leg 0 still swings: it stays down.
  for (int i = 0; i < 60; ++i) {
    g.update(dt, air);
    ASSERT_TRUE(g.leg(1).stance) << "step " << i;
    ASSERT_FALSE(g.leg(1).events & kLiftOff);
  }
  EXPECT_FALSE(g.leg(0).stance);
  // Leg 0, its swing over and late (still searching for the ground), lands ...
  for (int i = 0; i < 20 && !g.planted(); ++i) g.update(dt, down);
  ASSERT_TRUE(g.planted());
  // ... and from then on the clock stands still, every leg down.
  const double phase = g.phase();
  for (int i = 0; i < 240; ++i) {
    g.update(dt, down);
    ASSERT_EQ(g.phase(), phase);
    ASSERT_TRUE(g.planted());
  }
  // Released with leg 1 first: leg 1 lifts off at the next update, leg 0 stays down until its
  // own next lift-off.
  g.release(1, down);
  EXPECT_FALSE(g.held());
  g.update(dt, down);
  EXPECT_TRUE(g.leg(1).events & kLiftOff);
  EXPECT_FALSE(g.leg(1).stance);
  EXPECT_TRUE(g.leg(0).stance);
  EXPECT_NE(g.phase(), phase);
}

// A trot's diagonal pairs have triggers a little apart (the quadruped's 0.556 and 0.571):
// released with the later one first, the earlier one, scheduled to have just begun its swing,
// lifts off with it instead of standing a whole cycle more (GaitPlayer::kPairedSwing). A leg
// further into its scheduled swing stays down until its own next lift-off.
TEST(GaitPlayerHold, AReleasedLegLiftsOffWithThePartnerWhoseTriggerIsJustBefore) {
  GaitPlayer g;
  // Legs 0 and 3 one diagonal pair, 1 and 2 the other (2's trigger 0.015 of the cycle before 1's);
  // leg 0's swing lasts until 0.55 of its cycle, the others' until 0.3.
  const LegSchedule legs[4] = {{0.03, 0.45}, {0.57, 0.7}, {0.555, 0.7}, {0.02, 0.7}};
  g.configure(4, legs, 0.3, 0.9);  // every leg in stance (ψ 0.87, 0.33, 0.345, 0.88)
  ASSERT_TRUE(g.planted());
  g.hold();
  const bool down[4] = {true, true, true, true};
  g.release(1, down);
  g.update(1.0 / 120, down);
  EXPECT_TRUE(g.leg(1).events & kLiftOff) << "the leg released first";
  EXPECT_TRUE(g.leg(2).events & kLiftOff) << "its partner, 0.015 of the cycle into its swing";
  EXPECT_FALSE(g.leg(2).stance);
  EXPECT_TRUE(g.leg(0).stance) << "0.54 into its own cycle: late in a scheduled swing, it waits";
  EXPECT_TRUE(g.leg(3).stance);
  EXPECT_FALSE(g.leg(0).events & kLiftOff);
}

TEST(GaitPlayerHold, AReleasedFootOffTheGroundSwingsInsteadOfStandingOnNothing) {
  GaitPlayer g;
  const LegSchedule legs[2] = {{0.0, 0.6}, {0.5, 0.6}};
  g.configure(2, legs, 1.0, 0.45);  // both in stance (ψ 0.45 ≥ 0.4 and 0.95)
  ASSERT_TRUE(g.planted());
  g.hold();
  const bool oneUp[2] = {true, false};
  g.release(0, oneUp);
  g.update(1.0 / 120, oneUp);
  EXPECT_TRUE(g.leg(0).events & kLiftOff) << "the leg released first";
  EXPECT_TRUE(g.leg(1).events & kLiftOff) << "its foot was off the ground";
  EXPECT_FALSE(g.leg(1).stance);
}

}  // namespace
}  // namespace gaitlab::gait
