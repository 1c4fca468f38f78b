// Getting up after a fall (beyond the thesis; Coros et al. 2011 list getting up among their
// dog's skills): a body on several leg frames that the walking criteria would call fallen stops
// walking, rolls onto its belly, rises onto its feet and then stands (gait/standing.cpp) or walks
// on with its goal.
//
// The quadruped's leg frames are boxes, its hips swing sideways only ±0.35 rad, and lying on its
// side its legs all point the way it has to roll: a foot pressed into the ground there rolls the
// body back onto its side (docs/controller-notes.md, "Getting up"). What rolls it is each leg
// frame's roll about the body's long axis, read every step, choosing one pose per leg:
//   - on its back: every leg swung towards the lower side;
//   - on its side, resting on the back's edge: every leg held out towards the belly, the body's
//     weight moved that way, which tips it onto the flat of its side;
//   - on its side, resting on the belly's edge: the lower legs fold each foot over the back and
//     press it into the ground behind the body (hip swung to its limit, knee folded, the hip's
//     sideways swing into the ground), which lifts the back and rolls the body towards its belly;
//     the upper legs tuck, so that no foot held out props the body on the side it rolls to;
//   - up (rolled less than kUpRoll, down again past kDownRoll): legs under the body, wide and
//     crouched, the knees levelling the leg frame; once every leg frame is up, they straighten
//     into a stance over kStandTime.
// The spine twists each section against its limits so that the leg frames do not roll as one:
// while the one ahead is down the one behind leads it by kSpineTwist towards upright; once the one
// ahead is up the one behind follows it by as much; and while either is down it arches its back.
// Every joint is a PD towards its pose; the poses press against the joints' own limits (the hip's
// fold and sideways swing, the knee's flexion: LegGeometry). The numbers were found by a search
// over these poses (the controller notes give it and its validation).
//
// A body on one leg frame, which carries one pair of legs (the biped), has no such poses: it rolls
// onto its back and kips up (get_up_two_legs.cpp).
#include <algorithm>
#include <cmath>

#include "gait/controller.h"
#include "gait/fall.h"
#include "gait/heading.h"
#include "gait/pd.h"

namespace gaitlab::gait {

using Eigen::AngleAxisd;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

constexpr double kDownAfter = 0.3;   // s fallen before it stops walking and gets up
constexpr double kOnFeetFor = 0.5;   // s standing, straightened, before it hands over to the stand
constexpr double kDegree = kPi / 180.0;

// The leg frame's roll (0 upright, 90° on a side, 180° on its back) that switches the poses.
constexpr double kUpRoll = 65.0 * kDegree;         // up below this...
constexpr double kDownRoll = 75.0 * kDegree;       // ... and down again above this
constexpr double kBackEdgeRoll = 90.2 * kDegree;   // on the back's edge of its side above this
constexpr double kOnBackRoll = 123.4 * kDegree;    // on its back above this

constexpr double kPushKnee = 2.35;  // rad, a pushing leg's knee
constexpr double kPushTwist = -0.13;  // rad, a pushing leg's hip twist (signed by knee and side)
constexpr double kTuck = 0.95;        // share of the fold of a tucked leg's hip and knee
constexpr double kHeldOutKnee = 1.13;  // rad, legs held out towards the belly
constexpr double kOnBackKnee = 0.2;    // rad, legs swung to the side on its back
constexpr double kCrouchAbduct = 0.225;  // rad, the crouch's feet outwards
constexpr double kCrouchKnee = 1.885;    // rad, the crouch's knees
constexpr double kStandDelay = 0.3;      // s every leg frame up before the legs straighten
constexpr double kStandTime = 0.8;       // s to straighten
constexpr double kStandKnee = 0.3;       // rad, the knees straightened
// Up, the knees level the leg frame: each lower-side knee straightens, each upper-side one bends,
// by this much per radian of roll, at most kLevelMax (rad).
constexpr double kLevelKnee = 1.0, kLevelMax = 0.1;
constexpr double kSpineTwist = 0.192;    // rad per spine joint (beyond its limit: pressed against it)
constexpr double kSpineArch = 0.4;       // rad per spine joint, likewise
constexpr double kHipKp = 377.0, kHipKd = 3.0;    // N·m/rad, N·m·s/rad
constexpr double kFootKp = 20.0, kFootKd = 0.5;   // the foot held in line with the shin

}  // namespace

bool Controller::isDown(const CharacterState& s) const {
  for (int lf : m_.legFrames) {
    const BodyState& b = s.segments[lf];
    if (legFrameFallen(m_.segments[lf], b.position, b.orientation, s.ground.at(b.position.x(), b.position.z())))
      return true;
  }
  return false;
}

