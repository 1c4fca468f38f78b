// Probe, built only on request (`ninja -C build/native gaitlab_arena_log`): a crowd of quadrupeds
// wandering in the demo's arena (sim/wander.h) at one goal speed, and which of them fall
// (docs/controller-notes.md, "The demo's wandering slowing a hard turn").
//
//   build/native/gaitlab_arena_log SPEED [ARENA_RADIUS] [LAYOUTS] [verbose|GAIT_FILE] > log.txt
//
// Each layout (1, 2, ... LAYOUTS, also the simulation's seed) places 12 quadrupeds on a circle of
// 5 m about the arena's centre, turned 1.2 rad from facing out, gives them the preset's gait (or
// the quadruped gait file GAIT_FILE's) and the goal SPEED, lets them wander in an arena of
// ARENA_RADIUS m (default 12, the demo's smallest) for 60 simulated seconds, and prints each
// fall: the layout, the quadruped, the time. With `verbose`, also the turn rate and the speed each
// was steered at (its controller's goal) and its root leg frame's horizontal speed, every 0.1 s
// over the 4 s before it fell. Last, the falls of all and the farthest any leg frame went from the
// centre.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "gait/defaults.h"
#include "gait/params_io.h"
#include "sim/simulation.h"

using namespace gaitlab;
using gaitlab::gait::Character;

namespace {

constexpr int kCrowd = 12;
constexpr double kSeconds = 60;
constexpr int kHistory = 40;  // samples of 0.1 s before a fall, shown with `verbose`

struct Sample {
  double turn, steeredSpeed, speed;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: gaitlab_arena_log SPEED [ARENA_RADIUS] [LAYOUTS] [verbose|GAIT_FILE]\n");
    return 2;
  }
  const double speed = std::atof(argv[1]);
  const double radius = argc > 2 ? std::atof(argv[2]) : 12;
  const int layouts = argc > 3 ? std::atoi(argv[3]) : 1;
  const bool verbose = argc > 4 && std::string(argv[4]) == "verbose";
  std::optional<gait::GaitFile> file;
  if (argc > 4 && !verbose) {
    file.emplace();
    if (const auto error = gait::loadGaitFile(argv[4], Character::Quadruped, &*file)) {
      std::fprintf(stderr, "%s: %s\n", argv[4], error->describe().c_str());
      return 2;
    }
  }
  int falls = 0;
  double farthest = 0;
  for (int layout = 1; layout <= layouts; ++layout) {
    sim::Simulation s(1, static_cast<uint32_t>(layout));
    for (int i = 0; i < kCrowd; ++i) {
      const double a = 2 * M_PI * i / kCrowd + 0.3 * layout;
      s.spawn(Character::Quadruped, 5 * std::sin(a), 5 * std::cos(a), a + 1.2);
      if (file) s.controller(i).setGait(file->gait);
      s.setGoal(i, {speed, 0.0});
    }
    s.setWander(-1, radius);
    std::vector<std::vector<Sample>> history(kCrowd);
    std::vector<bool> reported(kCrowd, false);
    for (int step = 0; step < kSeconds * 120; ++step) {
      s.step(1);
      for (int i = 0; i < kCrowd; ++i) {
        const auto root = s.character(i).segmentState(s.character(i).morphology().legFrames[0]);
        farthest = std::max(farthest, std::hypot(root.position.x(), root.position.z()));
        if (step % 12 == 0)
          history[i].push_back({s.controller(i).goal().turnRate, s.controller(i).goal().speed,
                                std::hypot(root.linearVelocity.x(), root.linearVelocity.z())});
        if (!s.fallen(i) || reported[i]) continue;
        reported[i] = true;
        ++falls;
        std::printf("layout %d quadruped %d fell at %.1f s\n", layout, i, s.time());
        if (!verbose) continue;
        const size_t end = history[i].size(), begin = end > kHistory ? end - kHistory : 0;
        std::printf("  turn rate:    ");
        for (size_t k = begin; k < end; ++k) std::printf(" %+.2f", history[i][k].turn);
        std::printf("\n  steered at:   ");
        for (size_t k = begin; k < end; ++k) std::printf(" %5.2f", history[i][k].steeredSpeed);
        std::printf("\n  speed:        ");
        for (size_t k = begin; k < end; ++k) std::printf(" %5.2f", history[i][k].speed);
        std::printf("\n");
      }
    }
  }
  std::printf("goal %.2f m/s, arena %.0f m: %d of %d fell; farthest from the centre %.1f m\n", speed, radius,
              falls, layouts * kCrowd, farthest);
}
