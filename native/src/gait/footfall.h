// Footfall patterns by name: what the literature calls a gait, read from when each foot lifts off
// and how long it stays down. The locomotion criteria ask for named gaits (a biped that walks and
// runs; a quadruped that walks, trots, paces and canters or gallops), so the walking benchmark
// says which one a gait file's keys give at each speed instead of taking a file's name for it.
//
// The duty factor β (the share of the cycle a foot is down) separates walking from running
// (Alexander 1984: walking gaits have β > 1/2, running gaits β < 1/2). A quadruped's running
// gaits are named by the feet that lift off together, and so strike together at equal duty
// factors (Hildebrand 1965, 1977, who times the strikes):
//  * trot: the diagonal pairs (front left with back right, front right with back left);
//  * pace: the lateral pairs (front left with back left, right with right);
//  * bound: the front pair and the back pair; pronk: all four at once;
//  * symmetric gaits with no pair together (each leg frame's feet half a cycle apart): the
//    amble, a running walk;
//  * asymmetric gaits (a leg frame's feet not half a cycle apart): the canter, three beats with
//    one diagonal pair together, and the gallop, four.
// A biped's is the walk or the run. Bodies of other leg counts are not named (Unknown).
//
// "Together" and "half a cycle apart" are within kFootfallTogether of a cycle, the tolerance a
// change of footfall pattern is judged by (gait/gait_transition.h): the shipped trot's diagonal
// pairs lift off up to 0.10 apart (its 2.1 m/s key), the pace's lateral pairs 0.14, the walk's
// legs a quarter of a cycle.
#pragma once
#include "body/morphology.h"
#include "gait/gait_player.h"
#include "gait/gait_transition.h"

namespace gaitlab::gait {

enum class Footfall { Unknown, Walk, Run, Trot, Pace, Amble, Bound, Pronk, Canter, Gallop };

constexpr double kFootfallTogether = kFootfallTolerance;  // cycles

// The name of a pattern, lower case ("trot"); "unknown" for Unknown.
const char* footfallName(Footfall f);

// The pattern of leg schedules `legs` (step trigger and duty factor per leg, in `m`'s leg order):
// a walk if every leg's duty factor exceeds 1/2, otherwise named by the feet that lift off
// together, as above.
Footfall classifyFootfall(const body::Morphology& m, const LegSchedule* legs);

}  // namespace gaitlab::gait
