#include "gait/speed_keys.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "gait/gait_transition.h"

namespace gaitlab::gait {

// paramsAtSpeed blends two GaitParams double by double at the places the schema gives
// (paramRuns): every field is a double (motion graphs are arrays of them), so the struct is plain
// data, an array of doubles laid out alike in both.
static_assert(std::is_trivially_copyable_v<GaitParams> && std::is_standard_layout_v<GaitParams>,
              "GaitParams must stay plain data of doubles");
static_assert(sizeof(GaitParams) % sizeof(double) == 0, "GaitParams must hold doubles only");

int Gait::keyAt(double speed) const {
  for (size_t i = 0; i < keys.size(); ++i)
    if (std::abs(keys[i].speed - speed) <= 1e-9) return static_cast<int>(i);
  return -1;
}

int Gait::nearestKey(double speed) const {
  const double s = std::abs(speed);
  int best = 0;
  for (size_t i = 1; i < keys.size(); ++i)
    if (std::abs(keys[i].speed - s) < std::abs(keys[best].speed - s)) best = static_cast<int>(i);
  return best;
}

bool Gait::heldAlike(double a, double b) const {
  a = std::abs(a);
  b = std::abs(b);
  if (a == b) return true;
  if (!(a > keys.front().speed) && !(b > keys.front().speed)) return true;  // also NaN, as paramsAtSpeed
  return a >= keys.back().speed && b >= keys.back().speed;
}

Gait Gait::of(SpeedKey primary, std::vector<SpeedKey> others) {
  Gait g;
  const double primarySpeed = primary.speed;
  g.keys = std::move(others);
  g.keys.push_back(std::move(primary));
  std::sort(g.keys.begin(), g.keys.end(), [](const SpeedKey& a, const SpeedKey& b) { return a.speed < b.speed; });
  g.primary = g.keyAt(primarySpeed);
  return g;
}

void paramsAtSpeed(Character c, const Gait& gait, double speed, GaitParams* out) {
  const std::vector<SpeedKey>& keys = gait.keys;
  const double s = std::abs(speed);
  if (keys.size() == 1 || !(s > keys.front().speed)) {  // also NaN
    *out = keys.front().params;
    return;
  }
  if (s >= keys.back().speed) {
    *out = keys.back().params;
    return;
  }
  size_t hi = 1;
  while (keys[hi].speed <= s) ++hi;
  const SpeedKey& a = keys[hi - 1];
  const SpeedKey& b = keys[hi];
  // Between keys of different footfall patterns nothing is blended: the key of the half the
  // speed is in (a gait transition, gait/gait_transition.h).
  const int legs = static_cast<int>(legNames(c).size());
  if (footfallDiffers(a.params.legs, b.params.legs, legs)) {
    *out = s < 0.5 * (a.speed + b.speed) ? a.params : b.params;
    return;
  }
  const double t = (s - a.speed) / (b.speed - a.speed);
  *out = a.params;
  // Every parameter the character uses, run by run (schema.h, paramRuns): this runs in each
  // control step while the desired speed ramps, where a visitor call per field had cost the
  // biped's controller 8 % more instructions per step over the crowd benchmark's start
  // (docs/controller-notes.md §74, bench/cost.mjs).
  const double* x = reinterpret_cast<const double*>(&a.params);
  const double* y = reinterpret_cast<const double*>(&b.params);
  double* v = reinterpret_cast<double*>(out);
  for (const ParamRun& run : paramRuns(c))
    for (int k = run.first; k < run.first + run.count; ++k) v[k] = x[k] + (y[k] - x[k]) * t;
}

}  // namespace gaitlab::gait
