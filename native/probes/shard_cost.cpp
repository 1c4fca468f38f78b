// Probe: what a crowd's physics costs as it is split over more physics shards (docs/parallel.md,
// "How many shards"). One process builds the same crowd once per shard count, serially on one
// thread, and steps the copies in turns of TURN steps, so that whatever else the machine does
// slows every shard count alike. Built only on request:
//
//   ninja -C build/native gaitlab_shard_cost
//   build/native/gaitlab_shard_cost LEGS CHARACTERS STEPS SHARDS,SHARDS,... [TURN]
//
// Prints one JSON object: per shard count, the thread CPU time of a whole fixed step (serial:
// controller and physics), median, 10th and 90th percentile, in ms and in µs per character, its
// median over the first shard count's, and the final state hash. The first 20 steps of each copy
// are left out (scene building, solver pools).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "probe.h"
#include "sim/simulation.h"

int main(int argc, char** argv) {
  using namespace gaitlab::sim;
  if (argc < 5) {
    std::fprintf(stderr, "usage: gaitlab_shard_cost LEGS(2|4|mixed) CHARACTERS STEPS SHARDS,SHARDS,... [TURN]\n");
    return 2;
  }
  const std::string legs = argv[1];
  const int characters = std::atoi(argv[2]), steps = std::atoi(argv[3]);
  const int turn = argc > 5 ? std::max(1, std::atoi(argv[5])) : 10;
  std::vector<int> shards;
  std::stringstream list(argv[4]);
  for (std::string s; std::getline(list, s, ',');) shards.push_back(std::atoi(s.c_str()));
  const Crowd crowd = gaitlab::probe::crowdOf(legs);

  std::vector<std::unique_ptr<Simulation>> sims;
  std::vector<std::vector<double>> cpu(shards.size());
  for (int s : shards) {
    sims.push_back(std::make_unique<Simulation>(1, 1, s));
    sims.back()->crowdScene(crowd, characters, 4.0);
    sims.back()->setMode(Mode::Serial);
  }
  for (int done = 0; done < steps; done += turn) {
    for (size_t v = 0; v < sims.size(); ++v) {
      for (int k = done; k < std::min(steps, done + turn); ++k) {
        const double c0 = gaitlab::probe::threadSeconds();
        sims[v]->step(1);
        const double c1 = gaitlab::probe::threadSeconds();
        if (k >= 20) cpu[v].push_back((c1 - c0) * 1e3);
      }
    }
  }
  std::printf("{\"legs\": \"%s\", \"characters\": %d, \"steps\": %d, \"turn\": %d, \"shards\": [", legs.c_str(),
              characters, steps, turn);
  const double first = gaitlab::probe::quantile(cpu[0], 0.5);
  for (size_t v = 0; v < sims.size(); ++v) {
    const double median = gaitlab::probe::quantile(cpu[v], 0.5);
    std::printf("%s\n  {\"shards\": %d, \"characters_per_shard\": %.1f, \"cpu_ms\": {\"p10\": %.3f, \"p50\": %.3f, "
                "\"p90\": %.3f}, \"us_per_character\": %.2f, \"over_first\": %.3f, \"state_hash\": \"%s\"}",
                v ? "," : "", sims[v]->shards(), static_cast<double>(characters) / sims[v]->shards(),
                gaitlab::probe::quantile(cpu[v], 0.1), median, gaitlab::probe::quantile(cpu[v], 0.9), median * 1e3 / characters, median / first,
                sims[v]->stateHash().c_str());
  }
  std::printf("]}\n");
  return 0;
}
