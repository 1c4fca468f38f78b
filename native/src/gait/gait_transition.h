// Gait transitions: moving between speed keys of different footfall patterns.
//
// Blending every field linearly in the desired speed (gait/speed_keys.h) suits keys of one gait:
// a trot tuned at 0.8 and at 1.6 m/s, its stance a little shorter and its period a little longer.
// Between a walk and a trot it does not: the footfall patterns in between are neither, and a
// character asked to hold a speed there walks with one of them for as long as it is asked. The
// quadruped's walk keyed below its trot fell wherever the goal held the blend between the two
// (docs/controller-notes.md, "Gait transitions"). A change of gait is an event, not a speed:
// Coros et al. (2011) move their dog from one gait to the next in mid-stride.
//
// So between two neighbouring keys whose footfall patterns differ (a transition), the parameters
// are not blended: they are the key of the half of the interval the desired speed is in, and the
// gait changes once the desired speed has crossed the middle, where the gait phase next reaches the
// old key's transitionPhase (the controller's rule for every change of footfall pattern, a gait
// pinned by the user too). Where in the stride matters: taken up at whatever phase the stride was
// in, 3 to 6 % of the quadruped's switches from its pace fell, at the cycle's start none
// (docs/controller-notes.md §22); its canter left for the trot at the cycle's start fell in 27 % of
// the benchmark's runs of changes back and forth, left at 0.45 of its cycle in 10 % (§52). So each
// key says where its gait is left, 0 (the cycle's start) unless tuned. There the gait phase Φ is
// moved by the mean of the legs' step-trigger moves (transitionPhaseShift), so each leg's own phase
// ψ = Φ − trigger moves as little as the two patterns allow (walk to trot: an eighth of a cycle
// each, where the triggers move by up to half a cycle). Measured in the walking benchmark's
// transition trial (goals changing every 1 to 4 s between two speeds across the change, 20 runs per
// pair): with the shift the quadruped fell in none of 80 runs, without it in 9
// (docs/controller-notes.md §20).
#pragma once
#include "gait/params.h"

namespace gaitlab::gait {

// Two keys have different footfall patterns when their step triggers, once the whole pattern is
// shifted as well as it can be, leave some leg more than this fraction of a cycle from where it was
// (footfallDistance: the shipped trot's keys are at most 0.12 apart, its canter 0.26 from the trot,
// a pace or a bound 0.25 or more), or, on more than one pair of legs, when one walks (every foot
// down more than half the cycle, Alexander 1984's walking) and the other does not. A four-beat
// walk and a trot are only an eighth of a cycle apart at the best shift (a walk is a trot whose
// diagonal pairs lift a quarter of a cycle apart): what sets them apart is the walk's longer
// stance. The quadruped's walk keys blended into its trot fell in every walk held at 0.3 and
// 0.4 m/s. A biped's walk and run keep one pattern, left and right half a cycle apart, and blend:
// judged as a change instead, the shipped biped fell in 9 of 100 starts at 2.5 m/s (none
// blended) and in 3 of 40 runs of speed changes across its walk and run (none).
//
// Nothing here depends on the order of the legs, so a gait and its mirror image (left and right
// legs swapped) change pattern between the same keys. Judged from the first leg's trigger as it
// once was, the quadruped preset's walk keys differed from its trot by 0.150 from the front left
// leg and 0.08–0.09 from the right legs, and its mirror image changed pattern inside the trot
// (docs/controller-notes.md §63).
constexpr double kFootfallTolerance = 0.15;

// How far apart two gait phases are on the cycle, in [0, 0.5] cycles (0.95 and 0.02: 0.07).
double cyclicDistance(double a, double b);

// How far apart the footfall patterns of leg schedules `a` and `b` (`legs` legs each) are, in
// cycles, [0, 0.5]: the largest step-trigger move of any leg once the whole pattern is shifted so
// that this is least. The same for any order of the legs; 0 for a pattern only shifted.
double footfallDistance(const LegParams* a, const LegParams* b, int legs);

// Whether every one of `legs` legs (LegParams or LegSchedule) is down more than half the cycle:
// a walk (Alexander 1984), for the change of footfall pattern above and for the gaits by name
// (gait/footfall.h).
template <class Leg>
bool walks(const Leg* legs, int count) {
  for (int i = 0; i < count; ++i)
    if (!(legs[i].dutyFactor > 0.5)) return false;
  return true;
}

// Whether leg schedules `a` and `b` (`legs` legs each) differ in footfall pattern, as above.
bool footfallDiffers(const LegParams* a, const LegParams* b, int legs);

// The gait-phase shift (cycles, in (−0.5, 0.5]) for a change of leg schedules from `from` to `to`:
// the circular mean of the step triggers' moves. Shifting Φ by it leaves each leg's ψ moved by its
// own trigger move less the mean.
double transitionPhaseShift(const LegParams* from, const LegParams* to, int legs);

// Whether the gait phase, moving forward from `before` to `after` in one step (wrapping at 1),
// reached `at` (in [0, 1]): at = 0 (or 1) is the wrap itself, the cycle's start.
bool phaseReached(double before, double after, double at);

}  // namespace gaitlab::gait
