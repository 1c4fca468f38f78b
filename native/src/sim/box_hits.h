// The box-hit trial: boxes thrown at a walking character the way the demo throws them, and how
// many of the hits knock it over.
//
// A push at the leg frame (walk_trial.h) is a clean impulse at one body; a thrown box is what a
// user of the demo actually does to a character: shift-click on any part of it, and a 0.24 m box
// of 8.3 kg (the page's default size, 600 kg/m³) flies from the camera at 14 m/s or faster,
// aimed by the simulation where that part will be (Simulation::aimAt). It can strike a foot in
// swing, a shin, the trunk or the head, at any moment of the stride, from any side.
//
// Each throw is its own episode, so one fall does not end the trial: a fresh simulation, the
// character walking from rest at the goal speed for 2–4 s (a random phase of its stride), then one
// box from a random direction 8–18 m away and 1.5–4 m up (where the page's camera stands over a
// crowd), at a random body part's centre, at the page's throw speed for that distance
// (web/src/render/picking.ts: 14 m/s, faster beyond 14 m so that the flight stays within 1 s).
// A throw that does not touch the character within its flight and 0.3 s more is a miss and is
// thrown again from a new draw; a hit is judged 3 s later: fallen (the walking criteria's
// hasFallen at any step after the hit) or not. With getUpSeconds, a hit that knocked it over is
// watched that much longer: whether the character got up by itself (gait/get_up.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "sim/walk_trial.h"

namespace gaitlab::sim {

struct BoxHitOptions {
  WalkOptions walk;  // character, gait, goal speed, turn rate, terrain, heading, start phase, seed
  int hits = 50;     // hits to judge
  double half = 0.12;  // m, the box's half size (the page's BOX_HALF)
  // s after a fall to watch for the character getting up by itself; 0: the episode ends at the
  // fall.
  double getUpSeconds = 0;
};

struct BoxHit {
  int segment = 0;        // the body part aimed at (render buffer order: 0 is the root leg frame)
  double throwTime = 0;   // s after the start of the episode
  double speed = 0;       // m/s, straight distance over flight time
  bool fell = false;      // within 3 s of the throw
  double fallAfter = -1;  // s from the throw to the fall, -1 if it did not fall
  // With getUpSeconds: s from the fall until its controller was back on its feet (the last time,
  // if it fell again), -1 if it was not on its feet, or fallen again, when the watch ended.
  double gotUpAfter = -1;
};

// How long after a throw a hit is judged, s.
constexpr double kBoxJudgeSeconds = 3.0;

struct BoxHitResult {
  int throws = 0;  // thrown, hits and misses
  std::vector<BoxHit> hits;
  int falls() const;
  int getUps() const;  // falls it got up from (gotUpAfter ≥ 0)
};

BoxHitResult runBoxHits(const BoxHitOptions& options);

// One throw of the trial: takes its draws from `draw` (body part, walking time, direction,
// distance, height), walks a fresh simulation and throws. Returns whether the box touched the
// character (a hit, written to *hit) or missed. A character that fell before the throw counts
// as a hit that knocked it over (the gait, not the box: a fall all the same). The optimiser's
// box-hit episodes (optimize/objective.h) throw with this too.
bool throwBox(const BoxHitOptions& options, TrialDraws& draw, BoxHit* hit);

// Whether a dynamic body that is not one of character i's (in these scenes, a thrown box) touches
// one of its bodies now: a contact point within 1 cm.
bool boxTouches(const Simulation& sim, int i);

// The page's throw speed over `distance` metres (web/src/render/picking.ts throwSpeed): 14 m/s,
// or distance / 1 s beyond 14 m, at most 30 m/s.
double pageThrowSpeed(double distance);

}  // namespace gaitlab::sim
