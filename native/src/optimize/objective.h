// The optimiser's objective (thesis §3.3, eq. 3.10):
//
//   f = w_d·f_d + w_v·f_v + w_h·f_a + w_r·f_r  (+ a fall penalty)
//
// f_d motion deviation, f_v velocity deviation, f_a leg-frame acceleration, f_r leg-frame
// rotation deviation. The thesis names the terms but not their formulas (and its original code
// ran the objective, the reference gait and the physics on three different clocks: defect 9
// of the original implementation, docs/original-implementation.md). Here every term is measured on the simulation's own clock, once per fixed step, in
// the goal heading frame: the frame that starts at the character's start heading and turns at
// the goal turn rate. The reference is that goal, never the gait's own parameters, so the
// optimiser cannot lower a term by redefining what the controller aims at:
//
//   f_d  (travel deviation)² + (posture deviation)²: the distance walked along the goal heading
//        after the warm-up against goal speed × time, relative to max(that distance, 1 m); and
//        the leg frames' mean height above the ground against their standing height, relative
//        to it. The thesis used "desired travel distance and leg IK angles and positions" as
//        its stand-in for motion capture; standing height is ours.
//   f_v  mean over steps after the warm-up of |v − v_goal|², (m/s)², the root leg frame's
//        horizontal velocity in the goal heading frame against (0 left, goal speed forward).
//   f_a  mean over steps and leg frames of |a|²/g², a = the leg frame's linear acceleration
//        (finite difference of its velocity over one step).
//   f_r  mean over steps and leg frames of θ², θ the angle (rad) of the rotation from the goal
//        heading frame (upright, facing the goal heading) to the leg frame.
//
// Beyond the thesis, a fifth term, 0 unless weighted (w_t, default 0: searches score as before):
//
//   f_t  mean over legs of (measured duty factor − configured duty factor)²: how far the feet's
//        real stance time is from the footfall pattern (late strikes shorten it; the walking
//        criteria ask for ±0.1).
//
// and a sixth, also 0 unless weighted (w_k), for ramp episodes only:
//
//   f_k  the share of the ramp's speed samples off the goal by more than 10 %: the walking
//        benchmark's ramp criterion itself (sim::runWalk's tracking: the speed over 2 s windows
//        every 0.1 s against the goal at a lag of up to 1 s, where the goal exceeds 0.3 m/s).
//        f_v is a per-step error, in which the stride's own swing of the velocity outweighs a
//        mean 10 % too fast; f_k sees only the mean (docs/controller-notes.md §27).
//
// and a seventh, 0 unless weighted (w_s):
//
//   f_s  mean over steps after the warm-up of (|v| − goal speed)², (m/s)², |v| the root leg
//        frame's horizontal speed in whatever direction it goes. In a turning episode f_v also
//        counts the path's lag behind the goal heading, and a slower gait lowers that: searches
//        of the canter's turns with f_v alone turned at the told rate by running 2.0–2.6 m/s at
//        a goal of 3.5 (docs/controller-notes.md §62).
//        f_s keeps the speed whichever way the body goes.
//
// and an eighth, 0 unless weighted (w_p), for episodes held at goal 0 only:
//
//   f_p  the share of the episode's steps not standing on planted feet (gait/standing.cpp): the
//        walking benchmark's standing skill asks for 90 % or more. A search at goal 0 scored on
//        falls alone (box hits, pushes) found that stepping in place falls less, and gave up the
//        stand (docs/controller-notes.md §82).
//
// and a ninth, 0 unless weighted (w_o), for scheduled episodes that end held at goal 0 only:
//
//   f_o  the stop's overshoot: how far (m, horizontally) the root leg frame moves from the time
//        the goal reaches 0 for good to the episode's end: the walking benchmark's standing
//        drift after its ramp (criterion < 0.1 m). A standing key searched at goal 0 alone took
//        the box gain and stopped 0.12 m past the goal's return to 0, as no episode of its search
//        walked and stopped (docs/controller-notes.md §82); `stopFrom` adds such an episode.
//
// A fall (sim::hasFallen) ends the episode and adds fallPenalty·(1 + remaining/episode time):
// any fall scores worse than any walk whose terms stay below fallPenalty, and a later fall
// scores better than an earlier one, so a search that starts from a falling gait climbs
// towards walking.
#pragma once
#include <Eigen/Geometry>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "body/morphology.h"
#include "gait/schema.h"
#include "gait/speed_keys.h"
#include "physics/terrain.h"

