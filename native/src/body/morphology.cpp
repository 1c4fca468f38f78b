// The two characters, with real-world proportions and masses (not the original implementation's "scale 2"
// boxes, docs/original-implementation.md): a 59 kg human-sized biped (hip height 0.91 m) and a 33 kg dog-sized quadruped
// (shoulder height 0.49 m, leg frames 0.8 m apart, a 4-link spine as in the thesis).
// Proportions: thigh ≈ shin ≈ 0.245 × stature (Winter, Biomechanics of Human Movement);
// segment masses ≈ 10 % (thigh), 4.7 % (shank), 1.5 % (foot) of body mass, trunk + head + arms
// lumped into the leg frame, which is what the thesis's biped does as well.
#include "body/morphology.h"

namespace gaitlab::body {

namespace {

constexpr double kPi = 3.14159265358979323846;

Joint hinge(const Vector3d& pivot, double lo, double hi) {
  Joint j;
  j.type = JointType::Hinge;
  j.pivot = pivot;
  j.axes = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  j.lower = {lo, 0, 0};
  j.upper = {hi, 0, 0};
  return j;
}

// Sagittal pitch (about x) then roll (about z).
Joint universal(const Vector3d& pivot, double pitch, double roll) {
  Joint j;
  j.type = JointType::Universal;
  j.pivot = pivot;
  j.axes = {Vector3d::UnitX(), Vector3d::UnitZ(), Vector3d::UnitY()};
  j.lower = {-pitch, -roll, 0};
  j.upper = {pitch, roll, 0};
  return j;
}

Joint ball(const Vector3d& pivot, const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  Joint j;
  j.type = JointType::Ball;
  j.pivot = pivot;
  j.lower = lo;
  j.upper = hi;
  return j;
}

struct LegDims {
  double upper, lower;          // segment lengths
  double upperR, lowerR;        // half thickness
  Vector3d foot;                // foot half extents
  double footForward;           // foot centre ahead of the ankle
  double mUpper, mLower, mFoot;
};

// Appends upper leg, lower leg and foot hanging straight down from `hip`; returns the Leg.
Leg addLeg(Morphology& m, const std::string& name, int legFrame, const Vector3d& hip,
           const LegDims& d, double kneeBend, const Joint& hipJoint, unsigned rgba) {
  const double ankleY = hip.y() - d.upper - d.lower;
  const Vector3d knee(hip.x(), hip.y() - d.upper, hip.z());
  const Vector3d ankle(hip.x(), ankleY, hip.z());
  Leg leg;
  leg.name = name;
  leg.legFrame = legFrame;
  leg.kneeBend = kneeBend;

  Joint hj = hipJoint;
  hj.pivot = hip;
  leg.upper = static_cast<int>(m.segments.size());
  m.segments.push_back({name + ".upper", {d.upperR, d.upper / 2, d.upperR}, d.mUpper,
                        {hip.x(), hip.y() - d.upper / 2, hip.z()}, legFrame, hj, rgba});
  // Knee flexion: a positive angle about +x swings the lower leg backwards (human knee);
  // kneeBend = -1 mirrors the range for legs whose knee points backwards.
  const double flexLo = kneeBend > 0 ? -0.05 : -2.4, flexHi = kneeBend > 0 ? 2.4 : 0.05;
  leg.lower = static_cast<int>(m.segments.size());
  m.segments.push_back({name + ".lower", {d.lowerR, d.lower / 2, d.lowerR}, d.mLower,
                        {hip.x(), ankleY + d.lower / 2, hip.z()}, leg.upper,
                        hinge(knee, flexLo, flexHi), rgba});
  leg.foot = static_cast<int>(m.segments.size());
  m.segments.push_back({name + ".foot", d.foot, d.mFoot,
                        {hip.x(), d.foot.y(), hip.z() + d.footForward}, leg.lower,
                        universal(ankle, 0.9, 0.4), 0x3a3a40ffu});
  return leg;
}

}  // namespace

double Morphology::totalMass() const {
  double m = 0;
  for (const Segment& s : segments) m += s.mass;
  return m;
}

double Morphology::standingHeight() const { return segments[legFrames[0]].center.y(); }

Morphology makeBiped() {
  Morphology m;
  m.name = "biped";
  const LegDims d{0.42, 0.42, 0.06, 0.05, {0.05, 0.03, 0.12}, 0.04, 7.0, 3.5, 1.0};
  const double hipY = 2 * d.foot.y() + 0.01 + d.lower + d.upper;  // 0.91 m
  // Leg frame: pelvis and trunk as one body (thesis Figure 3.1a), hips at its lower edge.
  m.segments.push_back({"legframe", {0.17, 0.28, 0.11}, 36.0, {0, hipY + 0.25, 0}, -1, Joint{},
                        0xd9734eff});
  m.legFrames = {0};
  m.armature = 0.05;
  // Hip ranges (flexion is negative about +x: the thigh swings forward).
  const Joint hip = ball(Vector3d::Zero(), {-2.0, -0.6, -0.5}, {0.7, 0.6, 0.5});
  m.legs.push_back(addLeg(m, "left", 0, {0.09, hipY, 0}, d, +1, hip, 0x4e8fd9ff));
  m.legs.push_back(addLeg(m, "right", 0, {-0.09, hipY, 0}, d, +1, hip, 0x5fb36bff));
  return m;
}

Morphology makeQuadruped() {
  Morphology m;
  m.name = "quadruped";
  const LegDims d{0.22, 0.22, 0.035, 0.03, {0.035, 0.02, 0.05}, 0.015, 1.2, 0.6, 0.2};
  const double hipY = 2 * d.foot.y() + 0.005 + d.lower + d.upper;  // 0.485 m
  const double frameY = hipY + 0.04, halfLength = 0.40;
  m.segments.push_back({"legframe.front", {0.12, 0.09, 0.12}, 9.0, {0, frameY, halfLength}, -1,
                        Joint{}, 0xd9734eff});
  // A 4-link spine from the front leg frame to the back one (thesis §3.1, ±0.05π per axis).
  const double lim = 0.05 * kPi;
  const double spineFront = halfLength - 0.12, link = 2 * spineFront / 4;
  int parent = 0;
  for (int i = 0; i < 4; ++i) {
    const double zFront = spineFront - i * link;
    m.segments.push_back({"spine." + std::to_string(i), {0.075, 0.06, link / 2}, 2.0,
                          {0, frameY, zFront - link / 2}, parent,
                          ball({0, frameY, zFront}, {-lim, -lim, -lim}, {lim, lim, lim}),
                          0xc9a25aff});
    parent = static_cast<int>(m.segments.size()) - 1;
    m.spine.push_back(parent);
  }
  const int back = static_cast<int>(m.segments.size());
  m.segments.push_back({"legframe.back", {0.11, 0.08, 0.11}, 8.0, {0, frameY, -halfLength}, parent,
                        ball({0, frameY, -spineFront}, {-lim, -lim, -lim}, {lim, lim, lim}),
                        0xd9734eff});
  m.legFrames = {0, back};
  m.armature = 0.05;
  const Joint hip = ball(Vector3d::Zero(), {-1.2, -0.3, -0.35}, {1.2, 0.3, 0.35});
  // Front knees (elbow/carpus) point backwards, hind knees (stifle) forwards.
  m.legs.push_back(addLeg(m, "front.left", 0, {0.09, hipY, halfLength}, d, -1, hip, 0x4e8fd9ff));
  m.legs.push_back(addLeg(m, "front.right", 0, {-0.09, hipY, halfLength}, d, -1, hip, 0x5fb36bff));
  m.legs.push_back(addLeg(m, "back.left", back, {0.09, hipY, -halfLength}, d, +1, hip, 0x4e8fd9ff));
  m.legs.push_back(addLeg(m, "back.right", back, {-0.09, hipY, -halfLength}, d, +1, hip, 0x5fb36bff));
  return m;
}

}  // namespace gaitlab::body
