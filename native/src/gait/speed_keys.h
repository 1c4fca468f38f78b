// A gait over a range of speeds: key parameter sets, each tuned at one speed, blended by the
// desired speed.
//
// One parameter set walks well only near the speed it was tuned at (the biped's preset, tuned at
// 0.5 and 1.0 m/s, falls from 1.6 m/s: docs/controller-notes.md). Coros et al. (2011) give one
// dog many gaits, each a set of controller parameters for a speed, and move between them by
// interpolating the parameters; Coros et al. (2010) vary theirs continuously with the speed asked
// for. This is that mechanism, and the only one: a gait is one or more keys (speed, parameters),
// and the parameters in effect are every schema field interpolated linearly in the desired speed
// between the two keys around it, held at the first key's below it and at the last key's above.
// With one key a gait is exactly the parameter set it holds (every gait file before schema 4).
//
// A key holds every field, footfall pattern included (step triggers, duty factors, period), so a
// key may be a different gait (a run beside a walk, a walk below a trot) and moving between keys
// is a change in mid-stride: between keys of one footfall pattern the gait player keeps its phase
// and takes the blended period and schedule step by step; between keys of different patterns
// nothing is blended and the gait changes at the middle speed (gait/gait_transition.h).
#pragma once
#include <vector>

#include "gait/params.h"
#include "gait/schema.h"

namespace gaitlab::gait {

// Most keys a gait may have (each is a whole parameter set, ~4 kB in a file, ~1,600 characters in a link).
// Coros et al. (2011) give their dog six gaits; with a stand and several keys for the trot's
// speeds a quadruped needs about ten.
constexpr int kMaxSpeedKeys = 12;

struct SpeedKey {
  double speed = 0;  // m/s, the desired forward speed this parameter set is tuned for
  GaitParams params;
};

struct Gait {
  // By strictly increasing speed, at least one.
  std::vector<SpeedKey> keys;
  // The key a gait file names "params": the one the editors and parameter patches edit and the
  // optimiser tunes unless told otherwise.
  int primary = 0;

  static Gait single(const GaitParams& params, double speed = 0.0) { return Gait{{{speed, params}}, 0}; }
  const GaitParams& primaryParams() const { return keys[primary].params; }
  GaitParams& primaryParams() { return keys[primary].params; }
  // The key tuned at `speed` (within 1e-9 m/s), or -1.
  int keyAt(double speed) const;
  // The key whose speed is nearest |speed| (the slower of two as near): the one a walk at that
  // goal uses most.
  int nearestKey(double speed) const;
  // Whether paramsAtSpeed gives the same parameters at speeds `a` and `b`: both at or below the
  // first key's speed, or both at or above the last's (held there), or the same speed.
  bool heldAlike(double a, double b) const;
  // The gait of `primary` and `others` (speeds distinct), its keys put in speed order.
  static Gait of(SpeedKey primary, std::vector<SpeedKey> others);
};

// The parameters in effect at desired speed `speed` (its magnitude: a gait has no keys for walking
// backwards): the keys' values linear in speed between the two keys around it (or, if their
// footfall patterns differ, the nearer key's), the first key's below the first speed, the last
// key's above the last. Every field of the character's schema is blended; fields it does not use
// are the lower key's. No heap allocation, so the controller can call it every step.
void paramsAtSpeed(Character c, const Gait& gait, double speed, GaitParams* out);

}  // namespace gaitlab::gait
