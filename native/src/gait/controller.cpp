#include "gait/controller.h"

#include <algorithm>
#include <cmath>

#include "gait/foot_placement.h"
#include "gait/gait_transition.h"
#include "gait/gravity.h"
#include "gait/heading.h"
#include "gait/ik.h"
#include "gait/pd.h"
#include "gait/stance_forces.h"
#include "gait/virtual_force.h"

namespace gaitlab::gait {

using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

// Bound of a swing target's rate (rad/s): a step in the target (a new strike point) is not a
// velocity to follow.
constexpr double kMaxSwingRate = 20.0;

// Speed tracking (GaitParams::speedIntegralGain): from the key's speedTrackedFrom up, with the
// trim bounded by the key's maxSpeedTrim and fading with this time constant (s) below it. Tracked
// from 0.5 m/s, the slow goals were walked fast (the push-robust biped 0.4 m/s at 0.51, the
// quadruped's trot 0.4 at 0.37); from 0.15, both within 1 % (controller-notes §21); the biped's
// walk with double support, tracked from 0.15, walked goals 0.1 and 0.12 at 0.27 and 0.38 m/s,
// and from 0.05 within 3 % (§48).
constexpr double kSpeedTrimFade = 0.5;
// Speed tracking's proportional term (GaitParams::speedProportionalGain): the speed error is
// averaged by a first-order filter of this time constant (s), about a stride, and the term is
// bounded (m/s). The integral alone took 10–20 % too fast out of the biped's start only over
// several seconds; the bound keeps a push, whose error is 0.5–1 m/s, from being fought with the
// full gain (docs/controller-notes.md §28: 0.5 s and 0.1 m/s at gain 8 kept every held push).
constexpr double kSpeedMeanWindow = 0.5;
constexpr double kMaxSpeedCorrection = 0.1;
// The speed error the integral trim integrates is bounded (m/s): the trim is there to take out a
// gait's steady bias, not to chase the lag of a body still accelerating. Unbounded, the canter's
// trim (gain 1.7 1/s) wound up to 0.8–1.3 m/s within a second of a change from the trot, the body
// still 1 m/s behind its goal, and the quadruped fell. Of bounds 0.1–0.25 m/s (measured on trot ↔
// canter changes, held canter goals, pushes and the walking benchmark), 0.1 and 0.15 fell least on
// the changes; 0.1 tracked the quadruped's ramp worse (controller-notes §50).
constexpr double kMaxTrimError = 0.15;

// Standing (goal speed 0, beyond the thesis): the spot held, by a desired velocity of kHoldGain
// times the distance to it, at most kMaxHoldSpeed; and how far a character may be carried from it
// before the spot moves with it (a push or a drag moves where it stands: it walks back at most
// kHoldLeash). Measured against stepping in place alone (controller-notes §16): standing drift
// over 20 s after the ramp 0.40 → 0.04 m (biped), 0.74 → 0.05 m (quadruped); gains 0.3–1 1/s,
// speeds 0.1–0.2 m/s and leashes 0.15–0.3 m all held within 0.1 m except the quadruped at 1 1/s;
// 0.3 1/s and 0.1 m/s cost the fewest standing pushes. A gait that steps in place with a bias
// (the push-searched trot creeps forward and sideways at v_d = 0) settles where the bias balances
// kHoldGain × distance, 0.2 m off the spot; the integral term, kHoldIntegralGain × the distance
// integrated (world frame, bounded by kMaxHoldSpeed), takes it back, once the bound leaves room
// for the bias (0.1 m/s did not after a stop from 1 m/s: controller-notes §23, where the drift
// fell from 0.22 to 0.02-0.03 m for the quadruped and 0.10 to 0.02 m for the biped).
constexpr double kHoldGain = 0.3;           // 1/s
constexpr double kHoldIntegralGain = 0.2;   // 1/s²
constexpr double kMaxHoldSpeed = 0.15;      // m/s
constexpr double kHoldLeash = 0.3;          // m

Vector3d clampNorm(const Vector3d& v, double max) {
  const double n = v.norm();
  return n > max ? v * (max / n) : v;
}

// Signed rotation angle of `rel` about unit axis `axis` (swing–twist decomposition).
double twistAngle(const Quaterniond& rel, const Vector3d& axis) {
  const double p = rel.vec().dot(axis);
  double a = 2.0 * std::atan2(p, rel.w());
  return wrapAngle(a);
}

}  // namespace

Controller::Controller(const body::Morphology& morphology, const GaitParams& params,
                       double heading)
    : m_(morphology), character_(characterOf(morphology)), desiredHeading_(heading) {
  for (const body::Leg& leg : m_.legs) {
    const body::Segment& upper = m_.segments[leg.upper];
    const body::Segment& lower = m_.segments[leg.lower];
    const body::Segment& foot = m_.segments[leg.foot];
    const body::Segment& belowShin = m_.segments[leg.tarsus >= 0 ? leg.tarsus : leg.foot];
    LegGeometry g;
    g.thigh = (lower.joint.pivot - upper.joint.pivot).norm();
    g.shin = (belowShin.joint.pivot - lower.joint.pivot).norm();
    g.tarsus = leg.tarsus >= 0 ? (foot.joint.pivot - belowShin.joint.pivot).norm() : 0.0;
    g.ankleHeight = foot.joint.pivot.y() - (foot.center.y() - foot.halfExtents.y());
    g.side = upper.joint.pivot.x() >= 0 ? 1.0 : -1.0;
    const double ahead = foot.center.z() - foot.joint.pivot.z();
    g.toe = ahead + foot.halfExtents.z();
    g.heel = foot.halfExtents.z() - ahead;
    g.halfWidth = foot.halfExtents.x();
    // A ball hip's limits are [forward swing, twist, sideways swing] (body/creature.h); the knee's
    // flexion is its upper limit when it points forward, its lower mirrored when it points back.
    const body::Joint& hip = upper.joint;
    g.hipFold = leg.kneeBend > 0 ? hip.upper[0] : hip.lower[0];
    g.hipSideways = std::min(hip.upper[2], -hip.lower[2]);
    g.kneeFlexion = leg.kneeBend > 0 ? lower.joint.upper[0] : -lower.joint.lower[0];
    geometry_.push_back(g);
  }
  liftOff_.assign(m_.legs.size(), Vector3d::Zero());
  swingTargets_.assign(m_.legs.size(), SwingTargets());
  standPose_.assign(m_.segments.size(), Quaterniond::Identity());
  weight_ = m_.totalMass() * -gravity_.y();
  setParams(params);
}

