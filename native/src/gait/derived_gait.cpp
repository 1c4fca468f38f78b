#include "gait/derived_gait.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "gait/defaults.h"
#include "gait/schema.h"
#include "gait/speed_keys.h"

namespace gaitlab::gait {

namespace {

// Leg length: hip to ankle at rest.
double legLength(const body::Morphology& m, const body::Leg& leg) {
  return (m.segments[leg.foot].joint.pivot - m.segments[leg.upper].joint.pivot).norm();
}

void scaleGraph(MotionGraph& g, double s) {
  for (double& v : g.knots) v *= s;
}

}  // namespace

GaitParams derivedGait(const body::Morphology& m) {
  const body::Morphology& quadruped = shippedBody(Character::Quadruped);
  GaitParams trot;
  paramsAtSpeed(Character::Quadruped, defaultGait(Character::Quadruped), kDerivedFromSpeed, &trot);
  GaitParams p = trot;
  const int frames = static_cast<int>(m.legFrames.size());
  const double scale = legLength(m, m.legs[0]) / legLength(quadruped, quadruped.legs[0]);
  p.period = trot.period * std::sqrt(scale);
  for (int f = 0; f < frames && f < kMaxLegFrames; ++f) {
    LegFrameParams& lf = p.legFrames[f];
    lf = trot.legFrames[0];
    lf.stepForward *= scale;
    lf.stepSideways *= scale;
    scaleGraph(lf.stepHeight, scale);
    scaleGraph(lf.heightOffset, scale);
  }
  for (size_t l = 0; l < m.legs.size() && l < static_cast<size_t>(kMaxLegs); ++l) {
    const int pair = static_cast<int>(l / 2), side = static_cast<int>(l % 2);
    p.legs[l] = trot.legs[side];  // the quadruped's front leg of that side
    p.legs[l].stepTrigger = 0.5 * ((pair + side) % 2);
    p.legs[l].dutyFactor = kDerivedDutyFactor;
  }
  // Within the schema's bounds, so that what the body walks is a gait file of its kind: a body of
  // shorter legs than the quadruped's would step faster than the shortest period (0.3 s) allows.
  const Character c = characterOf(m);
  std::vector<double> v = toVector(c, p);
  clampToBounds(c, &v);
  fromVector(c, v, &p);
  return p;
}

}  // namespace gaitlab::gait