namespace gaitlab::optimize {

// One ground an episode is walked on: a terrain (physics/terrain.h; bumps drawn from the
// episode's seed) and the heading the character starts facing there (rad about +y, 0 = +z).
// On the slope the heading decides what comes first: 0 climbs from the origin, π descends,
// π/2 walks across. Written "slope@3.14159" (the heading after '@', 0 when left out).
struct Ground {
  physics::TerrainKind terrain = physics::TerrainKind::Flat;
  double heading = 0.0;
};
// Ground headings must lie in this range, rad (as `gaitlab walk --heading`).
constexpr double kMaxGroundHeading = 7.0;
// Parses "flat", "slope", "bumps", optionally "@HEADING"; returns an error message naming the
// `grounds` field, empty on success.
std::string parseGround(const std::string& text, Ground* out);
std::string groundText(const Ground& g);  // "slope@3.14159", "flat" for heading 0

// How candidates are scored: weights of eq. 3.10 and the episodes each candidate walks.
struct ObjectiveSettings {
  double wd = 1.0, wv = 1.0, wa = 1.0, wr = 1.0;  // w_d, w_v, w_h, w_r of eq. 3.10
  double wt = 0.0;                                 // w_t of f_t (footfall timing, ours)
  double wf = 0.0;                                 // w_f of f_f (flight: no foot down, ours)
  double wk = 0.0;                                 // w_k of f_k (a ramp's speed tracking, ours)
  double ws = 0.0;                                 // w_s of f_s (speed whatever the direction, ours)
  double wp = 0.0;                                 // w_p of f_p (not standing at goal 0, ours)
  double wo = 0.0;                                 // w_o of f_o (the stop's overshoot, ours)
  double fallPenalty = 100.0;
  double seconds = 800.0 / 120.0;  // per episode: the thesis's 800 fixed steps
  double warmup = 1.0;             // s before travel and velocity are measured
  // Episodes per evaluation: every ground × every goal speed × every start state; the objective
  // is their mean. The default, flat ground facing +z, is what every search before grounds ran.
  std::vector<Ground> grounds = {Ground{}};
  std::vector<double> speeds = {1.0};
  int starts = 1;                // start state 0 stands still; the others get a random nudge
  double startImpulse = 10.0;    // N·s, horizontal, random direction, for starts 1..N-1
  // 1: starts 1..N-1 also begin at their own gait phase (golden-ratio spread, as a crowd starts),
  // not at the gait's own start; 0 (default): every start at the gait's own phase.
  double startPhases = 0.0;
  double turnRate = 0.0;         // goal turn rate, rad/s
  // 1: start states 1, 3, 5… turn at −turnRate, the others at turnRate, so that a search meets
  // turns to both sides (a gait that is not left-right symmetric, such as a canter with its
  // lead, can turn well one way and fall the other); 0 (default): every episode at turnRate.
  double turnBothWays = 0.0;
  // 1: start states cycle through three episodes, turning at turnRate, at −turnRate and walking
  // straight (start states 0, 3, 6… left for a positive turnRate, 1, 4, 7… right, 2, 5, 8…
  // straight), so that a search of a gait's turns keeps its straight walk (a search of the
  // canter's fastest key on turns alone turned, and fell running straight: docs/controller-notes.md
  // §62). Overrides turnBothWays.
  double turnStraight = 0.0;
  double pushImpulse = 0.0;      // N·s pushes at the leg frame during the episode (0 = none)
  double pushEvery = 2.0;        // s between pushes, phase jittered
  double pushDuration = 0.0;     // s each push lasts (0: the whole impulse in one step)
  // 1: each push goes lateral, forward or backward at random; 0 (default): lateral only.
  double pushAnyWay = 0.0;
  // 1: one more episode per ground and start state, whose goal ramps from 0 up to the largest of
  // `speeds` and back to 0 over the episode (Wang et al. 2010 optimise over speed changes); the
  // velocity term then follows the ramping goal.
  double ramp = 0.0;
  // A goal speed, m/s (0 = none): one more episode per ground and start state that walks and
  // stops: its goal ramps from 0 up to `stopFrom` and back to 0 over `seconds`, as `ramp` does,
  // then holds 0 for kStopHoldSeconds, over which f_o measures how far it goes on. It is not
  // pushed (pushImpulse is for the other episodes): the benchmark's ramp has no pushes, and a push
  // in the hold would make f_o measure the steps that recover from it. Searched with pushes, a
  // standing key stopped within 0.1 m in its pushed stops and 0.4 m past the goal's return to 0
  // without them (docs/controller-notes.md §83).
  double stopFrom = 0.0;
  // Box-hit episodes per goal speed (0 = none): a box thrown as the demo throws one, at a random
  // body part from a random side (sim/box_hits.h), judged 3 s after the hit. Such an episode's
  // only term is the fall penalty, scaled by the share of the 3 s left when it fell; it counts
  // as one episode of the mean. The draws follow the evaluation's seed, so every candidate meets
  // the same throws; the walking benchmark's trial draws from seed 7, so a search does not see
  // the throws it is judged by.
  int boxHits = 0;
  // Speed-change episodes per ground (0 = none): the goal changes back and forth between the
  // slowest and the fastest of `speeds`, each goal held for 1–4 s drawn from the evaluation's
  // seed, kSpeedChangeHolds holds, as the walking benchmark's gait-change trial does (Wang et al.
  // 2010 optimise over speed changes). With keys on both sides of a change of footfall pattern,
  // these are the episodes that meet the change; the velocity term follows the goal.
  int speedChanges = 0;
};

// The goal turn rate of the episodes of start state `start` (settings.turnBothWays, turnStraight).
double episodeTurnRate(const ObjectiveSettings& settings, int start);

// Parameters that no episode of these settings can measure, which a search therefore leaves as
// they start (optimize/optimizer.h, beside SearchOptions::held): without a goal turn rate, the
// turn's maxTurnSlip, turnPlacement and turnRollMoment (gait/params.h), which act only while the
// goal turns, those of them that `c`'s schema has. Left free, CMA-ES moves them as far as its
// other coordinates, with nothing to pull them back: searches of the quadruped's canter keys for
// speed took one key's maxTurnSlip to its lower bound, and that key then turned at half the told
// rate (docs/controller-notes.md §66).
std::vector<std::string> unmeasuredParameters(gait::Character c, const ObjectiveSettings& settings);

// Goals held in one speed-change episode (the walking benchmark's gait-change trial holds 9).
constexpr int kSpeedChangeHolds = 9;

// The goal of speed-change episode `index`: `kSpeedChangeHolds` holds alternating from `lo` to
// `hi`, each 1–4 s long, as (time, goal) points for sim::WalkOptions::speedSchedule. The holds
// follow from `seed` and `index` alone, so every candidate meets the same changes.
std::vector<std::pair<double, double>> speedChangeSchedule(double lo, double hi, int index, uint32_t seed);

// The walk seed of speed-change episode `index` in an evaluation with `seed`: its own pushes and
// bumps, apart from the held goals' episodes (which vary the seed by start state, 7919 apart).
uint32_t speedChangeSeed(uint32_t seed, int index);

// The goal of a ramp episode (settings.ramp): from 0 up to `top` at half of `seconds` and back to
// 0 at its end, as the walking benchmark's ramp does over 60 s.
std::vector<std::pair<double, double>> rampSchedule(double top, double seconds);

// How long a stop episode (settings.stopFrom) stands at goal 0 after its ramp, s: past the
// stop's last step (the shipped biped comes to rest within 2 s) and short enough to leave the
// search's time to its other episodes.
constexpr double kStopHoldSeconds = 5.0;

// The goal of a stop episode: rampSchedule(top, seconds), then goal 0 held for kStopHoldSeconds.
std::vector<std::pair<double, double>> stopSchedule(double top, double seconds);

// The scalar settings as a schema-style table (name, bounds, default, unit, description), so
// they are read, checked and exported the same way as gait parameters. `speeds` is a list and
// is handled separately (`speeds` in JSON, --speeds on the command line), as is `grounds`
// (a list of strings, "flat", "slope@3.14159": --grounds on the command line).
struct SettingSpec {
  const char* name;
  double min, max;
  const char* unit;
  const char* description;
  bool integer = false;  // whole numbers only (rounded when set)
};
// Goal speeds (the `speeds` list) must lie in this range, m/s.
constexpr double kMinGoalSpeed = -5.0, kMaxGoalSpeed = 5.0;
void forEachSetting(ObjectiveSettings& s, const std::function<void(const SettingSpec&, double&)>& visit);
// Sets one scalar setting by name; returns an error message, empty on success.
std::string setSetting(ObjectiveSettings& s, const std::string& name, double value);
std::string settingsJson(const ObjectiveSettings& s);  // {"wd":1,...,"speeds":[...],"grounds":[...]}

struct ObjectiveTerms {
  double fd = 0, fv = 0, fa = 0, fr = 0;
  double ft = 0;          // footfall timing deviation (duty factors)
  double ff = 0;          // flight: the share of the time with no foot on the ground
  double fk = 0;          // a ramp's speed samples off the goal by more than 10 %, as a share
  double fs = 0;          // (horizontal speed − goal speed)², whatever the direction
  double fp = 0;          // at goal 0, the share of the time not standing on planted feet
  double fo = 0;          // m moved after a schedule's goal returned to 0 for good
  double fall = 0;        // the fall penalty, 0 if it did not fall
  double total = 0;       // w_d·f_d + w_v·f_v + w_h·f_a + w_r·f_r + w_t·f_t + w_f·f_f + w_k·f_k + w_s·f_s + w_p·f_p + w_o·f_o + fall
  bool fell = false;
  double seconds = 0;     // simulated
};

// The terms and the fall penalty by the names the CLI's and the C ABI's JSON give them: one list,
// so that the mean over episodes and both reports cannot leave a term out.
struct TermName {
  const char* name;
  double ObjectiveTerms::*member;
};
inline constexpr TermName kTermNames[] = {
    {"fd", &ObjectiveTerms::fd}, {"fv", &ObjectiveTerms::fv}, {"fa", &ObjectiveTerms::fa},
    {"fr", &ObjectiveTerms::fr}, {"ft", &ObjectiveTerms::ft}, {"ff", &ObjectiveTerms::ff},
    {"fk", &ObjectiveTerms::fk}, {"fs", &ObjectiveTerms::fs}, {"fp", &ObjectiveTerms::fp},
    {"fo", &ObjectiveTerms::fo}, {"fall", &ObjectiveTerms::fall}};

// What the recorder sees of one leg frame after a step.
struct LegFrameSample {
  Eigen::Vector3d position;   // world, m
  Eigen::Vector3d velocity;   // world, m/s
  Eigen::Quaterniond orientation;
  double heightAboveGround;   // m
  double standingHeight;      // m, its rest-pose height
};

// Accumulates the terms of one episode step by step (nothing stored per step). Leg frame 0 is
// the root (the one whose travel and velocity count).
class ObjectiveRecorder {
 public:
  // goalSpeed (m/s) and the goal heading frame's start: startHeading (rad) at t = 0.
  ObjectiveRecorder(const ObjectiveSettings& settings, double goalSpeed, double startHeading, double dt);

