// Standing on planted feet (beyond the thesis): at goal speed 0 the character stops stepping and
// stands on all its feet, stepping again only to recover from a push or to walk on.
//
// The thesis's controller (§3.1) has no standing: its gait clock always runs, so at 0 m/s a
// character steps in place. Generalized Biped Walking Control (Coros et al. 2010) stops by
// standing on both feet and steps when balance asks for it. What decides here is the capture
// point (Pratt et al. 2006), x + v·√(h/g), the point over which the inverted pendulum of the
// centre of mass would come to rest: while it lies inside the support polygon of the planted
// feet the body can be held over them; once it leaves, only a step can catch it.
//
// The states (Controller::Stand): Walking → Settling once the goal is 0 and the body has been
// slower than GaitParams::standSpeed for kSettleTime (the gait player holds every foot that
// lands: GaitPlayer::hold) → Planted once every foot is down → Walking when the goal moves, the
// capture point comes within kStepMargin of the support polygon's edge, the body moves faster
// than kStepSpeed, or a foot has been off the ground for kLiftedTime.
//
// How a body on one leg frame (the biped) is held (docs/controller-notes.md, "Standing on
// planted feet"):
// - the legs take one pose: each leg frame upright, at the height it came to rest at, moved to
//   keep the centre of mass over the middle of the feet (a PD on the centre of mass through the
//   pose, kComGain and kComDamping), each leg solved by the swing's two-link IK from its hip in
//   that pose to its planted ankle; the knee tracks the IK's flexion, and the ankle, which
//   walking leaves free (a stance foot is an inverted pendulum's pivot), holds the shin along
//   the IK's direction: the ankle strategy of standing;
// - the hips hold the leg frame upright, as the thesis's stance hips do (eq. 3.4–3.5);
// - the feet are held flat (a foot that starts to tip is pressed back down) and every ankle
//   torque is limited to what the sole can return (limitToSupport);
// - the weight is carried by ground forces shared among the feet by the whole-body least squares
//   (gait/stance_forces.h), delivered through each leg's Jacobian transpose;
// - the feet hold their place on the ground: the physics gives standing feet friction anchors
//   (physics::Character::holdFeet), without which they crept 5 cm/s.
//
// A body on several leg frames (the quadruped) stands as a table (controller-notes, "The
// quadruped stands as a table"): its feet already surround the centre of mass, and balancing on
// its small feet's ankles as the biped does tipped them over. Every leg joint holds the pose it
// came to rest in, by a joint PD (kTableKp, kTableKd), while the weight, shared among the feet by
// the whole-body least squares, is fed forward through each leg's Jacobian transpose, so that
// the PDs only correct. It steps only once the capture point nears the polygon's edge
// (kTableStepMargin), not because the body moves (kStepSpeed): a table held forward and backward
// pushes of 30 N·s, which the speed trigger turned into steps that fell.
#include <algorithm>
#include <cmath>
#include <limits>

#include "gait/controller.h"
#include "gait/heading.h"
#include "gait/ik.h"
#include "gait/pd.h"
#include "gait/stance_forces.h"
#include "gait/virtual_force.h"

namespace gaitlab::gait {

using Eigen::Quaterniond;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// Measured with the biped's standing pushes (held 0.2 s, 20–80 N·s from each side) and 30 s at
// goal 0 (controller-notes, "Standing on planted feet"); each was the best of the values tried.
constexpr double kSettleTime = 0.5;   // s slower than standSpeed before it comes to a stand
constexpr double kStepMargin = 0.04;  // m: it steps once the capture point is this near the edge
constexpr double kStepSpeed = 0.2;    // m/s: ... or once the body moves this fast (held by its
                                      // ankles until the capture point neared the edge, it fell
                                      // to pushes of 40–60 N·s)
constexpr double kLiftedTime = 0.05;  // s: a foot bouncing on landing is still planted
constexpr double kComGain = 4.0;      // the pose moves the body by this × the COM's offset
constexpr double kComDamping = 0.8;   // s: ... less this × its velocity
constexpr double kStep = 1.0 / 120;   // s, the controller's fixed step (physics::kFixedStep)
// The table's joint PD (several leg frames). With the weight fed forward, 100 and 300 stood still
// and 800 crept 0.48 m in 30 s; of 150 / 300 / 500, 300 fell least to sideways pushes (8 runs
// each at 20 and 30 N·s, before the standing key was searched: 12 / 8 / 10 falls). Damping above
// about 3 over-corrects the light feet (0.2 kg) and shins (0.6 kg) within a 1/120 s step, and the
// feet hopped off the ground.
constexpr double kTableKp = 300.0;  // N·m/rad
constexpr double kTableKd = 3.0;    // N·m·s/rad
// The table steps once the capture point is this near the edge. The quadruped's standing key
// pushed sideways 20 times at 25 and 30 N·s, 12 draws each: runs without a fall 0.02 m: 10 and 8
// of 12; 0.04: 5 and 9; 0.055: 10 and 9; 0.06: 11 and 10; 0.07: 10 and 9; 0.085: 8 and 9.
constexpr double kTableStepMargin = 0.06;  // m

Vector2d horizontal(const Vector3d& v) { return Vector2d(v.x(), v.z()); }

}  // namespace

