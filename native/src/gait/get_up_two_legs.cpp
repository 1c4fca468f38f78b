// Getting up on two legs (beyond the thesis; Coros et al. 2011 list getting up among their dog's
// skills): the biped, which has no arms to rise on, rolls onto its back and kips up onto its feet.
//
// Legs alone do not lift this body from its front: a tuck reaches a knee-chest position, and
// neither extending the hips nor pressing the knees into their fold carries the hips back over the
// heels (docs/controller-notes.md, "A get-up for the biped"). From its back they can throw it up:
// the legs swing up over the body, are whipped down with the knees folding, and the body follows
// them up onto its feet, the kip-up of gymnasts and martial artists. So the body first gets onto
// its back. What the legs do is a routine of keyframes (get_up_two_legs.h), one per way it lies:
//   - on its back (the torso's forward axis more than 37° above the horizontal): the kip-up;
//   - on its front, or face down with its hips raised over folded legs (the torso's up axis
//     pointing down), a roll onto its back over its head;
//   - on a side: a roll onto its back, the legs named by the side nearer the ground, so that one
//     routine serves both sides;
//   - sitting or otherwise upright, none: the legs relax, and it lies back.
// A routine starts once the body lies still (kStillChord) and runs to its end; then the way the
// body lies picks again, so a kip-up that falls back is tried again. At the top of a kip-up (the
// torso upright within acos kHandOverUp, its centre above kHandOverHeight) it hands over to the
// walk, which steps to catch the landing and starts from rest, as from a stop, towards the goal:
// at goal 0 it then comes to a stand (standing.cpp).
//
// The keyframes were found by CMA-ES (Hansen 2016). First from the body laid down still on its
// back, front or left side, rolled up to 10° either way about its long axis, scored by how high
// and upright its torso stood at the end (the rolls: how squarely it lay on its back). Then the
// kip-up and the roll from the front again, from 138 moments at which the box-hit trial's throws
// knocked it over (its bodies' states at the fall), each run as the whole get-up runs for the 10 s
// the benchmark watches, scored by how high and upright it stood at the end. The controller notes
// (§79, §80) give the searches, the probes that repeat them (native/probes/getup_search.cpp,
// getup_log.cpp) and what the get-up gets up from.
#include <algorithm>
#include <cmath>

#include "gait/controller.h"
#include "gait/get_up_two_legs.h"

namespace gaitlab::gait {

using Eigen::AngleAxisd;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

// Still: the torso's up and forward axes moved less than this (as a chord) over kStillTime. Its
// angular velocity is no measure: resting on the ground it reads several rad/s the contacts cancel.
constexpr double kStillTime = 0.2;  // s
constexpr double kStillChord = 0.2;
constexpr double kOnBack = 0.6, kOnFront = -0.6;  // the forward axis's height, on its back / front
constexpr double kUpright = 0.5;                  // the up axis's height above which it is not lying
constexpr double kHeadDown = -0.5;  // the up axis's height below which it lies face down, hips raised
constexpr double kHandOverUp = 0.9, kHandOverHeight = 0.8;  // up axis's height; torso's centre, m

// The PDs' gains at gain 1 (N·m/rad, N·m·s/rad). The foot's are small: a 1 kg foot's PD
// stiffer than about 60 / 1 is unstable at the physics' 120 Hz.
constexpr double kHipKp = 800, kHipKd = 40, kKneeKp = 500, kKneeKd = 25, kFootKp = 40, kFootKd = 0.6;

// While it waits to lie still: the legs relaxed and nearly straight.
constexpr GetUpKey kRelaxed = {1.0, 0.5, {0, 0}, {0.2, 0.2}, {0, 0}, {0, 0}, {0, 0}};

// The routines: seconds, gain, then per leg hip, knee, ankle, twist, outwards (get_up_two_legs.h).
// From its back, the kip-up: the legs fold (0.5 s), swing up over the body (1.3 s), are whipped
// down with the knees folding (0.22 s, stiff), and reach for the ground.
constexpr GetUpKey kKipUp[] = {
    {0.51390, 0.36351, {1.38336, 0.84955}, {1.16965, 1.33758}, {-0.36703, -0.56106}, {0, 0}, {0, 0}},
    {1.26646, 0.46492, {1.55780, 1.92133}, {0.24862, 0.55179}, {0.13222, -0.60010}, {0, 0}, {0, 0}},
    {0.22422, 1.43393, {-0.26991, 0.55716}, {2.33424, 1.53945}, {-0.29144, 0.47436}, {0, 0}, {0, 0}},
    {1.21821, 0.37417, {0.70500, 1.08010}, {0.54527, 0.99357}, {-0.59172, -0.87561}, {0, 0}, {0, 0}},
    {0.33175, 0.40007, {1.70398, -0.53312}, {1.60785, 0.95000}, {-0.85207, 0.77221}, {0, 0}, {0, 0}},
};
// From its front: one leg swung forwards and the other folded, then both tucked, which tips the
// body over its head onto its back.
constexpr GetUpKey kRollFromFront[] = {
    {0.30837, 1.16767, {0.34239, -0.44373}, {0.22427, 2.37816}, {-0.85401, 0.42337}, {0, 0}, {0, 0}},
    {0.43581, 0.72337, {0.16094, 1.54986}, {1.26059, 0.84806}, {-0.00490, -0.61637}, {0, 0}, {0, 0}},
    {0.99039, 1.98635, {1.97415, -0.68462}, {0.14557, 0.66015}, {-0.65486, 0.29668}, {0, 0}, {0, 0}},
    {0.22822, 0.33044, {0.96313, 0.62971}, {2.38673, 1.81828}, {0.46548, 0.16224}, {0, 0}, {0, 0}},
};
// From a side ([0] the lower leg): the legs scissor and fold, rolling the body onto its back.
constexpr GetUpKey kRollFromSide[] = {
    {0.67647, 1.42082, {1.87879, -0.54304}, {1.49664, 0.24677}, {0.61987, -0.53776}, {-0.31885, 0.29054}, {0.52551, 0.54307}},
    {1.14632, 1.01686, {-0.60234, 0.68861}, {0.20579, 1.78182}, {-0.03777, 0.34881}, {0.17088, 0.18968}, {0.18590, 0.19166}},
    {0.90329, 0.69566, {1.71319, 0.72401}, {1.96397, 1.97221}, {-0.54708, 0.58655}, {-0.34846, -0.47195}, {0.43706, 0.45760}},
};

template <int N>
GetUpRoutine routineOf(const GetUpKey (&keys)[N], bool bySide) {
  return GetUpRoutine{keys, N, bySide};
}

}  // namespace