void Controller::setParams(const GaitParams& params) { setGait(Gait::single(params)); }

void Controller::setGait(const Gait& gait) {
  gait_ = gait;
  // A gait set before the first step (a gait file given at spawn: `gaitlab walk --params`, the
  // optimiser's episodes) starts the gait player from its own footfall pattern, at the phase it
  // was given, as if the character had been spawned with it; once walking, a new gait is taken
  // up in mid-stride (one of another footfall pattern where the gait cycle starts again).
  blendAt(std::abs(desiredVelocity_.z()), /*restart=*/!started_);
}

void Controller::blendAt(double speed, bool restart, bool atTransitionPhase) {
  const bool first = player_.legCount() == 0 || restart;
  const int legs = static_cast<int>(m_.legs.size());
  GaitParams next;
  paramsAtSpeed(character_, gait_, speed, &next);
  blendedAt_ = speed;
  // A change of footfall pattern in mid-stride (gait/gait_transition.h) is taken up where the gait
  // phase reaches the old key's transitionPhase (the cycle's start unless it says otherwise), and
  // there the gait phase moves so that each leg's own phase moves as little as the two patterns
  // allow. Until then the parameters stay the old gait's.
  const bool change = !first && footfallDiffers(params_.legs, next.legs, legs);
  transitionPending_ = change && !atTransitionPhase;
  if (transitionPending_) return;
  if (change) {
    // Speed tracking's trim and mean error belong to the gait they were measured under: the
    // canter's trim, up to 1.45 m/s, asked the trot after it for 0.5 m/s more than its goal. The
    // new gait starts its own afresh (controller-notes §50): from zero, or, for a change made
    // while the desired speed holds the goal (a steady goal, or one moving slower than
    // maxAcceleration), from the body's lag behind it then, within the new key's bound. That
    // lag is the new gait's to make up, and F_v then aims as far ahead of the goal as the body
    // is behind it at once; the integral takes seconds (0.1 m/s per second at the canter's
    // gain), and the canter entered on the walking benchmark's slow ramp ran 2.25 m/s at goals
    // of 2.8–3.0 m/s meanwhile. A body ahead of its goal starts from zero: started below it,
    // the walk after the trot on a slow ramp down ran 16 % slow (controller-notes §72).
    const double lag = desiredVelocity_.z() - forwardSpeed_;
    const bool holdsGoal = desiredVelocity_.z() == goal_.speed && goal_.speed > 0;
    speedTrim_ = holdsGoal ? std::clamp(lag, 0.0, next.maxSpeedTrim) : 0.0;
    meanSpeedError_ = 0;
    player_.shiftPhase(transitionPhaseShift(params_.legs, next.legs, legs));
    ++gaitChanges_;
  }
  params_ = next;
  const GaitParams& params = params_;
  LegSchedule schedule[kMaxLegs];
  for (size_t i = 0; i < m_.legs.size(); ++i) {
    schedule[i].stepTrigger = params.legs[i].stepTrigger;
    schedule[i].dutyFactor = params.legs[i].dutyFactor;
  }
  if (first) {
    const double phase = player_.legCount() == 0 ? 0.0 : player_.phase();
    player_.configure(legs, schedule, params.period, phase);
  } else {
    player_.setPeriod(params.period);
    for (int i = 0; i < legs; ++i) player_.setLegSchedule(i, schedule[i]);
  }
}