  // The state after the step that ended at `time` (s, the simulation's clock).
  void add(double time, const LegFrameSample* frames, int count);

  // Terms over what was recorded; `fell` at `fallTime` adds the fall penalty. `ft`: the
  // episode's footfall timing deviation (timingDeviation, from the walk's duty factors); `ff`
  // its flight share; `fk` its speed tracking's misses (trackingMisses); `standing` the share of
  // its steps on planted feet (counted as f_p's complement in an episode whose goal is 0).
  ObjectiveTerms finish(bool fell, double fallTime, double ft = 0.0, double ff = 0.0, double fk = 0.0,
                        double standing = 1.0) const;

  double goalHeading(double time) const { return startHeading_ + settings_.turnRate * time; }
  // A goal speed that changes: (time s, speed m/s) points (sim::scheduleAt), instead of the
  // constructor's constant goalSpeed. If it ends held at 0, f_o measures from where that hold
  // begins.
  void setGoalSchedule(std::vector<std::pair<double, double>> schedule);

 private:
  ObjectiveSettings settings_;
  double goalSpeed_, startHeading_, dt_;
  std::vector<std::pair<double, double>> schedule_;  // empty: goalSpeed_ throughout
  // f_o: the time from which the schedule's goal stays 0 (infinite: it does not end at 0), and
  // the root leg frame's position at the first step from then and at the last.
  double stoppedFrom_ = std::numeric_limits<double>::infinity();
  std::optional<Eigen::Vector3d> stopPosition_;
  Eigen::Vector3d lastPosition_ = Eigen::Vector3d::Zero();
  double travel_ = 0, goalTravel_ = 0;      // along the goal heading, after the warm-up: walked, asked
  double velocitySum_ = 0;  int velocityCount_ = 0;
  double speedSum_ = 0;  // Σ (|v| − goal)², over the velocity term's steps
  double postureSum_ = 0, accelSum_ = 0, rotationSum_ = 0;
  int frameSamples_ = 0, accelSamples_ = 0;
  std::vector<Eigen::Vector3d> lastVelocity_;
  double lastTime_ = 0;
};

// f_t of one episode: the mean over legs of (measured − configured duty factor)²; 0 for no legs.
double timingDeviation(const std::vector<double>& measured, const std::vector<double>& configured);

// f_k of one episode: the share of its speed-tracking samples (sim::WalkResult) off by more than
// 10 %; 0 for a walk that has none (no speed schedule).
double trackingMisses(int samples, int within);

// One episode: the character walks with `params` on `ground` from start state `start` at goal
// `speed` (sim::runWalk with the recorder observing every step). With a `schedule` (a ramp's,
// a speed change's), the goal follows it instead of `speed` and the episode lasts until its last
// point. `seed` fixes the start nudge's direction, the pushes' phases and the bumps. `body`: the
// character's body (a creature file's, of the kind `c`), or nullptr for the kind's shipped body.
ObjectiveTerms runEpisode(gait::Character c, const gait::Gait& gait,
                          const ObjectiveSettings& settings, double speed, int start, uint32_t seed,
                          const Ground& ground = Ground{}, const body::Morphology* body = nullptr,
                          const std::vector<std::pair<double, double>>& schedule = {});

// The objective of a parameter set: the mean over every episode: ground × speed × start state,
// then the ramps, the stops, the speed changes and the box hits the settings ask for. Deterministic: the
// same inputs give the same bits (each episode is its own single-threaded simulation).
ObjectiveTerms evaluate(gait::Character c, const gait::Gait& gait,
                        const ObjectiveSettings& settings, uint32_t seed,
                        const body::Morphology* body = nullptr);

// One box-hit episode (settings.boxHits): throw `index` at goal `speed` with the evaluation's
// `seed`; a throw that misses is thrown again from new draws, up to three times (no hit: no
// fall). Its terms are zero but for the fall penalty.
ObjectiveTerms runBoxHitEpisode(gait::Character c, const gait::Gait& gait,
                                const ObjectiveSettings& settings, double speed, int index, uint32_t seed,
                                const body::Morphology* body = nullptr);

}  // namespace gaitlab::optimize