SupportPolygon Controller::supportPolygon(const CharacterState& s) const {
  Vector2d corners[kMaxSupportPoints];
  int n = 0;
  for (size_t l = 0; l < m_.legs.size() && n + 4 <= kMaxSupportPoints; ++l) {
    if (!player_.leg(static_cast<int>(l)).stance) continue;
    const body::Segment& foot = m_.segments[m_.legs[l].foot];
    const BodyState& b = s.segments[m_.legs[l].foot];
    const Vector3d h = foot.halfExtents;
    for (double x : {-h.x(), h.x()})
      for (double z : {-h.z(), h.z()}) corners[n++] = horizontal(b.position + b.orientation * Vector3d(x, -h.y(), z));
  }
  return SupportPolygon::hullOf(corners, n);
}

void Controller::updateStand(const CharacterState& s, const Vector3d& comVelocity) {
  const bool stopped = goal_.speed == 0.0 && desiredVelocity_.z() == 0.0;
  const double speed = horizontal(comVelocity).norm();
  bool allDown = s.footContact != nullptr;
  for (int l = 0; l < player_.legCount() && allDown; ++l) allDown = s.footContact[l];
  switch (stand_) {
    case Stand::Walking:
      // Slow for a while: a stride's pause between two steps is not a stop.
      calm_ = stopped && speed < params_.standSpeed ? calm_ + 1 : 0;
      if (calm_ * kStep >= kSettleTime) {
        player_.hold();
        stand_ = Stand::Settling;
      }
      return;
    case Stand::Settling:
      if (!stopped) release(s, 0);
      if (!stopped || !player_.planted() || !allDown) return;
      stand_ = Stand::Planted;
      lifted_ = 0;
      // It stands as high as it came to rest, in the walk's crouch: a higher stand pushed the
      // body off its feet, which land ahead of it, and rising to it slowly cost the stand pushes
      // and box hits (controller-notes §34).
      for (size_t f = 0; f < m_.legFrames.size(); ++f) {
        const BodyState& frame = s.segments[m_.legFrames[f]];
        standHeight_[f] = frame.position.y() - s.ground.at(frame.position.x(), frame.position.z());
      }
      // And facing where it stopped: a stand does not turn (the hips' twist turns the feet, which
      // friction holds only weakly about the vertical).
      standYaw_ = headingOf(s.segments[m_.legFrames[0]].orientation);
      // The table's pose: each leg joint as it came to rest (several leg frames).
      for (const body::Leg& leg : m_.legs) {
        int segs[4];
        for (int i = 0, n = leg.segments(segs); i < n; ++i)
          standPose_[segs[i]] = s.segments[m_.segments[segs[i]].parent].orientation.conjugate() * s.segments[segs[i]].orientation;
      }
      [[fallthrough]];
    case Stand::Planted: {
      const double h = std::max(0.1, com_.y() - s.ground.at(com_.x(), com_.z()));
      const Vector2d capture = horizontal(com_ + comVelocity * std::sqrt(h / 9.81));
      lifted_ = allDown ? 0 : lifted_ + 1;
      const bool table = standsAsTable();
      if (stopped && lifted_ * kStep < kLiftedTime && (table || speed < kStepSpeed) &&
          supportPolygon(s).inside(capture) > (table ? kTableStepMargin : kStepMargin))
        return;
      // It steps with the foot nearest the capture point: pushed sideways, the foot on that side
      // steps out under the body. A stand that comes to rest on feet too close together to hold
      // it steps on at once.
      int leg = 0;
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t l = 0; l < m_.legs.size(); ++l) {
        const double d = (horizontal(s.segments[m_.legs[l].foot].position) - capture).norm();
        if (d < nearest) nearest = d, leg = static_cast<int>(l);
      }
      release(s, leg);
      return;
    }
    case Stand::Down:  // getting up (gait/get_up.cpp) comes first: update() never gets here
      return;
  }
}

void Controller::release(const CharacterState& s, int leg) {
  player_.release(leg, s.footContact);
  stand_ = Stand::Walking;
  calm_ = 0;
}

