#include "gait/gait_player.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::gait {

namespace {

// Fractional part in [0, 1). x − floor(x) can round up to exactly 1 for tiny negative x.
double frac(double x) {
  if (!std::isfinite(x)) return 0.0;
  const double r = x - std::floor(x);
  return r >= 1.0 ? 0.0 : r;
}

double clampDuty(double d) {
  if (!std::isfinite(d)) return 0.5;
  return std::min(GaitPlayer::kMaxDutyFactor, std::max(GaitPlayer::kMinDutyFactor, d));
}

constexpr double kMinPeriod = 1e-3;  // s

}  // namespace

double GaitPlayer::legPhase(double gaitPhase, double stepTrigger) {
  return frac(gaitPhase - stepTrigger);
}

void GaitPlayer::configure(int legCount, const LegSchedule* legs, double period, double phase) {
  legCount_ = std::min(std::max(legCount, 0), kMaxLegs);
  for (int i = 0; i < legCount_; ++i) setLegSchedule(i, legs[i]);
  setPeriod(period);
  reset(phase);
}

void GaitPlayer::setPeriod(double period) {
  period_ = std::isfinite(period) ? std::max(kMinPeriod, period) : 2.0;
}

void GaitPlayer::setLegSchedule(int leg, const LegSchedule& schedule) {
  if (leg < 0 || leg >= kMaxLegs) return;
  schedule_[leg].stepTrigger = frac(schedule.stepTrigger);
  schedule_[leg].dutyFactor = clampDuty(schedule.dutyFactor);
}

void GaitPlayer::shiftPhase(double dPhase) {
  if (std::isfinite(dPhase)) phase_ = frac(phase_ + dPhase);
}

void GaitPlayer::setLateStrike(const LateStrikeParams& p) {
  late_.rate = std::isfinite(p.rate) ? std::max(0.0, p.rate) : 0.0;
  late_.maxOffset = std::isfinite(p.maxOffset) ? std::max(0.0, p.maxOffset) : 0.0;
}

void GaitPlayer::updateProgress(LegGaitState& s, double duty) const {
  const double swingEnd = 1.0 - duty;
  if (s.stance) {
    // Before the scheduled touch-down (early strike) stance has not begun on the schedule.
    s.progress = s.scheduledStance ? std::min(1.0, (s.legPhase - swingEnd) / duty) : 0.0;
  } else {
    // A late foot holds the end of its swing trajectory (ϕ = 1) while it searches for ground.
    s.progress = s.scheduledStance ? 1.0 : s.legPhase / swingEnd;
  }
}

void GaitPlayer::reset(double phase) {
  phase_ = frac(phase);
  for (int i = 0; i < legCount_; ++i) {
    LegGaitState& s = legs_[i];
    s = LegGaitState();
    const double duty = schedule_[i].dutyFactor;
    s.legPhase = legPhase(phase_, schedule_[i].stepTrigger);
    s.scheduledStance = s.legPhase >= 1.0 - duty;
    s.stance = s.scheduledStance;
    s.startsInSwing = !s.stance;
    updateProgress(s, duty);
  }
}

bool GaitPlayer::planted() const {
  for (int i = 0; i < legCount_; ++i)
    if (!legs_[i].stance) return false;
  return true;
}

void GaitPlayer::hold() { held_ = true; }

void GaitPlayer::release(int leg, const bool* footContact) {
  if (!held_) return;
  held_ = false;
  if (leg < 0 || leg >= legCount_) leg = 0;
  // Just before the trigger, so that the next update passes it: ψ wraps, the leg lifts off.
  phase_ = frac(schedule_[leg].stepTrigger - 1e-9);
  for (int i = 0; i < legCount_; ++i) {
    LegGaitState& s = legs_[i];
    const double duty = schedule_[i].dutyFactor;
    s.legPhase = legPhase(phase_, schedule_[i].stepTrigger);
    s.scheduledStance = s.legPhase >= 1.0 - duty;
    if (footContact != nullptr && !footContact[i] && s.stance) {
      s.stance = false;  // in the air: swinging, or searching for the ground
      s.startsInSwing = true;  // the next update reports the lift-off
    }
    // A leg whose step trigger lies just before `leg`'s (the trot's diagonal partner, 0.015 of
    // the cycle earlier) is paired with it: it lifts off now rather than stand a whole cycle.
    if (s.stance && !s.scheduledStance && s.legPhase < kPairedSwing * (1.0 - duty)) {
      s.stance = false;
      s.startsInSwing = true;
    }
    s.early = s.stance && !s.scheduledStance;
    updateProgress(s, duty);
  }
}

