#include "gait/footfall.h"

namespace gaitlab::gait {

namespace {

bool together(const LegSchedule& a, const LegSchedule& b) {
  return cyclicDistance(a.stepTrigger, b.stepTrigger) <= kFootfallTogether;
}

bool halfACycleApart(const LegSchedule& a, const LegSchedule& b) {
  return cyclicDistance(a.stepTrigger, b.stepTrigger) >= 0.5 - kFootfallTogether;
}

}  // namespace

const char* footfallName(Footfall f) {
  switch (f) {
    case Footfall::Walk: return "walk";
    case Footfall::Run: return "run";
    case Footfall::Trot: return "trot";
    case Footfall::Pace: return "pace";
    case Footfall::Amble: return "amble";
    case Footfall::Bound: return "bound";
    case Footfall::Pronk: return "pronk";
    case Footfall::Canter: return "canter";
    case Footfall::Gallop: return "gallop";
    case Footfall::Unknown: break;
  }
  return "unknown";
}

Footfall classifyFootfall(const body::Morphology& m, const LegSchedule* legs) {
  const int count = static_cast<int>(m.legs.size());
  if (count < 2 || count > GaitPlayer::kMaxLegs) return Footfall::Unknown;
  const bool walking = walks(legs, count);
  if (count == 2 && m.legFrames.size() == 1) return walking ? Footfall::Walk : Footfall::Run;
  if (count != 4 || m.legFrames.size() != 2) return Footfall::Unknown;
  if (walking) return Footfall::Walk;

  // The four legs by leg frame (front: the root's) and side (left: the hip at +x).
  int front[2] = {-1, -1}, back[2] = {-1, -1};  // [left, right]
  for (int l = 0; l < count; ++l) {
    const body::Leg& leg = m.legs[l];
    const int side = m.segments[leg.upper].joint.pivot.x() >= 0 ? 0 : 1;
    (leg.legFrame == m.legFrames[0] ? front : back)[side] = l;
  }
  if (front[0] < 0 || front[1] < 0 || back[0] < 0 || back[1] < 0) return Footfall::Unknown;
  const LegSchedule &fl = legs[front[0]], &fr = legs[front[1]], &bl = legs[back[0]], &br = legs[back[1]];

  const bool diagonals = together(fl, br) && together(fr, bl);
  const bool laterals = together(fl, bl) && together(fr, br);
  const bool girdles = together(fl, fr) && together(bl, br);
  if (girdles && laterals) return Footfall::Pronk;
  if (diagonals) return Footfall::Trot;
  if (laterals) return Footfall::Pace;
  if (girdles) return Footfall::Bound;
  if (halfACycleApart(fl, fr) && halfACycleApart(bl, br)) return Footfall::Amble;
  return together(fl, br) || together(fr, bl) ? Footfall::Canter : Footfall::Gallop;
}

}  // namespace gaitlab::gait
