// Gait player (thesis §3.1.1): advances the normalised gait phase Φ = t/T by dt/T each step
// (wrapping at 1, Algorithm 1 lines 2–6) and derives each leg's role from its step trigger and
// duty factor, corrected by the feet's actual contacts (early and late foot strikes).
//
// Leg-local phase ψ = frac(Φ − trigger): the step trigger is the gait phase of the leg's lift-off.
// The leg swings while ψ < 1 − D (swing progress ϕ = ψ / (1 − D)) and stands for the rest of the
// cycle (stance progress (ψ − (1 − D)) / D); D = duty factor, the fraction of the cycle in stance.
//
// Contact corrections (§3.1.1):
//  * early strike: a foot that touches down during swing with ϕ > 0.8 switches to stance at once
//    and stays in stance until its next scheduled lift-off;
//  * late strike: when the schedule says stance but the foot has not touched down, the leg keeps
//    swinging (ϕ held at 1) and its foot target sinks by an offset that grows at a fixed rate up to
//    a bound, until contact; the offset resets on contact.
//
// Fixed capacity, no allocation: one GaitPlayer per character, updated once per fixed step.
#pragma once
#include <cstdint>

namespace gaitlab::gait {

// Bits of LegGaitState::events (what happened during the last update).
enum GaitEvent : unsigned {
  kLiftOff = 1u,      // stance → swing (or a new swing begins after a whole missed stance)
  kTouchDown = 2u,    // swing → stance
  kEarlyStrike = 4u,  // the touch-down was early (ϕ > 0.8, before the scheduled touch-down)
  kLateStrike = 8u,   // the schedule reached stance with the foot still in the air
};

struct LegSchedule {
  double stepTrigger = 0.0;  // gait phase of lift-off, [0, 1)
  double dutyFactor = 0.62;  // fraction of the cycle in stance (the original implementation's default, docs/original-implementation.md)
};

struct LateStrikeParams {
  double rate = 0.5;       // m/s the foot target sinks while the strike is late
  double maxOffset = 0.2;  // m, bound of that offset
};

struct LegGaitState {
  bool stance = true;             // current role
  double progress = 0.0;          // swing progress ϕ in swing, stance progress in stance, [0, 1]
  double legPhase = 0.0;          // ψ = frac(Φ − trigger)
  bool scheduledStance = true;    // what the schedule alone says
  bool early = false;             // in stance through an early strike, before the scheduled one
  bool late = false;              // schedule says stance, foot not down yet: still swinging
  double lateStrikeOffset = 0.0;  // m, lower the swing foot target by this much (≥ 0)
  unsigned events = 0;            // GaitEvent bits of the last update
  bool startsInSwing = false;     // set by reset(): the first update reports this swing's lift-off

  // Statistics since the last reset().
  double stanceTime = 0.0;  // s spent in the stance role
  double time = 0.0;        // s since reset
  int liftOffs = 0, touchDowns = 0, earlyStrikes = 0, lateStrikes = 0;
};

class GaitPlayer {
 public:
  static constexpr int kMaxLegs = 8;
  static constexpr double kEarlyStrikeProgress = 0.8;  // §3.1.1
  // Duty factors are clamped to this range so both phases have a length (ϕ divides by 1 − D).
  static constexpr double kMinDutyFactor = 0.01;
  static constexpr double kMaxDutyFactor = 0.99;
  // release(leg): a leg scheduled to swing at the release, and no further into its swing than
  // this share of it, lifts off with `leg` (its partner in the footfall pattern). Without it the
  // quadruped's trot released from a stand stepped with one leg, its diagonal partner standing a
  // cycle more, and a sideways push rolled the body over the feet still down (controller-notes
  // §36).
  static constexpr double kPairedSwing = 0.1;

  // Sets the legs (at most kMaxLegs; extra legs are ignored) and the period T (s), then reset().
  void configure(int legCount, const LegSchedule* legs, double period, double phase = 0.0);

  // Live edits (the gait editor). A changed trigger moves ψ; if that moves it backwards the
  // next update sees a new cycle (a lift-off), which is the sensible reading of the edit.
  void setPeriod(double period);
  void setLegSchedule(int leg, const LegSchedule& schedule);
  void setLateStrike(const LateStrikeParams& p);  // negative or NaN values become 0
  // Φ += dPhase, the legs' schedules unchanged (a gait transition re-aligning the phase to a new
  // footfall pattern, gait/gait_transition.h). As with an edited trigger, a leg whose ψ moves
  // back starts a new swing at the next update.
  void shiftPhase(double dPhase);

  // Φ := phase; every leg takes the role its schedule gives; offsets and statistics cleared.
  // A leg that starts in swing has its lift-off at the reset (a character is spawned with its
  // feet on the ground): the first update() reports kLiftOff for it, so a controller that records
  // the lift-off position P0 on kLiftOff needs no special start-up case.
  void reset(double phase = 0.0);

  // One fixed step: Φ += dt/T (wrapped), then each leg's role from its schedule and its foot
  // contact this step (footContact[leg], legCount() entries; nullptr = no foot in contact).
  // dt/T is capped below one cycle per step.
  void update(double dt, const bool* footContact);

  // Coming to a stand (beyond the thesis; Coros et al. 2010 stop by standing on both feet).
  // While held, no stance leg lifts off; a swing leg finishes its swing (late strikes
  // included) and stays down; the phase advances only while some leg is still in its
  // scheduled swing, so once every foot is down the clock has stopped (planted()).
  // release(leg) starts the clock again just before `leg`'s step trigger, so that this leg
  // lifts off first (the stepping leg a recovery chooses) with those its pattern pairs with it
  // (their triggers just after `leg`'s, or just before it: kPairedSwing); every other leg down
  // stays down until its own next lift-off, as after an early strike.
  // Statistics are kept.
  // A leg whose foot is off the ground (footContact, legCount() entries; nullptr: every foot
  // down) is not left standing on nothing: it swings, searching for the ground as a late strike.
  void hold();
  void release(int leg, const bool* footContact = nullptr);
  bool held() const { return held_; }
  bool planted() const;  // every leg in stance

  double phase() const { return phase_; }
  double period() const { return period_; }
  int legCount() const { return legCount_; }
  const LegSchedule& schedule(int leg) const { return schedule_[leg]; }
  const LegGaitState& leg(int i) const { return legs_[i]; }
  const LateStrikeParams& lateStrike() const { return late_; }

  // Fraction of the time since reset() the leg spent in stance (compare with its duty factor).
  double measuredDutyFactor(int leg) const;

  // ψ = frac(Φ − trigger), in [0, 1).
  static double legPhase(double gaitPhase, double stepTrigger);

 private:
  void updateProgress(LegGaitState& s, double duty) const;

  int legCount_ = 0;
  double period_ = 2.0;  // s (the original implementation's default, docs/original-implementation.md)
  double phase_ = 0.0;   // Φ in [0, 1)
  bool held_ = false;    // hold(): no lift-offs, the clock runs only while a leg swings
  LateStrikeParams late_;
  LegSchedule schedule_[kMaxLegs];
  LegGaitState legs_[kMaxLegs];
};

}  // namespace gaitlab::gait
