// One character walking for a while, measured: the walking criteria of the controller issue
// (speed, heading drift, turn rate, duty factors, falls, pushes survived). Used by the CLI's
// `walk` subcommand, its WASM twin, the tests and the benchmark.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "gait/footfall.h"
#include "gait/params.h"
#include "gait/speed_keys.h"
#include "sim/simulation.h"

namespace gaitlab::sim {

// Which way the pushes go, in the heading frame at the moment of the push. Any: each push one of
// lateral, forward and backward at random (a third each).
enum class PushDirection { Lateral, Forward, Backward, Any };

struct WalkOptions {
  Character character = Character::Biped;
  const gait::Gait* gait = nullptr;  // nullptr: the character's preset
  // The character's body: nullptr is the shipped one, else a creature file's with the
  // character's leg frames (`gaitlab walk --creature`). It must outlive the walk.
  const body::Morphology* body = nullptr;
  double speed = 1.0;      // goal speed, m/s
  double turnRate = 0.0;   // goal turn rate, rad/s
  double seconds = 20.0;   // simulated
  physics::TerrainKind terrain = physics::TerrainKind::Flat;  // the ground; bumps follow `seed`
  double pushImpulse = 0.0;  // N·s, at the leg frame; 0 = no pushes
  double pushEvery = 0.0;    // s between pushes (the first after 2 s); phase jittered by the seed
  PushDirection pushDirection = PushDirection::Lateral;  // lateral: left or right at random
  // How long each push lasts: 0 gives the whole impulse in one step (a blow); longer spreads it
  // as a constant force over that time, as the literature pushes (Yin et al. 2007: 350 N held
  // for 0.2 s). Rounded to whole steps; at most 0.3 s, shorter than the least time between pushes
  // (0.75 of pushEvery ≥ 0.5 s), so pushes never overlap.
  double pushDuration = 0.0;
  // A goal-speed schedule (the ramp trial): (time s, speed m/s) points, the goal linear between
  // them and held after the last; empty = `speed` throughout. Times must increase.
  std::vector<std::pair<double, double>> speedSchedule;
  // Gaits taken up in mid-walk (the demo's gait menu pins one while the character walks):
  // (time s, gait) points, times increasing; each gait is set at the first step at or after its
  // time, in mid-stride, as Controller::setGait takes a gait up. The gaits must outlive the walk.
  std::vector<std::pair<double, const gait::Gait*>> gaitSchedule;
  // Position drift is measured over the last `driftWindow` seconds (0: the second half).
  double driftWindow = 0.0;
  uint32_t seed = 1;
  bool trace = false;  // record the leg frame's path every 0.1 s
  // Start state (the optimiser's "several start states"): the heading the character starts
  // facing, and a horizontal impulse at its root leg frame at t = 0 in the heading frame
  // (x = left, z = forward), N·s.
  double heading = 0.0;
  // The gait phase it starts at, 0 to 1 (a crowd starts each character at its own); negative:
  // the gait player's own start.
  double startPhase = -1.0;
  double startImpulseLeft = 0.0, startImpulseForward = 0.0;
  // Called after every fixed step, before the fall check (the optimiser's objective records
  // the leg frames here). May be empty.
  std::function<void(const Simulation&)> observe;
};

struct WalkResult {
  bool fell = false;
  double fallTime = -1;         // s, -1 if it never fell
  double distance = 0;          // m, horizontal, start to end (or to the fall)
  double meanSpeed = 0;         // m/s, horizontal, over the second half of the run
  double goalSpeed = 0;
  double headingDrift = 0;      // degrees: |final heading − start heading − turnRate·t|
  double yawRate = 0;           // rad/s, mean over the second half
  std::vector<double> dutyMeasured, dutyConfig;
  // The footfall pattern of the gait in effect at the end (gait/footfall.h): its configured step
  // triggers and duty factors, named.
  gait::Footfall footfall = gait::Footfall::Unknown;
  int pushesApplied = 0, pushesSurvived = 0;
  // Horizontal displacement of the leg frame over the drift window (standing: how far it crept).
  double positionDrift = 0;     // m
  // Share of the second half's steps with no foot on the ground (a run's flight phases).
  double flightFraction = 0;
  // Share of all steps it stood on planted feet, the gait clock stopped (gait::Controller::standing).
  double standingFraction = 0;
  // Changes of footfall pattern in the run (a gait of walk and trot keys, gait/gait_transition.h).
  int gaitChanges = 0;
  // Speed tracking (a schedule): the speed measured over a 2 s window against the goal at the
  // window's centre less a lag of up to 1 s, wherever the goal 1 s before the centre exceeds
  // 0.3 m/s (the walking benchmark's ramp criterion: within ±10 % after a lag of 1 s). Samples
  // every 0.1 s.
  int trackingSamples = 0, trackingWithin = 0;  // within ±10 % at the best lag of 0 to 1 s
  int trackingWithinAtFullLag = 0;              // within ±10 % of the goal exactly 1 s before
  double trackingWorst = 0;     // largest |measured − goal| / goal, at the best lag
  double controllerMicrosPerStep = 0;  // controller only, one character
  double seconds = 0;
  std::string stateHash;
  std::string terrainHash;  // physics::Terrain::hash() of the ground walked on
  std::vector<double> trace;  // x, y, z, heading every 0.1 s when requested
};

WalkResult runWalk(const WalkOptions& options);

// The walk's scene in `sim` (made with the walk's seed): its ground, its one character facing
// `heading` with its gait, its goal at t = 0 and its start phase. runWalk and the box-hit trial
// (box_hits.h) start from it.
void setUpWalk(Simulation& sim, const WalkOptions& options);

// The trials' random draws (push sides and phases, throws): a small xorshift generator, so that
// a seed draws the same numbers in every build, native and WebAssembly, which <random>'s
// distributions do not promise.
class TrialDraws {
 public:
  explicit TrialDraws(uint32_t seed) : state_(seed * 2654435761u + 1) {}
  // Uniform in [0, 1).
  double unit() {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 17;
    state_ ^= state_ << 5;
    return (state_ >> 8) * (1.0 / 16777216.0);
  }

 private:
  uint32_t state_;
};

// The goal speed of `o` at time t (its schedule, or its constant speed).
double goalSpeedAt(const WalkOptions& o, double t);
// A (time s, speed m/s) schedule at time t: linear between its points, held before the first
// and after the last. Not empty.
double scheduleAt(const std::vector<std::pair<double, double>>& schedule, double t);

// Fall criterion (controller issue): the leg frame below half its standing height above the
// ground, or tilted more than 60° from upright.
bool hasFallen(const Simulation& sim, int character);
// The same for a character in `world` (any shard's world will do: they share one terrain). Reads
// only that character and the terrain, so characters can be tested on many threads at once.
bool hasFallen(const physics::Character& character, const physics::World& world);

}  // namespace gaitlab::sim
