#include "api/cli.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "api/cli_bench.h"
#include "sim/walk_trial.h"

namespace gaitlab::api {

namespace {

using nlohmann::json;

const char* kUsage =
    "usage: gaitlab [--version] [--help] <command> [options]\n"
    "\n"
    "Physics-driven procedural locomotion for bipeds and quadrupeds (Bullet Physics).\n"
    "\n"
    "commands:\n"
    "  walk       one character walks; prints what it achieved (speed, drift, duty factors...)\n"
    "  bench      the thesis's performance experiment on crowds (gaitlab bench --help)\n"
    "\n"
    "walk options:\n"
    "  --character biped|quadruped   (default biped)\n"
    "  --speed M_S                   goal speed, m/s (default 1.0)\n"
    "  --turn RAD_S                  goal turn rate, rad/s (default 0)\n"
    "  --seconds S                   simulated time (default 20)\n"
    "  --terrain flat                ground (default flat)\n"
    "  --push-impulse N_S            lateral push at the leg frame (default 0: none)\n"
    "  --push-every S                seconds between pushes (default 4)\n"
    "  --seed N                      (default 1)\n"
    "  --trace                       include the leg frame's path every 0.1 s\n"
    "  --json                        print one JSON document\n"
    "\n"
    "options:\n"
    "  --version    print the version and exit\n"
    "  --help       print this help and exit\n";

int usageError(const std::string& message) {
  std::fprintf(stderr, "gaitlab: %s (see gaitlab --help)\n", message.c_str());
  return 2;
}

// "--name value" and "--flag" options; refuses anything not in `valued` or `flags`.
struct Options {
  std::map<std::string, std::string> values;
  std::set<std::string> flags;
  std::string error;

  Options(int argc, char** argv, int first, const std::set<std::string>& valued,
          const std::set<std::string>& flagNames) {
    for (int i = first; i < argc; ++i) {
      const std::string a = argv[i];
      if (flagNames.count(a)) {
        flags.insert(a);
      } else if (valued.count(a)) {
        if (i + 1 >= argc) {
          error = "option " + a + " needs a value";
          return;
        }
        values[a] = argv[++i];
      } else {
        error = "unknown option '" + a + "'";
        return;
      }
    }
  }

  // A finite number within [lo, hi], or the default when absent.
  bool number(const std::string& name, double lo, double hi, double fallback, double* out) {
    auto it = values.find(name);
    if (it == values.end()) {
      *out = fallback;
      return true;
    }
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || *end != '\0' || !std::isfinite(v)) {
      error = name + ": '" + it->second + "' is not a number";
      return false;
    }
    if (v < lo || v > hi) {
      error = name + ": " + it->second + " is outside [" + json(lo).dump() + ", " + json(hi).dump() + "]";
      return false;
    }
    *out = v;
    return true;
  }
};

int walk(int argc, char** argv) {
  Options o(argc, argv, 2,
            {"--character", "--speed", "--turn", "--seconds", "--terrain", "--push-impulse",
             "--push-every", "--seed"},
            {"--json", "--trace"});
  if (!o.error.empty()) return usageError(o.error);
  sim::WalkOptions w;
  const std::string character = o.values.count("--character") ? o.values["--character"] : "biped";
  if (character == "biped") {
    w.character = sim::Kind::Biped;
  } else if (character == "quadruped") {
    w.character = sim::Kind::Quadruped;
  } else {
    return usageError("--character: '" + character + "' is not biped or quadruped");
  }
  w.terrain = o.values.count("--terrain") ? o.values["--terrain"] : "flat";
  if (w.terrain != "flat") return usageError("--terrain: '" + w.terrain + "' is not flat");
  double seed = 1;
  if (!o.number("--speed", -5, 5, 1.0, &w.speed) || !o.number("--turn", -3, 3, 0.0, &w.turnRate) ||
      !o.number("--seconds", 0.01, 3600, 20.0, &w.seconds) ||
      !o.number("--push-impulse", 0, 10000, 0.0, &w.pushImpulse) ||
      !o.number("--push-every", 0.5, 3600, 4.0, &w.pushEvery) ||
      !o.number("--seed", 0, 4294967295.0, 1, &seed))
    return usageError(o.error);
  w.seed = static_cast<uint32_t>(seed);
  w.trace = o.flags.count("--trace") > 0;

  const sim::WalkResult r = sim::runWalk(w);
  json out = {
      {"character", character},
      {"terrain", w.terrain},
      {"seconds", r.seconds},
      {"fell", r.fell},
      {"fall_time_s", r.fell ? json(r.fallTime) : json(nullptr)},
      {"distance_m", r.distance},
      {"mean_speed_m_s", r.meanSpeed},
      {"goal_speed_m_s", r.goalSpeed},
      {"heading_drift_deg", r.headingDrift},
      {"yaw_rate_rad_s", r.yawRate},
      {"goal_turn_rad_s", w.turnRate},
      {"duty_factor_measured", r.dutyMeasured},
      {"duty_factor_config", r.dutyConfig},
      {"pushes_applied", r.pushesApplied},
      {"pushes_survived", r.pushesSurvived},
      {"push_impulse_n_s", w.pushImpulse},
      {"controller_us_per_step", r.controllerMicrosPerStep},
      {"seed", w.seed},
      {"state_hash", r.stateHash},
  };
  if (w.trace) out["trace"] = r.trace;
  if (o.flags.count("--json")) {
    std::printf("%s\n", out.dump().c_str());
  } else {
    std::printf("%s\n", out.dump(2).c_str());
  }
  return 0;
}

}  // namespace

int runCli(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string cmd = argv[1];
  if (cmd == "--version" || cmd == "-V") {
    std::printf("gaitlab %s\n", GAITLAB_VERSION);
    return 0;
  }
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd == "walk") return walk(argc, argv);
  if (cmd == "bench") return runBenchCli(argc, argv);
  return usageError("unknown command '" + cmd + "'");
}

}  // namespace gaitlab::api