void Controller::update(double dt, const CharacterState& s, Vector3d* torques) {
  const int segments = static_cast<int>(m_.segments.size());
  for (int i = 0; i < segments; ++i) torques[i].setZero();

  // Heading frame (correction of defect 7: nothing in world axes) and the goal (steering).
  const BodyState& root = s.segments[m_.legFrames[0]];
  const double yaw = headingOf(root.orientation);
  desiredHeading_ = wrapAngle(desiredHeading_ + goal_.turnRate * dt);
  // Keep the heading goal within reach: a character knocked around does not try to spin back
  // through half a turn at once.
  const double headingError = wrapAngle(desiredHeading_ - yaw);
  if (std::abs(headingError) > 0.6) desiredHeading_ = wrapAngle(yaw + std::copysign(0.6, headingError));

  // Centre-of-mass velocity in m/s (defect 1: the original never divided by dt).
  Vector3d comVelocity = Vector3d::Zero(), comPosition = Vector3d::Zero();
  double mass = 0;
  for (int i = 0; i < segments; ++i) {
    comVelocity += m_.segments[i].mass * s.segments[i].linearVelocity;
    comPosition += m_.segments[i].mass * s.segments[i].position;
    mass += m_.segments[i].mass;
  }
  comVelocity /= mass;
  comPosition /= mass;
  com_ = comPosition;
  if (getsUp(s, dt, torques)) return;  // fallen: getting up (gait/get_up.cpp) before it walks again
  Vector3d velocityH = worldToHeading(yaw, comVelocity);
  velocityH.y() = 0;
  forwardSpeed_ = velocityH.z();
  desiredVelocity_ = rampDesiredVelocity(desiredVelocity_, Vector3d(0, 0, goal_.speed),
                                         params_.maxAcceleration, dt);
  // Speed keys (gait/speed_keys.h): the parameters follow the desired speed as it ramps, and the
  // gait changes where the keys' footfall patterns do (gait/gait_transition.h). With one key
  // there is nothing to blend, nor while the speed stays below the first key or above the last
  // (a crowd ramping up from 0 to its cruise speed below the first key copies nothing).
  if (gait_.keys.size() > 1 && !transitionPending_ && !gait_.heldAlike(desiredVelocity_.z(), blendedAt_))
    blendAt(std::abs(desiredVelocity_.z()));
  // Speed tracking (speedIntegralGain, beyond the thesis): F_v = K_v (v_d − v) alone leaves a
  // speed error that depends on the speed (the biped walked 0.92 m/s at 1.0 and 1.53 at 1.4,
  // controller-notes §14). The velocity F_v aims at is v_d plus the integral of that error (each
  // step's error bounded by kMaxTrimError, and the integral reset at a change of gait). Below
  // speedTrackedFrom the low-speed capture-point placement governs and the trim fades out.
  // While v_d is still ramping to the goal the body lags it by design; integrating that lag
  // wound the trim up on every start from rest (from 0.15 m/s one biped in 16 of the crowd
  // benchmark's fell), so the error counts only once v_d has reached the goal (or follows a
  // goal that moves slower than maxAcceleration).
  // The proportional term on the stride-mean error (speedProportionalGain) counts and fades alike.
  if (desiredVelocity_.z() >= params_.speedTrackedFrom) {
    if (desiredVelocity_.z() == goal_.speed) {
      const double error = desiredVelocity_.z() - velocityH.z();
      speedTrim_ += params_.speedIntegralGain * std::clamp(error, -kMaxTrimError, kMaxTrimError) * dt;
      meanSpeedError_ += (dt / kSpeedMeanWindow) * (error - meanSpeedError_);
    }
  } else {
    const double fade = std::exp(-dt / kSpeedTrimFade);
    speedTrim_ *= fade;
    meanSpeedError_ *= fade;
  }
  speedTrim_ = std::clamp(speedTrim_, -params_.maxSpeedTrim, params_.maxSpeedTrim);
  speedCorrection_ = std::clamp(params_.speedProportionalGain * meanSpeedError_, -kMaxSpeedCorrection, kMaxSpeedCorrection);

  // Standing: once the goal is 0 and the ramp has reached it, hold the spot where the centre of
  // mass was then, by a small desired velocity towards it (heading frame) that the foot placement
  // and F_v follow, proportional and integral; stepping in place alone drifts (0.4 m in 20 s).
  if (goal_.speed == 0.0 && desiredVelocity_.z() == 0.0) {
    if (!anchored_) {
      anchor_ = com_;
      holdIntegral_.setZero();
    }
    anchored_ = true;
    Vector3d away = com_ - anchor_;
    away.y() = 0;
    if (away.norm() > kHoldLeash) anchor_ += away * (1.0 - kHoldLeash / away.norm());
    Vector3d toAnchorWorld = anchor_ - com_;
    toAnchorWorld.y() = 0;
    holdIntegral_ = clampNorm(holdIntegral_ + kHoldIntegralGain * toAnchorWorld * dt, kMaxHoldSpeed);
    const Vector3d toAnchor = worldToHeading(yaw, toAnchorWorld);  // y stays 0: a turn about y
    hold_ = clampNorm(kHoldGain * toAnchor + worldToHeading(yaw, holdIntegral_), kMaxHoldSpeed);
  } else {
    anchored_ = false;
    hold_.setZero();
  }

  // Gait player (§3.1.1): phase, stance/swing, early and late strikes; held while standing.
  const double phaseBefore = player_.phase();
  player_.update(dt, s.footContact);
  updateStand(s, comVelocity);
  // A change of footfall pattern left pending is taken up where the old gait's cycle reaches its
  // transitionPhase.
  if (transitionPending_ && phaseReached(phaseBefore, player_.phase(), params_.transitionPhase))
    blendAt(std::abs(desiredVelocity_.z()), false, true);
  // The turn's heading bounded by this step's parameters, once the keys have been blended: the
  // quadruped's bridge key, 0.02 m/s above the trot's top key, tightens maxTurnSlip from 0.8 to
  // 0.25 m/s within one step of a start from rest, and bounded before the blend the heading led
  // the path by 0.1 rad more than the new bound for that step.
  boundTurnLead(comVelocity);
  // P0 of a leg whose first swing starts without a lift-off event: where its foot is now.
  if (!started_) {
    for (size_t l = 0; l < m_.legs.size(); ++l)
      liftOff_[l] = jointPivot(m_.legs[l].foot, s) - Vector3d(0, geometry_[l].ankleHeight, 0);
    started_ = true;
  }
  const double phase = player_.phase();

  int stanceLegs = 0;
  for (int l = 0; l < player_.legCount(); ++l) stanceLegs += player_.leg(l).stance ? 1 : 0;
  const double stanceLoad = weight_ / std::max(1, stanceLegs);  // N per stance leg

  if (!m_.spine.empty()) spine(s, torques);
  if (stand_ == Stand::Planted) {
    if (standsAsTable())
      plantedTable(s, torques);
    else
      plantedStance(s, torques);
    finishTorques(s, torques);
    return;
  }

  // Stance legs per leg frame; swing legs first (§3.1.4–3.1.6), so that what they exert on the
  // leg frames is known when the stance legs are set.
  const int frames = static_cast<int>(m_.legFrames.size());
  int stanceIn[kMaxLegFrames] = {};
  for (size_t l = 0; l < m_.legs.size(); ++l) {
    const body::Leg& leg = m_.legs[l];
    const int li = static_cast<int>(l);
    if (player_.leg(li).events & kLiftOff) {
      liftOff_[l] = jointPivot(leg.foot, s) - Vector3d(0, geometry_[l].ankleHeight, 0);
      swingTargets_[l].valid = false;
    }
    if (player_.leg(li).stance)
      ++stanceIn[legFrameIndex(leg)];
    else
      swingLeg(li, s, dt, yaw, velocityH, torques);
  }

  if (frames > 1) {
    bodyStance(s, yaw, comPosition, comVelocity, phase, torques);
    finishTorques(s, torques);
    return;
  }

  // One leg frame (the biped): the thesis's scheme. Leg-frame torque feedback (§3.1.3,
  // eq. 3.4–3.5): the torque the leg frame should feel, a PD towards its orientation graphs in
  // the heading frame, less what the swing hips already exert on it: `net` is what its stance
  // legs must add, shared among their hips.
  for (int f = 0; f < frames; ++f) {
    const int lf = m_.legFrames[f];
    const LegFrameParams& p = params_.legFrames[f];
    const BodyState& frame = s.segments[lf];
    const int stance = stanceIn[f];
    if (stance == 0) continue;
    Vector3d net = frameOrientationPd(f, s, phase);
    for (int i = 0; i < segments; ++i) {
      if (m_.segments[i].parent != lf) continue;
      bool stanceHip = false;
      for (size_t l = 0; l < m_.legs.size(); ++l)
        if (m_.legs[l].upper == i && player_.leg(static_cast<int>(l)).stance) stanceHip = true;
      if (!stanceHip) net += torques[i];  // the joint's reaction on the leg frame is −torques[i]
    }
    if (m_.segments[lf].parent >= 0) net -= torques[lf];

    // Stance forces on the leg frame (§3.1.4): height F_h, velocity F_v (eq. 3.6); F_D per leg.
    const Vector3d fh = heightForce(f, s, phase);
    const Vector3d fv = velocityForce(p.velocityGain, headingToWorld(yaw, trimmedVelocity()), comVelocity);
    const PhaseForceCoefficients c{p.fd[0], p.fd[1], p.fd[2], p.fd[3]};

    // The stance hips deliver the leg frame's net torque (eq. 3.5).
    const Vector3d perHip = -net / stance;
    for (size_t l = 0; l < m_.legs.size(); ++l) {
      const body::Leg& leg = m_.legs[l];
      const int li = static_cast<int>(l);
      if (leg.legFrame != lf || !player_.leg(li).stance) continue;
      const double d = footProgress(frame.position, s.segments[leg.foot].position, yaw);
      stanceLeg(li, s, yaw, (fh + fv) / stance + phaseForce(c, d, yaw), stanceLoad, false, torques);
      torques[leg.upper] = perHip;
    }
  }

  finishTorques(s, torques);
}