int Controller::shareWeight(const CharacterState& s, Vector3d* points, Vector3d* forces) const {
  const int count = std::min(static_cast<int>(m_.legs.size()), kMaxStanceFeet);
  for (int l = 0; l < count; ++l) points[l] = jointPivot(m_.legs[l].foot, s) - Vector3d(0, geometry_[l].ankleHeight, 0);
  distributeStanceForces(com_, -weight_ / 9.81 * gravity_, Vector3d::Zero(), points, count, StanceForceSettings(),
                         forces);
  return count;
}

void Controller::plantedStance(const CharacterState& s, Vector3d* torques) {
  const int segments = static_cast<int>(m_.segments.size());
  const JointGains& k = params_.gains;
  const Quaterniond upright = headingQuat(standYaw_);
  const Vector3d forward = headingForward(standYaw_);

  // Where the centre of mass should be: over the middle of the feet, at rest.
  const Vector2d middle = supportPolygon(s).centroid();
  Vector3d comVelocity = Vector3d::Zero();
  for (int i = 0; i < segments; ++i) comVelocity += m_.segments[i].mass * s.segments[i].linearVelocity;
  comVelocity *= 9.81 / weight_;
  const Vector3d shift(kComGain * (middle.x() - com_.x()) - kComDamping * comVelocity.x(), 0.0,
                       kComGain * (middle.y() - com_.z()) - kComDamping * comVelocity.z());

  // The body's weight, shared among the feet.
  Vector3d points[kMaxStanceFeet], forces[kMaxStanceFeet];
  const int count = shareWeight(s, points, forces);

  int legsOfFrame[kMaxLegFrames] = {};
  for (const body::Leg& leg : m_.legs) ++legsOfFrame[legFrameIndex(leg)];
  for (int l = 0; l < count; ++l) {
    const body::Leg& leg = m_.legs[l];
    const int f = legFrameIndex(leg);
    const int lf = m_.legFrames[f];
    const LegFrameParams& p = params_.legFrames[f];
    const BodyState& frame = s.segments[lf];
    const BodyState& aboveAnkle = s.segments[leg.aboveAnkle()];

    // The pose: this leg frame upright at the height it stands at, moved by the centre of mass's
    // correction; the hip where that puts it; the leg from there to its planted ankle.
    Vector3d framePosition = frame.position + shift;
    framePosition.y() = s.ground.at(framePosition.x(), framePosition.z()) + standHeight_[f];
    const Vector3d hip = framePosition + upright * (m_.segments[leg.upper].joint.pivot - m_.segments[lf].center);
    const LegIk ik = legIk(l, hip, jointPivot(leg.foot, s), forward);

    // Weight: this foot's ground force through the leg's Jacobian transpose, taken at the sole.
    accumulateJointTorques(legChain(l, s), points[l], -forces[l], torques, segments);
    // The hips hold the leg frame upright (eq. 3.4–3.5: the torque it should feel, shared).
    torques[leg.upper] -=
        orientationPd(p.orientationKp, p.orientationKd, frame.orientation, upright, frame.angularVelocity) / legsOfFrame[f];
    // The knee's flexion, and the shin over the planted foot: the ankle's torque on the shin is
    // the opposite of its torque on the foot, which the ground holds.
    kneePd(l, s, ik.kneeFlexion, torques);
    torques[leg.foot] -= orientationPd(k.stanceAnkleKp, k.stanceAnkleKd, aboveAnkle.orientation,
                                       limbOrientation(ik.ankleLimb, forward), aboveAnkle.angularVelocity);
    // The foot flat on the ground, so that a foot that starts to tip is pressed back down; and no
    // more ankle torque than the sole can return.
    footPd(l, s, standYaw_, 0.0, k.stanceAnkleKp, k.stanceAnkleKd, torques);
    limitToSupport(l, s, std::max(0.0, forces[l].y()), torques);
  }
}

void Controller::plantedTable(const CharacterState& s, Vector3d* torques) {
  const int segments = static_cast<int>(m_.segments.size());
  // The body's weight, shared among the feet, fed forward through each leg.
  Vector3d points[kMaxStanceFeet], forces[kMaxStanceFeet];
  const int count = shareWeight(s, points, forces);
  for (int l = 0; l < count; ++l) {
    const body::Leg& leg = m_.legs[l];
    accumulateJointTorques(legChain(l, s), points[l], -forces[l], torques, segments);
    // Every joint of the leg holds the pose it came to rest in.
    int segs[4];
    for (int i = 0, n = leg.segments(segs); i < n; ++i)
      jointHold(segs[i], s, standPose_[segs[i]], kTableKp, kTableKd, torques);
    limitToSupport(l, s, std::max(0.0, forces[l].y()), torques);
  }
}

}  // namespace gaitlab::gait