GetUpRoutine defaultGetUpRoutine(Lying lying) {
  switch (lying) {
    case Lying::OnBack: return routineOf(kKipUp, false);
    case Lying::OnFront: return routineOf(kRollFromFront, false);
    case Lying::OnSide: return routineOf(kRollFromSide, true);
  }
  return {};
}

void Controller::getUpOnTwoLegs(const CharacterState& s, double dt, Vector3d* torques) {
  const BodyState& torso = s.segments[m_.legFrames[0]];
  const Vector3d up = torso.orientation * Vector3d::UnitY(), forward = torso.orientation * Vector3d::UnitZ();
  const double height = torso.position.y() - s.ground.at(torso.position.x(), torso.position.z());
  if (lying_ == Lying::OnBack && up.y() > kHandOverUp && height > kHandOverHeight) {
    // The top of a kip-up: the walk takes over, stepping from rest, the higher foot first. The
    // body is still rising and moving, and the stand's planted feet (standing.cpp) did not hold
    // that landing: of 133 box-hit falls at goal 0, 60 stood at the end of the watch handed to
    // them, 116 stepping. At a goal of 0.5 m/s, walking on at once at the goal stood 67, from a
    // desired speed of 0 ramped up as after a stop 87 (controller-notes §80).
    int first = 0;
    for (size_t l = 1; l < m_.legs.size(); ++l)
      if (s.segments[m_.legs[l].foot].position.y() > s.segments[m_.legs[first].foot].position.y()) first = static_cast<int>(l);
    player_.hold();  // release() restarts a held gait player's cycle at `first`'s lift-off
    release(s, first);
    desiredVelocity_.setZero();
    speedTrim_ = 0;
    meanSpeedError_ = 0;
    downSteps_ = 0;
    lying_.reset();
    return;
  }
  if (!lying_) {
    bool still = false;
    if (++stillSteps_ * dt >= kStillTime) {
      still = (forward - stillForward_).norm() < kStillChord && (up - stillUp_).norm() < kStillChord;
      stillForward_ = forward;
      stillUp_ = up;
      stillSteps_ = 0;
    }
    if (still) {
      if (forward.y() > kOnBack) lying_ = Lying::OnBack;
      else if (forward.y() < kOnFront || up.y() < kHeadDown) lying_ = Lying::OnFront;
      else if (up.y() < kUpright) lying_ = Lying::OnSide;
      if (lying_ && getUpRoutine(*lying_).count == 0) lying_.reset();
      routineSteps_ = 0;
    }
  }
  const GetUpKey* key = &kRelaxed;
  bool bySide = false;
  if (lying_) {
    const GetUpRoutine& r = getUpRoutine(*lying_);
    const double t = (routineSteps_++) * dt;
    int k = 0;
    double start = 0;
    while (k < r.count && t > start + r.keys[k].seconds) start += r.keys[k++].seconds;
    if (k == r.count) {  // done: the way it lies picks again once it is still
      lying_.reset();
      stillSteps_ = 0;
    } else {
      key = &r.keys[k];
      bySide = r.bySide;
    }
  }
  const double lowerSide = (torso.orientation * Vector3d::UnitX()).y() < 0 ? 1.0 : -1.0;  // +1 the left
  const double kp = key->gain, kd = std::sqrt(key->gain);
  for (size_t l = 0; l < m_.legs.size(); ++l) {
    const body::Leg& leg = m_.legs[l];
    const double side = geometry_[l].side;  // +1 left
    const int i = bySide ? (side == lowerSide ? 0 : 1) : (side > 0 ? 0 : 1);
    const Quaterniond hip(AngleAxisd(side * key->outwards[i], Vector3d::UnitZ()) *
                          AngleAxisd(-key->hip[i], Vector3d::UnitX()) *
                          AngleAxisd(side * key->twist[i], Vector3d::UnitY()));
    jointHold(leg.upper, s, hip, kHipKp * kp, kHipKd * kd, torques);
    jointHold(leg.lower, s, Quaterniond(AngleAxisd(key->knee[i] * leg.kneeBend, Vector3d::UnitX())), kKneeKp * kp,
              kKneeKd * kd, torques);
    jointHold(leg.foot, s, Quaterniond(AngleAxisd(key->ankle[i], Vector3d::UnitX())), kFootKp * kp, kFootKd * kd,
              torques);
  }
  clampTorques(torques);
}

}  // namespace gaitlab::gait