void Controller::boundTurnLead(const Vector3d& comVelocity) {
  // maxTurnSlip (params.h): the body slides sideways past its heading at v·sin(lead), where lead
  // is how far the goal heading is ahead of the path. A turn that runs ahead of what the stance
  // can follow is held back to asin(maxTurnSlip / v): the heading then turns as fast as the
  // velocity does. Only the lead in the turn's direction is bounded (a body pushed off its path,
  // or not turning, is left to the balance feedback), and at speeds below the bound nothing is.
  if (goal_.turnRate == 0.0) return;
  const double speed = std::hypot(comVelocity.x(), comVelocity.z());
  if (speed <= params_.maxTurnSlip) return;
  const double path = std::atan2(comVelocity.x(), comVelocity.z());  // heading.h: yaw of +z
  const double lead = wrapAngle(desiredHeading_ - path);
  const double bound = std::asin(params_.maxTurnSlip / speed);
  if (lead * goal_.turnRate > 0 && std::abs(lead) > bound) desiredHeading_ = wrapAngle(path + std::copysign(bound, lead));
}

Vector3d Controller::frameOrientationPd(int f, const CharacterState& s, double phase) const {
  // Eq. 3.4: PD towards the leg frame's orientation graphs, in the heading frame.
  const LegFrameParams& p = params_.legFrames[f];
  const BodyState& frame = s.segments[m_.legFrames[f]];
  const Quaterniond desired = headingQuat(desiredHeading_ + p.yaw.eval(phase)) *
                              Quaterniond(Eigen::AngleAxisd(p.pitch.eval(phase), Vector3d::UnitX())) *
                              Quaterniond(Eigen::AngleAxisd(p.roll.eval(phase), Vector3d::UnitZ()));
  return orientationPd(p.orientationKp, p.orientationKd, frame.orientation, desired,
                       frame.angularVelocity);
}

Vector3d Controller::heightForce(int f, const CharacterState& s, double phase) const {
  // F_h (§3.1.4): PD towards the leg frame's standing height plus its height graph, above the
  // ground under it (defect 7: ray cast, not a constant).
  const int lf = m_.legFrames[f];
  const LegFrameParams& p = params_.legFrames[f];
  const BodyState& frame = s.segments[lf];
  const double ground = s.ground.at(frame.position.x(), frame.position.z());
  const double height = ground + m_.segments[lf].center.y() + p.heightOffset.eval(phase);
  return Vector3d(0, p.heightKp * (height - frame.position.y()) - p.heightKd * frame.linearVelocity.y(), 0);
}

