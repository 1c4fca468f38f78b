#include "sim/experiment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#if defined(__EMSCRIPTEN__)
#include <malloc.h>
#elif defined(__GLIBC__)
#include <malloc.h>
#endif

namespace gaitlab::sim {

namespace {

Stat meanSd(const double* x, size_t n, size_t stride) {
  if (n == 0) return {};
  double sum = 0;
  for (size_t i = 0; i < n; ++i) sum += x[i * stride];
  const double mean = sum / n;
  double sq = 0;
  for (size_t i = 0; i < n; ++i) sq += (x[i * stride] - mean) * (x[i * stride] - mean);
  // Population standard deviation, as a spread of the measurements themselves.
  return {mean, std::sqrt(sq / n)};
}

Crowd crowdOf(int legs) {
  return legs == kBiped ? Crowd::Bipeds : legs == kQuadruped ? Crowd::Quadrupeds : Crowd::Mixed;
}

}  // namespace

double percentile(std::vector<double>& samples, double p) {
  if (samples.empty()) return 0;
  std::sort(samples.begin(), samples.end());
  // Nearest rank.
  const size_t rank = static_cast<size_t>(std::ceil(p / 100.0 * samples.size()));
  return samples[std::min(samples.size() - 1, rank == 0 ? 0 : rank - 1)];
}

double p99OfMediansOverRuns(const std::vector<double>& samples, size_t runs, size_t steps) {
  std::vector<double> medians(steps), atIndex(runs);
  for (size_t s = 0; s < steps; ++s) {
    for (size_t run = 0; run < runs; ++run) atIndex[run] = samples[run * steps + s];
    medians[s] = percentile(atIndex, 50);
  }
  return percentile(medians, 99);
}

int64_t heapInUse() {
#if defined(__EMSCRIPTEN__)
  const struct mallinfo m = mallinfo();
  return static_cast<int64_t>(m.uordblks);
#elif defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  const struct mallinfo2 m = mallinfo2();
  return static_cast<int64_t>(m.uordblks + m.hblkhd);
#else
  return -1;
#endif
}

int64_t residentSetBytes() {
  // Linux: natively, and under Node through the WASM build's NODERAWFS (Node's own process).
  // In a browser there is no /proc and the answer is -1.
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return -1;
  char line[256];
  int64_t kb = -1;
  while (std::fgets(line, sizeof line, f)) {
    if (std::strncmp(line, "VmRSS:", 6) == 0) {
      kb = std::strtoll(line + 6, nullptr, 10);
      break;
    }
  }
  std::fclose(f);
  return kb < 0 ? -1 : kb * 1024;
}

void warmUp(const std::vector<int>& legs, int threads) {
  for (int l : legs) {
    PointSpec spec;
    spec.legs = l;
    spec.characters = 10;
    spec.threads = threads;
    spec.mode = Mode::Full;
    spec.steps = 120;
    spec.runs = 1;
    runPoint(spec);
  }
}

int maxCharacters(int legs) {
  const int biped = static_cast<int>(body::makeBiped().segments.size());
  const int quadruped = static_cast<int>(body::makeQuadruped().segments.size());
  // A mixed crowd alternates, starting with a biped.
  const int perPair = biped + quadruped;
  const int cap = Simulation::kRenderCapacity;
  if (legs == kBiped) return cap / biped;
  if (legs == kQuadruped) return cap / quadruped;
  return 2 * (cap / perPair) + (cap % perPair >= biped ? 1 : 0);
}

PointResult runPoint(const PointSpec& spec) {
  if (spec.characters > maxCharacters(spec.legs))
    throw std::invalid_argument("a simulation holds at most " + std::to_string(maxCharacters(spec.legs)) +
                                " characters of this kind");
  PointResult r;
  r.spec = spec;
  r.shards = std::max(1, std::min(spec.shards, spec.characters));
  const size_t steps = static_cast<size_t>(spec.steps), runs = static_cast<size_t>(spec.runs);
  // Samples, laid out [run][step]; allocated before any simulation runs.
  std::vector<double> controller(steps * runs), physics(steps * runs), step(steps * runs);

  for (size_t run = 0; run < runs; ++run) {
    const int64_t heapBefore = heapInUse();
    // A fresh simulation per run: "for each new initiated run the BulletPhysics engine is
    // restarted" (thesis §4.2). Thread creation and scene building happen here, outside the
    // timed steps.
    auto sim = std::make_unique<Simulation>(spec.threads, spec.seed, r.shards);
    if (!spec.creatures.empty()) {
      std::vector<body::Morphology> bodies;
      for (const body::Morphology* m : spec.creatures) bodies.push_back(*m);
      sim->creatureScene(bodies, spec.characters, spec.spacing);
    } else {
      sim->crowdScene(crowdOf(spec.legs), spec.characters, spec.spacing);
    }
    if (sim->characterCount() < spec.characters) {
      // Timings labelled with a crowd that was not simulated would be wrong: say so instead.
      r.error = "characters: only " + std::to_string(sim->characterCount()) + " of " +
                std::to_string(spec.characters) + " fit in the memory left";
      return r;
    }
    sim->setMode(spec.mode);
    for (size_t s = 0; s < steps; ++s) {
      sim->step(1);
      const StepTiming& t = sim->lastStep();
      controller[run * steps + s] = t.controller * 1e3;
      physics[run * steps + s] = t.physics * 1e3;
      step[run * steps + s] = t.step * 1e3;
    }
    const std::string hash = sim->stateHash();
    if (run == 0) r.stateHash = hash;
    if (hash != r.stateHash) r.deterministic = false;
    if (run + 1 == runs) {
      r.heapBytes = heapInUse();
      r.sceneHeapBytes = heapBefore >= 0 ? r.heapBytes - heapBefore : -1;
      r.rssBytes = residentSetBytes();
    }
  }

  const size_t n = steps * runs;
  r.controller = meanSd(controller.data(), n, 1);
  r.physics = meanSd(physics.data(), n, 1);
  r.step = meanSd(step.data(), n, 1);
  if (spec.frames) {
    for (size_t s = 0; s < steps; ++s) {
      r.frameController.push_back(meanSd(controller.data() + s, runs, steps));
      r.framePhysics.push_back(meanSd(physics.data() + s, runs, steps));
      r.frameStep.push_back(meanSd(step.data() + s, runs, steps));
    }
  }
  r.stepP99MedianOverRuns = p99OfMediansOverRuns(step, runs, steps);
  r.stepMedian = percentile(step, 50);  // sorts `step`: last
  r.stepP99 = percentile(step, 99);
  r.stepMax = step.empty() ? 0 : step.back();
  return r;
}

}  // namespace gaitlab::sim
