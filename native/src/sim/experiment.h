// The thesis's performance experiment (Chapter 4), extended to the physics step and to our
// execution modes: one *point* of the experiment is a crowd of N characters with a leg count,
// simulated `runs` times for `steps` fixed steps (thesis: 20 runs of 800 steps at 120 Hz),
// a fresh simulation (a restarted Bullet) for every run, each step timed.
//
// Statistics, after thesis §4.1 ("mean and standard deviation are calculated on a per-frame- and
// per-execution basis"):
//   per frame      for each step index f, mean and sd over the runs (thesis Figures 5.1, 5.2);
//   per execution  mean and sd over every step of every run (Figures 5.3-5.5, Tables 6.1-6.3),
//                  plus the median, 99th percentile and maximum step (the thesis saw single-frame
//                  spikes it could not explain, §6.3), and the 99th percentile of the per-frame
//                  medians: a spike of the simulation's own recurs at its step in every run and
//                  counts there, one from outside (another process, the host) hits one run and
//                  does not.
// Used by the `gaitlab bench` command (api/cli_bench.cpp) and the browser's performance page
// (through the C API), so that every runtime measures with the same code.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sim/simulation.h"

namespace gaitlab::sim {

// Leg count of a crowd: 2 (bipeds), 4 (quadrupeds), or 0 for a mixed crowd (alternating).
enum Legs { kMixed = 0, kBiped = 2, kQuadruped = 4 };

struct PointSpec {
  int legs = kBiped;
  // A crowd of creature files' bodies instead, in turn (body/creature.h, `gaitlab bench
  // --creature A,B`); `legs` is then their leg count, or kMixed if they differ. They must outlive
  // the point.
  std::vector<const body::Morphology*> creatures;
  int characters = 1;
  int threads = 1;
  Mode mode = Mode::Serial;
  int steps = 800;
  int runs = 20;
  // Physics shards (simulation.h). Fixed by the experiment, not by the thread count, so that
  // every mode and thread count of a point simulates exactly the same thing (physics_shards.h).
  int shards = kCrowdShards;
  double spacing = 4.0;  // metres between neighbours on the grid: well apart, no overlap
  uint32_t seed = 1;
  bool frames = false;  // keep the per-frame statistics
};

struct Stat {
  double mean = 0, sd = 0;
};

struct PointResult {
  PointSpec spec;
  int shards = 1;  // in use: min(spec.shards, characters)
  // Per execution, milliseconds.
  Stat controller, physics, step;
  double stepMedian = 0, stepP99 = 0, stepMax = 0;
  // 99th percentile over step indices of each step's median over the runs (see above; with one
  // run it is stepP99).
  double stepP99MedianOverRuns = 0;
  // Per frame (spec.frames), milliseconds, one entry per step index.
  std::vector<Stat> frameController, framePhysics, frameStep;
  // Memory after the last run with its simulation still alive: bytes the allocator hands out
  // (on the WASM heap in WebAssembly) and what the scene itself added; the process's resident
  // set where the system tells it (-1 if not).
  int64_t heapBytes = 0, sceneHeapBytes = 0, rssBytes = -1;
  std::string stateHash;
  bool deterministic = true;  // every run ended in the same state
  // Not empty when the point could not be measured as asked: a scene that held fewer characters
  // than spec.characters (the module's memory ran short: sim/capacity.h). No timings then.
  std::string error;
};

// The largest crowd of a leg count one simulation holds (its render buffer's bodies,
// Simulation::kRenderCapacity).
int maxCharacters(int legs);

// Untimed: simulates a crowd of 10 characters of each leg count in `legs` for 1 s on `threads`
// threads (full mode), before a grid is measured. A WebAssembly engine starts a module in a
// baseline compiler and recompiles hot functions with its optimising one as they run (V8: Liftoff,
// then TurboFan): without this the first point measured, the grid's smallest crowd, ran the
// baseline code and took several times as long per step as later points, which skewed the
// thesis's 1-character ratios (Tables 6.1-6.3). Natively it only warms the caches.
void warmUp(const std::vector<int>& legs, int threads);

// Runs one point of the experiment. Throws std::invalid_argument for a crowd larger than
// maxCharacters.
PointResult runPoint(const PointSpec& spec);

// Nearest-rank percentile p (0-100) of `samples`.
double percentile(std::vector<double>& samples, double p);  // sorts `samples`

// The 99th percentile over step indices of each step's median over the runs; `samples` is laid
// out [run][step]. A spike that recurs at its step in every run counts, one in a single run not.
double p99OfMediansOverRuns(const std::vector<double>& samples, size_t runs, size_t steps);

// Allocator and process memory, for the memory figures.
int64_t heapInUse();
int64_t residentSetBytes();

}  // namespace gaitlab::sim