double Controller::comHeight(const CharacterState& s) const {
  return std::max(0.1, com_.y() - s.ground.at(com_.x(), com_.z()));
}

void Controller::finishTorques(const CharacterState& s, Vector3d* torques) const {
  // Twist scaling on swing hips only: a stance leg cannot spin about its own axis (knee hinge,
  // ankle and the foot on the ground lock it), and its hip twist is what turns the leg frame.
  for (size_t l = 0; l < m_.legs.size(); ++l) {
    const body::Leg& leg = m_.legs[l];
    if (player_.leg(static_cast<int>(l)).stance) continue;
    const Vector3d axis = s.segments[leg.upper].orientation * Vector3d::UnitY();
    Vector3d& t = torques[leg.upper];
    t -= (1.0 - params_.gains.hipTwistScale) * t.dot(axis) * axis;
  }
  clampTorques(torques);
}

void Controller::jointHold(int seg, const CharacterState& s, const Quaterniond& relative, double kp, double kd,
                           Vector3d* torques) const {
  const BodyState& c = s.segments[seg];
  const BodyState& p = s.segments[m_.segments[seg].parent];
  torques[seg] += jointPd(kp, kd, p.orientation, c.orientation, relative, p.angularVelocity, c.angularVelocity);
}

void Controller::clampTorques(Vector3d* torques) const {
  const int segments = static_cast<int>(m_.segments.size());
  for (int i = 0; i < segments; ++i) torques[i] = clampNorm(torques[i], params_.gains.maxTorque);
}

void Controller::bodyStance(const CharacterState& s, double yaw, const Vector3d& com,
                            const Vector3d& comVelocity, double phase, Vector3d* torques) {
  // Whole-body stance (beyond the thesis; stance_forces.h): the body's wanted force and torque
  // from the leg frames' own PDs (§3.1.3–3.1.4), then one ground force per stance foot.
  const int segments = static_cast<int>(m_.segments.size());
  const int frames = static_cast<int>(m_.legFrames.size());
  Vector3d force = -weight_ / 9.81 * gravity_;  // gravity compensation of the whole body
  Vector3d torque = Vector3d::Zero();
  double kv = 0;
  for (int f = 0; f < frames; ++f) {
    const int lf = m_.legFrames[f];
    const LegFrameParams& p = params_.legFrames[f];
    const BodyState& frame = s.segments[lf];
    torque += frameOrientationPd(f, s, phase);
    // Height F_h of this leg frame, acting where the leg frame is: unequal heights pitch the body.
    const Vector3d fh = heightForce(f, s, phase);
    force += fh;
    torque += (frame.position - com).cross(fh);
    kv += p.velocityGain;
    // What the swing hips exert on this leg frame (their reaction, −τ) the stance must make up.
    for (int i = 0; i < segments; ++i) {
      if (m_.segments[i].parent != lf) continue;
      for (size_t l = 0; l < m_.legs.size(); ++l)
        if (m_.legs[l].upper == i && !player_.leg(static_cast<int>(l)).stance) torque += torques[i];
    }
  }
  // F_v (eq. 3.6) on the whole body.
  force += velocityForce(kv, headingToWorld(yaw, trimmedVelocity()), comVelocity);
  // Turning: the roll moment of the turn's sideways ground force about the centre of mass, left
  // to the stance rather than cancelled (turnRollMoment, params.h). The force m v ω points to the
  // turn's centre (left for ω > 0) from the ground h below the centre of mass, so its moment
  // (−h·up) × (m v ω·left) = m v ω h·forward rolls the body out of the turn.
  if (params_.turnRollMoment > 0 && goal_.turnRate != 0.0)
    torque += params_.turnRollMoment * (weight_ / 9.81) * forwardSpeed_ * goal_.turnRate * comHeight(s) *
              headingForward(yaw);

  Vector3d points[kMaxStanceFeet], forces[kMaxStanceFeet];
  int legOf[kMaxStanceFeet];
  int count = 0;
  for (size_t l = 0; l < m_.legs.size() && count < kMaxStanceFeet; ++l) {
    if (!player_.leg(static_cast<int>(l)).stance) continue;
    points[count] = jointPivot(m_.legs[l].foot, s) - Vector3d(0, geometry_[l].ankleHeight, 0);
    legOf[count++] = static_cast<int>(l);
  }
  if (count == 0) return;
  StanceForceSettings settings;
  distributeStanceForces(com, force, torque, points, count, settings, forces);
  for (int i = 0; i < count; ++i)
    stanceLeg(legOf[i], s, yaw, forces[i], std::max(0.0, forces[i].y()), true, torques);
}

