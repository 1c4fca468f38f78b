#include "gait/gait_transition.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::gait {

namespace {

constexpr double kTwoPi = 6.283185307179586;

}  // namespace

double cyclicDistance(double a, double b) { return std::abs(std::remainder(a - b, 1.0)); }

bool footfallDiffers(const LegParams* a, const LegParams* b, int legs) {
  for (int i = 1; i < std::min(legs, kMaxLegs); ++i) {
    const double ra = a[i].stepTrigger - a[0].stepTrigger;
    const double rb = b[i].stepTrigger - b[0].stepTrigger;
    if (cyclicDistance(ra, rb) > kFootfallTolerance) return true;
  }
  return false;
}

bool phaseReached(double before, double after, double at) {
  if (after >= before) return before < at && at <= after;
  return at > before || at <= after;  // wrapped
}

double transitionPhaseShift(const LegParams* from, const LegParams* to, int legs) {
  double c = 0, s = 0;
  for (int i = 0; i < std::min(legs, kMaxLegs); ++i) {
    const double move = kTwoPi * (to[i].stepTrigger - from[i].stepTrigger);
    c += std::cos(move);
    s += std::sin(move);
  }
  if (c == 0 && s == 0) return 0;  // moves that cancel: no mean to follow
  return std::atan2(s, c) / kTwoPi;
}

}  // namespace gaitlab::gait