bool Controller::getsUp(const CharacterState& s, double dt, Vector3d* torques) {
  if (stand_ != Stand::Down) {
    downSteps_ = isDown(s) ? downSteps_ + 1 : 0;
    if (downSteps_ * dt < kDownAfter) return false;
    stand_ = Stand::Down;
    onFeetSteps_ = 0;
    risenSteps_ = 0;
    for (bool& up : frameUp_) up = false;
    lying_.reset();
    stillSteps_ = 0;
    stillForward_ = stillUp_ = Vector3d::Zero();
  }
  if (standsAsTable()) getUp(s, dt, torques);
  else getUpOnTwoLegs(s, dt, torques);
  return true;
}

void Controller::getUp(const CharacterState& s, double dt, Vector3d* torques) {
  // Each leg frame's roll about the body's long axis: +90° on its left side, ±180° on its back.
  const int frames = static_cast<int>(m_.legFrames.size());
  double roll[kMaxLegFrames];
  for (int f = 0; f < frames; ++f) {
    const Quaterniond& q = s.segments[m_.legFrames[f]].orientation;
    roll[f] = std::atan2(-(q * Vector3d::UnitX()).y(), (q * Vector3d::UnitY()).y());
    if (std::abs(roll[f]) < kUpRoll) frameUp_[f] = true;
    if (std::abs(roll[f]) > kDownRoll) frameUp_[f] = false;
  }
  bool allUp = true;
  for (int f = 0; f < frames; ++f) allUp = allUp && frameUp_[f];
  risenSteps_ = allUp ? risenSteps_ + 1 : 0;
  const double stand = std::clamp((risenSteps_ * dt - kStandDelay) / kStandTime, 0.0, 1.0);

  // The spine, section by section (a child's twist θ about z rolls it by −θ against its parent).
  for (int f = 1; f < frames; ++f) {
    double twist = 0;
    if (!frameUp_[f - 1]) twist = std::copysign(kSpineTwist, roll[f - 1]);
    else if (!frameUp_[f]) twist = -std::copysign(kSpineTwist, roll[f]);
    const double arch = frameUp_[f - 1] && frameUp_[f] ? 0.0 : kSpineArch;
    const Quaterniond target(AngleAxisd(twist, Vector3d::UnitZ()) * AngleAxisd(arch, Vector3d::UnitX()));
    for (int seg : m_.spine)
      if (seg > m_.legFrames[f - 1] && seg < m_.legFrames[f])
        jointHold(seg, s, target, params_.gains.spineKp, params_.gains.spineKd, torques);
    jointHold(m_.legFrames[f], s, target, params_.gains.spineKp, params_.gains.spineKd, torques);
  }

  for (size_t l = 0; l < m_.legs.size(); ++l) {
    const body::Leg& leg = m_.legs[l];
    const LegGeometry& g = geometry_[l];
    const double side = g.side;  // +1 left
    const int f = legFrameIndex(leg);
    const double r = std::abs(roll[f]);
    const bool lower = side == (roll[f] > 0 ? 1.0 : -1.0);  // on the side nearer the ground
    // The hip's pose: its sideways swing (outwards positive), forward swing and twist.
    double outwards = 0, swing = 0, twist = 0, knee = 0;
    if (frameUp_[f]) {
      outwards = kCrouchAbduct;
      // The legs on the lower side straighten and those on the upper side bend, levelling the leg
      // frame: on a slope the stand could not hold the tilt left over and fell again.
      const double level = std::clamp(kLevelKnee * roll[f], -kLevelMax, kLevelMax);
      knee = (1 - stand) * kCrouchKnee + stand * kStandKnee - level * side;
      knee = std::clamp(knee, 0.0, g.kneeFlexion);
    } else if (r >= kOnBackRoll) {
      outwards = lower ? g.hipSideways : -g.hipSideways;
      knee = kOnBackKnee;
    } else if (r >= kBackEdgeRoll) {
      knee = kHeldOutKnee;
    } else if (lower) {
      // Folded over the back, the foot points up the body: swinging the hip inwards presses it
      // outwards, into the ground.
      swing = g.hipFold;
      knee = kPushKnee;
      outwards = -g.hipSideways;
      twist = kPushTwist * leg.kneeBend * side;
    } else {
      swing = -kTuck * g.hipFold;
      knee = kTuck * g.kneeFlexion;
    }
    const Quaterniond hip(AngleAxisd(side * outwards, Vector3d::UnitZ()) * AngleAxisd(swing, Vector3d::UnitX()) *
                          AngleAxisd(twist, Vector3d::UnitY()));
    jointHold(leg.upper, s, hip, kHipKp, kHipKd, torques);
    kneePd(static_cast<int>(l), s, knee, torques);
    jointHold(leg.foot, s, Quaterniond::Identity(), kFootKp, kFootKd, torques);
  }

  // On its feet: straightened, and no longer fallen, for kOnFeetFor: it stands, holding every foot
  // that lands (standing.cpp), and walks on if its goal moves.
  onFeetSteps_ = stand == 1.0 && !isDown(s) ? onFeetSteps_ + 1 : 0;
  if (onFeetSteps_ * dt >= kOnFeetFor) {
    stand_ = Stand::Settling;
    player_.hold();
    downSteps_ = 0;
  }
  clampTorques(torques);
}

}  // namespace gaitlab::gait