void Controller::stanceLeg(int l, const CharacterState& s, double yaw, const Vector3d& force,
                           double load, bool supported, Vector3d* torques) {
  const body::Leg& leg = m_.legs[l];

  // The virtual force F wanted on the leg frame (§3.1.4, Figure 3.4), by the Jacobian
  // transpose over the stance leg. The foot is what stays put, so each joint's torque is the
  // moment of F about it taken at the leg frame, (p_j − p_lf) × F: turning joint j with the
  // foot fixed moves the leg frame, not the foot. Written with the chain's usual leg-frame-base
  // convention this is −F at the point p_lf. Taking −F at the sole instead, as a free swing
  // leg would, differs by the constant moment (p_sole − p_lf) × F, which only the stance hip
  // could supply, and the stance hip is spent on the leg frame's orientation (below): the
  // knee and ankle were left pushing the leg frame backwards when it was asked to go forwards.
  // In the whole-body stance (bodyStance, more than one leg frame) F is this foot's ground
  // force, chosen with the other feet's so that together they balance the body: it is taken
  // at the sole, and the hip delivers its moment like every other joint.
  const DofChain chain = legChain(l, s);
  const Vector3d at = supported ? jointPivot(leg.foot, s) - Vector3d(0, geometry_[l].ankleHeight, 0)
                                : s.segments[leg.legFrame].position;
  accumulateJointTorques(chain, at, -force, torques, static_cast<int>(m_.segments.size()));

  // Knee: PD towards a slightly bent stance knee (§3.1.4, §3.1.7).
  kneePd(l, s, params_.gains.stanceKneeFlexion, torques);

  // Stance ankle (§3.1.6–3.1.7): the foot is held flat on the ground in the heading frame, and
  // pitched to the toe-off angle after the toe-off time. While it lies flat this PD exerts
  // nothing and the stance leg pivots freely over its ankle, an inverted pendulum; the ankle
  // torque left is the virtual forces' share from above. Whatever the sum, it is limited to
  // what the ground can return (limitToSupport): a foot asked for more rolls onto its edge.
  const LegParams& lp = params_.legs[l];
  const LegFrameParams& fp = params_.legFrames[legFrameIndex(leg)];
  const double pitch = player_.leg(l).progress > lp.toeOffTime ? fp.toeOffAngle : 0.0;
  footPd(l, s, yaw, pitch, params_.gains.stanceAnkleKp, params_.gains.stanceAnkleKd, torques);
  limitToSupport(l, s, load, torques);
}

void Controller::swingLeg(int l, const CharacterState& s, double dt, double yaw,
                          const Vector3d& velocityH, Vector3d* torques) {
  const body::Leg& leg = m_.legs[l];
  const LegGeometry& g = geometry_[l];
  const JointGains& k = params_.gains;
  const LegFrameParams& p = params_.legFrames[legFrameIndex(leg)];
  const LegParams& lp = params_.legs[l];
  const LegGaitState& state = player_.leg(l);
  const BodyState& frame = s.segments[leg.legFrame];
  const BodyState& thigh = s.segments[leg.upper];
  const BodyState& shin = s.segments[leg.lower];
  const BodyState& aboveAnkle = s.segments[leg.aboveAnkle()];
  const BodyState& foot = s.segments[leg.foot];
  const double phi = state.stance ? 1.0 : state.progress;

  // Foot placement (§3.1.6): P1 = P_lf + (v − v_d)·s, re-evaluated every step (defect 8), on the
  // ground under it (defect 7: ray cast, not a constant).
  // The thesis's nominal offset is a constant, which suits one speed only: with v = v_d the
  // foot would land the same distance ahead at 0.3 m/s and at 1.5 m/s. It grows here with the
  // desired velocity (footPlacementLead), so that (v − v_d)·s is feedback around a placement
  // that already fits the speed asked for.
  const Vector3d nominal = nominalFootOffset(g.side, p.stepSideways, p.stepForward) +
                           p.footPlacementLead * desiredVelocity_;
  Vector3d p1 = footPlacementTarget(frame.position, yaw, nominal, velocityH, desiredVelocity_ + hold_,
                                    p.footPlacementScale, 0.0);
  // At low speed, towards the capture point of the centre of mass (Coros et al. 2010's inverted-
  // pendulum placement; beyond the thesis): the thesis's placement, tuned for walking, keeps
  // walking at ≈ 0.4 m/s when asked to stop, while a foot placed where the pendulum would come
  // to rest over it brings the body to a stop and steps in place (controller-notes §13).
  const double capture = p.capturePlacement *
                         std::max(0.0, 1.0 - std::abs(desiredVelocity_.z()) / std::max(1e-3, p.captureBlendSpeed));
  if (capture > 0) {
    Vector3d offset = (velocityH - hold_) * std::sqrt(comHeight(s) / 9.81);
    offset.x() += g.side * p.captureSideways;
    offset.y() = 0;
    p1 += capture * (com_ + headingToWorld(yaw, offset) - p1);
  }
  // While turning, outwards from the turn by turnPlacement · h v ω / g (params.h): where the ground
  // force that carries the body round the turn passes through its centre of mass.
  if (params_.turnPlacement > 0 && goal_.turnRate != 0.0) {
    const double speed = std::hypot(velocityH.x(), velocityH.z());
    p1 -= params_.turnPlacement * (comHeight(s) * speed * goal_.turnRate / 9.81) * headingLeft(yaw);
  }
  p1.y() = s.ground.at(p1.x(), p1.z());
  const Vector3d footTarget = swingFootTarget(liftOff_[l], p1, phi, p.swingEase, p.stepHeight,
                                              state.lateStrikeOffset);
  const Vector3d ankleTarget = footTarget + Vector3d(0, g.ankleHeight, 0);

  // Hip and knee by two-link IK (law of cosines) plus PD (§3.1.4); a three-segment leg's hock
  // follows its knee (solveLegIk).
  const Vector3d hip = jointPivot(leg.upper, s);
  const Vector3d forward = headingForward(yaw);
  const LegIk ik = legIk(l, hip, ankleTarget, forward);
  const Quaterniond thighWanted = limbOrientation(ik.thighDir, forward);
  // The PDs may track the trajectory's velocity as well as its position (beyond the thesis,
  // swingTargetRate): with only the position, a PD lags a moving target by k_d/k_p (80 ms at
  // the quadruped's knee) and the foot struck late on every step (controller-notes §11). The
  // targets' rates are their change since the last step. Rate 0 damps the thigh relative to
  // the leg frame, as before.
  SwingTargets& last = swingTargets_[l];
  Vector3d thighRate = frame.angularVelocity;
  double kneeRate = 0.0;
  const double share = k.swingTargetRate;
  if (last.valid && dt > 0 && share > 0) {
    const Eigen::AngleAxisd turn(thighWanted * last.thigh.conjugate());
    const Vector3d rate = clampNorm(turn.axis() * wrapAngle(turn.angle()) / dt, kMaxSwingRate);
    thighRate += share * (rate - thighRate);
    kneeRate = share * std::clamp((ik.kneeFlexion - last.knee) / dt, -kMaxSwingRate, kMaxSwingRate);
  }
  last = {thighWanted, ik.kneeFlexion, true};
  torques[leg.upper] += orientationPd(k.hipKp, k.hipKd, thigh.orientation, thighWanted,
                                      thigh.angularVelocity, thighRate);
  kneePd(l, s, ik.kneeFlexion, torques, kneeRate);

  // Swing virtual force F_sw with gain k_ft(ϕ), K_d = 0.1 K_p (§3.1.4; defect 2), and gravity
  // compensation of the swing leg's segments (§3.1.5), both over the chain leg frame → ankle.
  const Vector3d ankle = jointPivot(leg.foot, s);
  const Vector3d ankleVelocity =
      aboveAnkle.linearVelocity + aboveAnkle.angularVelocity.cross(ankle - aboveAnkle.position);
  const DofChain chain = legChain(l, s);
  const int n = static_cast<int>(m_.segments.size());
  const int aboveAnkleDofs = chain.count - 2;  // every DOF but the ankle's two
  accumulateJointTorques(chain, ankle,
                         swingFootForce(p.footTrackingGain.eval(phi), ankle, ankleVelocity, ankleTarget),
                         torques, n, aboveAnkleDofs);
  SegmentLoad loads[4];
  int loadCount = 0;
  loads[loadCount++] = {m_.segments[leg.upper].mass, thigh.position, 3, 1.0};
  loads[loadCount++] = {m_.segments[leg.lower].mass, shin.position, 4, 1.0};
  if (leg.tarsus >= 0) loads[loadCount++] = {m_.segments[leg.tarsus].mass, aboveAnkle.position, 5, 1.0};
  loads[loadCount++] = {m_.segments[leg.foot].mass, foot.position, chain.count, 1.0};
  accumulateGravityCompensation(chain, loads, loadCount, gravity_, torques, n);

  // Foot: level during swing, to the strike angle after the strike time (§3.1.6).
  footPd(l, s, yaw, phi > lp.strikeTime ? p.strikeAngle : 0.0, k.ankleKp, k.ankleKd, torques);
}

