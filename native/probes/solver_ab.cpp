// Probe: the fast constraint sweep (physics/solver.h) against Bullet's own, in one process, on one
// simulation, switching between the two step by step. Both compute the same state, so the two sets
// of steps simulate the same crowd; on a shared machine, whatever else runs slows both alike. Built
// only on request (docs/parallel.md, "Where the physics time goes"):
//
//   ninja -C build/native gaitlab_solver_ab
//   build/native/gaitlab_solver_ab LEGS CHARACTERS STEPS [SHARDS] [PART]
//
// PART: `sweep` (the default) switches the constraint sweep (physics/solver.h); `rows` switches
// only the setup of the joints' rows (physics/joint_rows.h), the sweep staying the fast one; `all`
// switches both.
//
// Prints one JSON object: per sweep, the thread CPU time of a whole fixed step (serial: controller
// and physics), median, 10th and 90th percentile, in ms and in µs per character, the ratio of the
// medians, and the final state hash (the same as `gaitlab bench` with the same crowd, shards and
// steps gives). The first 20 steps are left out.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "probe.h"
#include "sim/simulation.h"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: gaitlab_solver_ab LEGS(2|4|mixed) CHARACTERS STEPS [SHARDS] [sweep|rows|all]\n");
    return 2;
  }
  const std::string legs = argv[1];
  const int characters = std::atoi(argv[2]), steps = std::atoi(argv[3]);
  const int shards = argc > 4 ? std::atoi(argv[4]) : std::min(gaitlab::sim::kCrowdShards, characters);
  const std::string part = argc > 5 ? argv[5] : "sweep";
  if (part != "sweep" && part != "rows" && part != "all") {
    std::fprintf(stderr, "gaitlab_solver_ab: PART must be sweep, rows or all, not %s\n", part.c_str());
    return 2;
  }
  using gaitlab::sim::Crowd;
  const Crowd crowd = gaitlab::probe::crowdOf(legs);
  gaitlab::sim::Simulation sim(1, 1, shards);
  sim.crowdScene(crowd, characters, 4.0);
  std::vector<double> ms[2];  // [0] Bullet's sweep, [1] the fast one
  for (int s = 0; s < steps; ++s) {
    const bool fast = s % 2 == 1;
    sim.setFastSolver(fast || part == "rows");
    sim.setFastJointRows(fast || part == "sweep");
    const double t0 = gaitlab::probe::threadSeconds();
    sim.step(1);
    const double t1 = gaitlab::probe::threadSeconds();
    if (s >= 20) ms[fast].push_back((t1 - t0) * 1e3);
  }
  std::printf("{\"legs\": \"%s\", \"characters\": %d, \"steps\": %d, \"shards\": %d, \"part\": \"%s\",",
              legs.c_str(), characters, steps, shards, part.c_str());
  const char* names[2] = {"bullet", "fast"};
  for (int v = 0; v < 2; ++v) {
    const double p50 = gaitlab::probe::quantile(ms[v], 0.5);
    std::printf(" \"%s\": {\"cpu_ms_p50\": %.3f, \"cpu_ms_p10\": %.3f, \"cpu_ms_p90\": %.3f, "
                "\"us_per_character_p50\": %.1f},",
                names[v], p50, gaitlab::probe::quantile(ms[v], 0.1), gaitlab::probe::quantile(ms[v], 0.9), p50 * 1e3 / characters);
  }
  std::printf(" \"ratio_p50\": %.3f, \"state_hash\": \"%s\"}\n",
              gaitlab::probe::quantile(ms[0], 0.5) / gaitlab::probe::quantile(ms[1], 0.5), sim.stateHash().c_str());
  return 0;
}
