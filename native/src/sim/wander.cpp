#include "sim/wander.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;
// m: how far a walker goes before its turn follows the asked turn rate (about half a second at
// 1 m/s), left over when a U-turn at the full rate reaches the arena's edge.
constexpr double kTurnLag = 0.5;

// The angle (rad, in (-pi, pi]) to turn left from direction `from` to direction `to` (both
// angles about +y, 0 = +z).
double turnTo(double from, double to) { return std::remainder(to - from, 2 * kPi); }

// The heading of direction (dx, dz): 0 = +z, positive towards +x (left when facing +z, as the
// goal's turn rate).
double headingOfDirection(double dx, double dz) { return std::atan2(dx, dz); }

// A hash of a character's id to [0, 1): its own phases of the wander drift.
double idHash(int id, uint32_t salt) {
  uint32_t h = static_cast<uint32_t>(id) * 2654435761u ^ salt;
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  return (h >> 8) * (1.0 / 16777216.0);
}

}  // namespace

double wanderTurnRate(const std::vector<WanderBody>& bodies, int self, double arenaRadius, double time,
                      const WanderSettings& s) {
  const WanderBody& b = bodies[self];
  const double fx = std::sin(b.heading), fz = std::cos(b.heading);

  // Containment: the margin is what a U-turn at this speed and the allowed turn rate needs (its
  // diameter, 2 v / omega) plus a metre, at most half the arena.
  const double turnRadius = std::abs(b.speed) / s.maxTurnRate;
  const double margin = std::min(0.5 * arenaRadius, 2 * turnRadius + 1.0);
  const double r = std::hypot(b.x, b.z);
  // The weight of containment: 0 inside the margin's inner side, rising to 1 where a character
  // heading straight out still has the turning circle's radius before the edge (halfway across
  // a full margin; sooner where the margin is capped at half the arena, which a fast walker in a
  // small arena reaches: a biped at 1 m/s turning at 0.3 rad/s needs 7.7 m). Full weight comes
  // kTurnLag sooner still: a walker's turn follows the asked rate only after a step or two, and
  // without that room a biped of the demo's crowd, steered by a neighbour, left a 10 m arena by
  // 0.12 m.
  double edge = 0;
  double containment = 0;
  if (r > arenaRadius - margin && r > 1e-9) {
    const double rise = std::max(0.25 * margin, margin - turnRadius - kTurnLag);
    edge = std::min(1.0, (r - (arenaRadius - margin)) / rise);
    const double error = turnTo(b.heading, headingOfDirection(-b.x, -b.z));
    containment = std::clamp(s.gain * error, -s.maxTurnRate, s.maxTurnRate) * edge;
  }

  // Separation: away from neighbours within `separation` that are ahead (a neighbour behind is
  // walking into this one's back and turns itself), weighted by closeness. The distance that
  // counts as close shrinks with speed (a dog at 0.4 m/s needs 1 m, a person at 1 m/s 2.5 m): a
  // slow walker that turned away from everything within 2.5 m would walk in circles.
  const double reach = std::clamp(s.separation * std::abs(b.speed), 1.0, s.separation);
  double ax = 0, az = 0;
  for (int j = 0; j < static_cast<int>(bodies.size()); ++j) {
    if (j == self) continue;
    const double dx = bodies[j].x - b.x, dz = bodies[j].z - b.z;
    const double d = std::hypot(dx, dz);
    if (d >= reach || d < 1e-9) continue;
    if (dx * fx + dz * fz <= 0) continue;  // behind
    const double w = 1 - d / reach;
    ax -= dx / d * w;
    az -= dz / d * w;
  }
  double separation = 0;
  const double push = std::hypot(ax, az);
  if (push > 1e-9) {
    const double error = turnTo(b.heading, headingOfDirection(ax, az));
    separation = std::clamp(s.gain * error, -s.maxTurnRate, s.maxTurnRate) * std::min(1.0, push);
  }

  // Wander: two slow sines per character, phases and rates from its id (periods of 40–90 s).
  const double w1 = 2 * kPi / (40 + 20 * idHash(b.id, 1)), w2 = 2 * kPi / (60 + 30 * idHash(b.id, 2));
  const double drift = 0.6 * std::sin(w1 * time + 2 * kPi * idHash(b.id, 3)) +
                       0.4 * std::sin(w2 * time + 2 * kPi * idHash(b.id, 4));
  // A drift of curvature rather than of turn rate: at most wanderShare × maxTurnRate for a 1 m/s
  // walker (a circle of 6.7 m radius), the same curvature slower, so a dog does not circle.
  const double wander = s.wanderShare * s.maxTurnRate * drift * std::min(1.0, std::abs(b.speed));

  // Priorities (Reynolds 1999, combining behaviours): containment outranks separation, both
  // outrank the drift, which fades out as the edge nears.
  const double turn = containment + (1 - edge) * (separation + (1 - std::min(1.0, push)) * wander);
  return std::clamp(turn, -s.maxTurnRate, s.maxTurnRate);
}

void Wander::set(int id, bool on) {
  if (id < 0) return;
  if (id >= static_cast<int>(byId_.size())) {
    if (!on) return;
    byId_.resize(id + 1, 0);
  }
  if (static_cast<bool>(byId_[id]) == on) return;
  byId_[id] = on ? 1 : 0;
  count_ += on ? 1 : -1;
}

}  // namespace gaitlab::sim
