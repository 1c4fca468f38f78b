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

// Two keys have different footfall patterns when some leg's step trigger, relative to the first
// leg's, differs between them by more than this fraction of a cycle (walk and trot differ by a
// quarter; the trot's own keys, tuned apart, by under a tenth). Judged from the first leg, so a
// gait and its mirror image (left and right legs swapped) can be judged differently: the
// quadruped preset's slow walk keys differ from its trot by 0.150 from the front left leg and by
// 0.08–0.09 from the right legs (docs/controller-notes.md §63).
constexpr double kFootfallTolerance = 0.15;

// How far apart two gait phases are on the cycle, in [0, 0.5] cycles (0.95 and 0.02: 0.07).
double cyclicDistance(double a, double b);

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
