// Arena wandering (beyond the thesis): the demo page's crowd walks about inside a round arena
// for as long as the page is open, instead of walking straight out of view.
//
// Each wandering character keeps the speed of its goal and is given a turn rate: Reynolds's
// steering behaviours (Reynolds 1999, "Steering Behaviors For Autonomous Characters") summed
// with priorities, as he combines them:
//   containment  turn towards the arena's centre once inside the margin along its edge that the
//                character needs to turn round at its speed and the turn rate it may use;
//   separation   turn away from neighbours close ahead;
//   wander       a slow, smooth drift of heading, different for every character, so that the
//                crowd does not walk in lockstep circles.
// The result is clamped to the turn rate both presets are measured to follow (README, Walking:
// ±0.3 rad/s, yaw rates within 1 % of the goal), but for the quadruped's canter, which turns at
// 0.19–0.3 rad/s when told 0.3 (turnPlacement and maxTurnSlip, gait/params.h) and so runs a
// little wider than the arena before it comes round. Everything is a function of the characters'
// positions, headings, ids and the step index, computed serially between fixed steps, so a run
// is as deterministic and replayable as one without wandering.
#pragma once
#include <cstdint>
#include <vector>

namespace gaitlab::sim {

// What wandering reads of one character.
struct WanderBody {
  int id;
  double x, z;     // root leg frame's centre, m
  double heading;  // rad about +y, 0 = +z
  double speed;    // its goal speed, m/s (sets the margin it needs to turn round)
  bool wanders;    // steered by wandering (others are obstacles only)
  bool fallen;     // a fallen character is an obstacle, not steered
};

struct WanderSettings {
  // The turn rate the presets are measured to follow (README, Walking): ±0.3 rad/s.
  double maxTurnRate = 0.3;
  // Turn rate per radian of heading error for containment and separation.
  double gain = 1.2;
  // Neighbours closer than this (m, between leg frames) push a 1 m/s walker away (slower ones:
  // proportionally closer, at least 1 m).
  double separation = 2.5;
  // The wander drift: at most this share of maxTurnRate.
  double wanderShare = 0.5;
};

// Goals are recomputed every kPeriodSteps fixed steps (0.1 s at 120 Hz): steering is slow next to
// the gait, and recomputing at fixed step indices keeps runs replayable.
constexpr int kWanderPeriodSteps = 12;

// The turn rate (rad/s, positive = left) for body `self` of `bodies`, at simulated time `time`,
// in an arena of radius `arenaRadius` centred on the origin.
double wanderTurnRate(const std::vector<WanderBody>& bodies, int self, double arenaRadius, double time,
                      const WanderSettings& settings = {});

// Which characters wander (by id, stable across resets) and the arena they wander in.
class Wander {
 public:
  // Character `id` wanders (on) or keeps the goal it is given (off).
  void set(int id, bool on);
  bool wanders(int id) const { return id >= 0 && id < static_cast<int>(byId_.size()) && byId_[id]; }
  bool any() const { return count_ > 0; }
  // One arena per simulation: a circle of this radius (m) about the origin.
  void setArenaRadius(double radius) { arenaRadius_ = radius; }
  double arenaRadius() const { return arenaRadius_; }

 private:
  std::vector<char> byId_;
  int count_ = 0;
  double arenaRadius_ = 12;
};

}  // namespace gaitlab::sim
