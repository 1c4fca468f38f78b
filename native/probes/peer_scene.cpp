// Probe: the peer benchmark's reference scene (peers/reference_scene.h) natively, one thread, in
// a given number of physics worlds, for timing and profiling why one Bullet world's cost per
// character grows with its crowd (docs/peers.md, "Why Jolt is faster where it is"). Built only on
// request:
//
//   ninja -C build/native gaitlab_peer_scene
//   build/native/gaitlab_peer_scene LEGS CHARACTERS SHARDS [STEPS [ROUNDS]]
//   perf record -g build/native/gaitlab_peer_scene 4 250 1 240
//
// Prints one JSON object: the median over the rounds of the calling thread's CPU time per fixed
// step, ms (CPU time, so that other processes on the machine do not count), and its range.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "peers/reference_scene.h"
#include "probe.h"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s LEGS CHARACTERS SHARDS [STEPS [ROUNDS]]\n", argv[0]);
    return 2;
  }
  const int legs = std::atoi(argv[1]);
  const int characters = std::atoi(argv[2]);
  const int shards = std::atoi(argv[3]);
  const int steps = argc > 4 ? std::atoi(argv[4]) : 120;
  const int rounds = argc > 5 ? std::atoi(argv[5]) : 3;
  if ((legs != 2 && legs != 4) || characters < 1 || shards < 1 || steps < 1 || rounds < 1) {
    std::fprintf(stderr, "LEGS is 2 or 4; CHARACTERS, SHARDS, STEPS, ROUNDS are at least 1\n");
    return 2;
  }
  const auto character = legs == 2 ? gaitlab::gait::Character::Biped : gaitlab::gait::Character::Quadruped;
  std::vector<double> ms;
  for (int r = 0; r < rounds; ++r) {
    gaitlab::peers::ReferenceScene scene(character, characters, 1, shards);
    scene.step(30);  // the first contacts, as the peer benchmark settles them
    const double t0 = gaitlab::probe::threadSeconds();
    scene.step(steps);
    ms.push_back(1e3 * (gaitlab::probe::threadSeconds() - t0) / steps);
  }
  std::sort(ms.begin(), ms.end());
  std::printf("{\"legs\": %d, \"characters\": %d, \"shards\": %d, \"steps\": %d, \"cpu_ms_per_step\": %.3f, \"min\": %.3f, \"max\": %.3f}\n",
              legs, characters, shards, steps, ms[ms.size() / 2], ms.front(), ms.back());
  return 0;
}