int Controller::legFrameIndex(const body::Leg& leg) const {
  int f = 0;
  while (m_.legFrames[f] != leg.legFrame) ++f;
  return f;
}

Vector3d Controller::jointPivot(int segment, const CharacterState& s) const {
  // Segments start unrotated in the rest pose, so the pivot's rest offset from the segment's
  // centre, turned by the segment's orientation, gives the pivot now.
  const body::Segment& seg = m_.segments[segment];
  const BodyState& b = s.segments[segment];
  return b.position + b.orientation * (seg.joint.pivot - seg.center);
}

DofChain Controller::legChain(int l, const CharacterState& s) const {
  // A leg's DOFs from the leg frame to the foot (§3.1.2): hip (3), knee (1), the hock (1) of a
  // leg of three segments, ankle (2).
  const body::Leg& leg = m_.legs[l];
  const Vector3d hip = jointPivot(leg.upper, s), knee = jointPivot(leg.lower, s),
                 ankle = jointPivot(leg.foot, s);
  DofChain chain;
  chain.push(Vector3d::UnitX(), hip, leg.upper);
  chain.push(Vector3d::UnitY(), hip, leg.upper);
  chain.push(Vector3d::UnitZ(), hip, leg.upper);
  chain.push(s.segments[leg.upper].orientation * Vector3d::UnitX(), knee, leg.lower);
  if (leg.tarsus >= 0)
    chain.push(s.segments[leg.lower].orientation * Vector3d::UnitX(), jointPivot(leg.tarsus, s), leg.tarsus);
  chain.push(s.segments[leg.aboveAnkle()].orientation * Vector3d::UnitX(), ankle, leg.foot);
  chain.push(s.segments[leg.foot].orientation * Vector3d::UnitZ(), ankle, leg.foot);
  return chain;
}

LegIk Controller::legIk(int l, const Vector3d& hip, const Vector3d& ankle, const Vector3d& forward) const {
  const LegGeometry& g = geometry_[l];
  return solveLegIk(hip, ankle, g.thigh, g.shin, g.tarsus, forward * m_.legs[l].kneeBend);
}

void Controller::kneePd(int l, const CharacterState& s, double flexionWanted, Vector3d* torques,
                        double rateWanted) {
  // Knee flexion is the shin's rotation about the thigh's x axis, signed so that bending the
  // way the knee points is positive (kneeBend), §3.1.4 and §3.1.7.
  const body::Leg& leg = m_.legs[l];
  const Hinge knee = hinge(leg.upper, leg.lower, leg.kneeBend, s);
  hingePd(knee, flexionWanted, rateWanted, torques);
  // A three-segment leg's hock follows the knee as it is, not as it is asked to be: bent the
  // other way by as much, at its rate, with its gains. That keeps the tarsus parallel to the thigh
  // (solveLegIk's pantograph) as a pantograph leg's spring does (Sprowitz et al. 2013), while the
  // knee alone takes the stance's compliance. Held instead to the knee's wanted flexion, the hock
  // pushed the stance legs off the ground early: the insect with a 2 cm tarsus walked a 0.4 m/s
  // goal at 0.11 m/s (docs/creatures.md, "Legs of three segments").
  if (leg.tarsus >= 0) hingePd(hinge(leg.lower, leg.tarsus, -leg.kneeBend, s), knee.flexion, knee.rate, torques);
}

