#include "gait/gait_transition.h"

#include "gait/gait_player.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::gait {

namespace {

constexpr double kTwoPi = 6.283185307179586;

}  // namespace

double cyclicDistance(double a, double b) { return std::abs(std::remainder(a - b, 1.0)); }

double footfallDistance(const LegParams* a, const LegParams* b, int legs) {
  // Each leg's trigger move b − a, as a point on the cycle. A shift δ of the whole pattern moves
  // every point by δ, so the best shift centres the shortest arc that holds them all, and the
  // farthest leg is then half that arc away: (1 − the widest gap between neighbouring points) / 2.
  const int n = std::min(legs, kMaxLegs);
  if (n < 2) return 0;
  double moves[kMaxLegs];
  for (int i = 0; i < n; ++i) moves[i] = GaitPlayer::legPhase(b[i].stepTrigger, a[i].stepTrigger);  // in [0, 1)
  std::sort(moves, moves + n);
  double widestGap = 1.0 - (moves[n - 1] - moves[0]);  // across the cycle's start
  for (int i = 1; i < n; ++i) widestGap = std::max(widestGap, moves[i] - moves[i - 1]);
  return (1.0 - widestGap) / 2;
}

bool footfallDiffers(const LegParams* a, const LegParams* b, int legs) {
  const int n = std::min(legs, kMaxLegs);
  if (footfallDistance(a, b, n) > kFootfallTolerance) return true;
  if (n <= 2) return false;  // one pair of legs: walk and run blend (gait_transition.h)
  return walks(a, n) != walks(b, n);
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
