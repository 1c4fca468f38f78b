// A first gait for any body: what a creature walks with before any search (the thesis's §7.5:
// creatures of any leg count). The footfall pattern comes from the leg count, the rest from the
// quadruped's tuned trot, scaled to the body's legs by dynamic similarity.
//
// - Footfall: the legs fall in two alternating groups, leg pair k's left leg with the pairs of
//   the other parity's right legs: a trot's diagonal pairs on four legs, the alternating tripods
//   of insects on six (Wilson 1966), alternating tetrapods on eight. Each leg is down for
//   kDerivedDutyFactor of the cycle, so that one group stands before the other lifts.
// - Everything else from the quadruped preset's trot at kDerivedFromSpeed, its front leg frame's
//   and front legs' parameters for every pair. Measured on the shipped creatures (insect, spider,
//   dragon; docs/creatures.md): the back pair's parameters on the last pair lifted those legs
//   early (duty factors 0.33–0.44 for 0.55) and the dragon fell on the slope; the trot at its
//   0.45 m/s cruise key ran the insect 18 % slow at 0.8 m/s.
// - Scale: bodies of equal Froude number move alike (Alexander & Jayes 1983), so the period
//   scales by √(L / L₀) and the lengths the gait places feet at (step offsets, step height) by
//   L / L₀, with L the leg's length (upper + lower) and L₀ the quadruped's.
// - Every value then within the schema's bounds of the body's kind (gait/schema.h), so that the
//   gait is a gait file of that kind: it can be read, edited, searched and shared as any other.
//
// Bodies of one or two leg frames have tuned gaits, the shipped presets; this is for the others.
#pragma once
#include "body/morphology.h"
#include "gait/params.h"

namespace gaitlab::gait {

constexpr double kDerivedDutyFactor = 0.55;
constexpr double kDerivedFromSpeed = 0.8;  // m/s, where the quadruped preset's trot is taken

GaitParams derivedGait(const body::Morphology& morphology);

}  // namespace gaitlab::gait
