// Probe: where the slow steps come from (docs/parallel.md, "Where the physics time goes", p99).
// Runs the benchmark's crowd (`gaitlab bench`: same scene, shards and seed) and records, for every
// fixed step, its wall-clock time, the CPU time of the calling thread, and the number of times the
// process's threads were switched out involuntarily (preempted by the kernel for another process)
// during the step. Built only on request:
//
//   ninja -C build/native gaitlab_step_times
//   build/native/gaitlab_step_times LEGS CHARACTERS STEPS MODE THREADS [RUNS [series]]
//
// Prints one JSON object: percentiles of the step's wall time over all steps, over the steps in
// which no thread was preempted, and of the calling thread's CPU time; how many steps were
// preempted; the same without the first step of each run (a fresh Bullet world creates its
// contact pairs, manifolds and solver arrays in its first step); the slowest steps with their index; and the per-step-index CPU time profile summary
// (whether the slow steps are the same steps in every run, i.e. a property of the scene).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "probe.h"
#include "sim/simulation.h"

namespace {

long involuntarySwitches() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_nivcsw;
}

struct Sample {
  int run, step;
  double wall, cpu;
  long switches;
};

void printStats(const char* name, const std::vector<double>& x, bool comma = true) {
  const double p50 = gaitlab::probe::quantile(x, 0.5), p99 = gaitlab::probe::quantile(x, 0.99);
  std::printf("\"%s\": {\"n\": %zu, \"p50\": %.3f, \"p99\": %.3f, \"max\": %.3f, \"p99_over_p50\": %.2f}%s ",
              name, x.size(), p50, p99, gaitlab::probe::quantile(x, 1.0), p50 > 0 ? p99 / p50 : 0.0, comma ? "," : "");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: gaitlab_step_times LEGS(2|4|mixed) CHARACTERS STEPS MODE THREADS [RUNS]\n");
    return 2;
  }
  using namespace gaitlab::sim;
  const std::string legs = argv[1];
  const int characters = std::atoi(argv[2]), steps = std::atoi(argv[3]);
  Mode mode;
  if (!parseMode(argv[4], &mode)) return 2;
  const int threads = std::atoi(argv[5]);
  const int runs = argc > 6 ? std::atoi(argv[6]) : 1;
  const Crowd crowd = gaitlab::probe::crowdOf(legs);
  std::vector<Sample> samples;
  samples.reserve(static_cast<size_t>(steps) * runs);
  for (int run = 0; run < runs; ++run) {
    auto sim = std::make_unique<Simulation>(threads, 1, std::min(kCrowdShards, characters));
    sim->crowdScene(crowd, characters, 4.0);
    sim->setMode(mode);
    for (int s = 0; s < steps; ++s) {
      const long sw0 = involuntarySwitches();
      const double c0 = gaitlab::probe::threadSeconds();
      const auto w0 = std::chrono::steady_clock::now();
      sim->step(1);
      const auto w1 = std::chrono::steady_clock::now();
      const double c1 = gaitlab::probe::threadSeconds();
      const long sw1 = involuntarySwitches();
      samples.push_back({run, s, std::chrono::duration<double, std::milli>(w1 - w0).count(),
                         (c1 - c0) * 1e3, sw1 - sw0});
    }
  }
  std::vector<double> wall, quiet, cpu, wallAfterFirst, cpuAfterFirst, firstCpu;
  int preempted = 0;
  for (const Sample& x : samples) {
    wall.push_back(x.wall);
    cpu.push_back(x.cpu);
    if (x.step > 0) wallAfterFirst.push_back(x.wall), cpuAfterFirst.push_back(x.cpu);
    else firstCpu.push_back(x.cpu);
    if (x.switches == 0) quiet.push_back(x.wall);
    else ++preempted;
  }
  // Per step index: the CPU time's median over the runs, then how far the slowest step index is
  // above the median step index (a property of the scene if the runs agree).
  std::vector<double> byIndex;
  for (int s = 0; s < steps; ++s) {
    std::vector<double> v;
    for (int run = 0; run < runs; ++run) v.push_back(samples[static_cast<size_t>(run) * steps + s].cpu);
    byIndex.push_back(gaitlab::probe::quantile(v, 0.5));
  }
  std::printf("{\"legs\": \"%s\", \"characters\": %d, \"steps\": %d, \"runs\": %d, \"mode\": \"%s\", "
              "\"threads\": %d, ", legs.c_str(), characters, steps, runs, modeName(mode), threads);
  printStats("wall_ms", wall);
  printStats("wall_ms_not_preempted", quiet);
  printStats("cpu_ms_calling_thread", cpu);
  printStats("wall_ms_without_first_step", wallAfterFirst);
  printStats("cpu_ms_without_first_step", cpuAfterFirst);
  printStats("cpu_ms_first_step", firstCpu);
  printStats("cpu_ms_median_over_runs_by_step_index", byIndex);
  std::printf("\"preempted_steps\": %d, \"slowest\": [", preempted);
  std::vector<Sample> sorted = samples;
  std::sort(sorted.begin(), sorted.end(), [](const Sample& a, const Sample& b) { return a.wall > b.wall; });
  for (size_t i = 0; i < std::min<size_t>(12, sorted.size()); ++i)
    std::printf("%s{\"run\": %d, \"step\": %d, \"wall\": %.2f, \"cpu\": %.2f, \"switches\": %ld}",
                i ? ", " : "", sorted[i].run, sorted[i].step, sorted[i].wall, sorted[i].cpu,
                sorted[i].switches);
  std::printf("]");
  // With a seventh argument "series": the per-step-index CPU medians themselves.
  if (argc > 7 && std::string(argv[7]) == "series") {
    std::printf(", \"cpu_ms_by_step_index\": [");
    for (size_t i = 0; i < byIndex.size(); ++i) std::printf("%s%.3f", i ? ", " : "", byIndex[i]);
    std::printf("]");
  }
  std::printf("}\n");
  return 0;
}