void GaitPlayer::update(double dt, const bool* footContact) {
  if (!(dt > 0.0) || !std::isfinite(dt)) dt = 0.0;
  // Held (coming to a stand): the clock runs only while a leg is in its scheduled swing.
  bool swinging = false;
  for (int i = 0; i < legCount_ && held_; ++i)
    swinging = swinging || (!legs_[i].stance && !legs_[i].scheduledStance);
  const double clock = held_ && !swinging ? 0.0 : dt;
  // Algorithm 1 lines 2–6: Φ += dt/T, wrapped. More than a whole cycle per step would hide
  // lift-offs, so the advance is capped just below one cycle.
  const double dPhase = std::min(clock / period_, 0.999);
  phase_ = frac(phase_ + dPhase);

  for (int i = 0; i < legCount_; ++i) {
    LegGaitState& s = legs_[i];
    const double duty = schedule_[i].dutyFactor;
    const double swingEnd = 1.0 - duty;
    const double prevPsi = s.legPhase;
    const bool contact = footContact != nullptr && footContact[i];

    s.events = 0;
    if (s.startsInSwing) {
      s.startsInSwing = false;
      if (!s.stance) {
        s.events |= kLiftOff;
        ++s.liftOffs;
      }
    }
    s.legPhase = legPhase(phase_, schedule_[i].stepTrigger);
    s.scheduledStance = s.legPhase >= swingEnd;

    // ψ went backwards: the phase passed the step trigger, the scheduled lift-off. Every leg
    // starts a new swing here, whatever it was doing: a stance leg (on time or since an early
    // strike) lifts off; a leg still late after a whole missed stance starts its swing afresh.
    // Held, a leg down stays down.
    if (s.legPhase < prevPsi && !(held_ && s.stance)) {
      s.stance = false;
      s.early = false;
      s.late = false;
      s.lateStrikeOffset = 0.0;
      if (!(s.events & kLiftOff)) ++s.liftOffs;  // not twice with the start-up lift-off
      s.events |= kLiftOff;
    }

    if (!s.stance) {
      if (!s.scheduledStance) {
        // Early strike: only in the last part of the swing, so the foot still scraping the
        // ground just after lift-off does not end the swing at once.
        const double phi = s.legPhase / swingEnd;
        if (contact && phi > kEarlyStrikeProgress) {
          s.stance = true;
          s.early = true;
          s.events |= kTouchDown | kEarlyStrike;
          ++s.touchDowns;
          ++s.earlyStrikes;
        }
      } else if (contact) {
        // On time (or the end of a late strike): stance, and the search offset resets.
        s.stance = true;
        s.late = false;
        s.lateStrikeOffset = 0.0;
        s.events |= kTouchDown;
        ++s.touchDowns;
      } else {
        // Late strike: keep swinging, and lower the target until the foot finds the ground.
        if (!s.late) {
          s.late = true;
          s.events |= kLateStrike;
          ++s.lateStrikes;
        }
        s.lateStrikeOffset = std::min(late_.maxOffset, s.lateStrikeOffset + late_.rate * dt);
      }
    }

    updateProgress(s, duty);
    s.time += dt;
    if (s.stance) s.stanceTime += dt;
  }
}

double GaitPlayer::measuredDutyFactor(int leg) const {
  const LegGaitState& s = legs_[leg];
  return s.time > 0.0 ? s.stanceTime / s.time : 0.0;
}

}  // namespace gaitlab::gait