Controller::Hinge Controller::hinge(int parent, int child, double bend, const CharacterState& s) const {
  const BodyState& p = s.segments[parent];
  const BodyState& c = s.segments[child];
  Hinge h;
  h.child = child;
  h.bend = bend;
  h.axis = p.orientation * Vector3d::UnitX();
  h.flexion = bend * twistAngle(p.orientation.conjugate() * c.orientation, Vector3d::UnitX());
  h.rate = bend * (c.angularVelocity - p.angularVelocity).dot(h.axis);
  return h;
}

void Controller::hingePd(const Hinge& h, double flexionWanted, double rateWanted, Vector3d* torques) const {
  const JointGains& k = params_.gains;
  torques[h.child] += h.bend * pd(k.kneeKp, k.kneeKd, flexionWanted - h.flexion, rateWanted - h.rate) * h.axis;
}

void Controller::footPd(int l, const CharacterState& s, double yaw, double pitch, double kp,
                        double kd, Vector3d* torques) {
  const body::Leg& leg = m_.legs[l];
  const BodyState& aboveAnkle = s.segments[leg.aboveAnkle()];
  const BodyState& foot = s.segments[leg.foot];
  const Quaterniond wanted = headingQuat(yaw) * Quaterniond(Eigen::AngleAxisd(pitch, Vector3d::UnitX()));
  torques[leg.foot] += orientationPd(kp, kd, foot.orientation, wanted, foot.angularVelocity,
                                     aboveAnkle.angularVelocity);
}

void Controller::limitToSupport(int l, const CharacterState& s, double load, Vector3d* torques) const {
  // A flat foot carrying `load` newtons stays flat while the centre of pressure that balances
  // the ankle torque lies under the sole: pitch torque within load × toe (toes pressed down, +x)
  // and load × heel (−x), roll within load × half the width, twist within what friction holds
  // (taken as load × a quarter of the width). Clamped in the foot's own frame.
  const body::Leg& leg = m_.legs[l];
  const LegGeometry& g = geometry_[l];
  const Quaterniond& q = s.segments[leg.foot].orientation;
  Vector3d local = q.conjugate() * torques[leg.foot];
  local.x() = std::clamp(local.x(), -load * g.heel, load * g.toe);
  local.y() = std::clamp(local.y(), -0.25 * load * g.halfWidth, 0.25 * load * g.halfWidth);
  local.z() = std::clamp(local.z(), -load * g.halfWidth, load * g.halfWidth);
  torques[leg.foot] = q * local;
}

void Controller::spine(const CharacterState& s, Vector3d* torques) {
  // Spine joints hold the rest shape (§3.1.7), and the spine links are held up against gravity
  // through the two leg frames either side of them, with weights that sum to one (§3.1.5;
  // defect 5, defect 6: every link driven, targets are rotations). A body of more than two leg
  // frames has a section of spine between each two (body/creature.h); each is held alike.
  const JointGains& k = params_.gains;
  const int n = static_cast<int>(m_.segments.size());
  size_t first = 0;  // the section's first link in m_.spine
  for (size_t f = 1; f < m_.legFrames.size(); ++f) {
    const int front = m_.legFrames[f - 1], back = m_.legFrames[f];
    // Joints along the section, front to back: its links (the segments between its two leg
    // frames), then the back leg frame.
    int joints[body::kMaxSpineLinks + 1];
    int count = 0;
    for (size_t i = first; i < m_.spine.size() && m_.spine[i] < back; ++i) joints[count++] = m_.spine[i];
    const size_t links = static_cast<size_t>(count);
    joints[count++] = back;
    for (int j = 0; j < count; ++j) jointHold(joints[j], s, Quaterniond::Identity(), k.spineKp, k.spineKd, torques);
    for (size_t li = 0; li < links; ++li) {
      const int link = joints[li];
      const SpineWeights w = spineGravityWeights(s.segments[back].position, s.segments[front].position,
                                                 s.segments[link].position);
      // From the front leg frame: the section's joints up to this link's, crossed parent → child.
      DofChain fromFront;
      for (size_t j = 0; j <= li; ++j) {
        const int child = joints[j];
        const Vector3d b = jointPivot(child, s);
        fromFront.push(Vector3d::UnitX(), b, child);
        fromFront.push(Vector3d::UnitY(), b, child);
        fromFront.push(Vector3d::UnitZ(), b, child);
      }
      SegmentLoad load{m_.segments[link].mass, s.segments[link].position, fromFront.count, w.front};
      accumulateGravityCompensation(fromFront, &load, 1, gravity_, torques, n);
      // From the back leg frame: its joint, then the links back to this one, crossed child → parent.
      DofChain fromBack;
      for (int j = count - 1; j > static_cast<int>(li); --j) {
        const int child = joints[j];
        const Vector3d b = jointPivot(child, s);
        fromBack.push(Vector3d::UnitX(), b, child, true);
        fromBack.push(Vector3d::UnitY(), b, child, true);
        fromBack.push(Vector3d::UnitZ(), b, child, true);
      }
      load = {m_.segments[link].mass, s.segments[link].position, fromBack.count, w.back};
      accumulateGravityCompensation(fromBack, &load, 1, gravity_, torques, n);
    }
    first += links;
  }
}

}  // namespace gaitlab::gait
