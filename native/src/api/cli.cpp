#include "api/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "api/c_api.h"
#include "api/cli_bench.h"
#include "api/options.h"
#include "gait/defaults.h"
#include "gait/params_io.h"
#include "gait/schema.h"
#include "optimize/optimizer.h"
#include "optimize/settings.h"
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
    "  schema     prints the gait parameter schema (names, groups, bounds, defaults, units)\n"
    "  optimize   searches gait parameters (thesis §3.3) and writes the best as a gait file\n"
    "\n"
    "walk options:\n"
    "  --character biped|quadruped   (default biped, or the --params file's character)\n"
    "  --params FILE                 gait file (public/presets/*.json format); default: preset\n"
    "  --speed M_S                   goal speed, m/s (default 1.0)\n"
    "  --turn RAD_S                  goal turn rate, rad/s (default 0)\n"
    "  --heading RAD                 heading it starts facing, about +y (default 0: +z)\n"
    "  --start-push-forward N_S      impulse at the leg frame at t = 0, forward (default 0)\n"
    "  --start-push-left N_S         the same, to the left (default 0)\n"
    "  --seconds S                   simulated time (default 20)\n"
    "  --terrain flat|slope|bumps    ground (default flat): slope = ridges and valleys of ±5°\n"
    "                                across the walking direction, bumps = smooth random bumps\n"
    "                                of 2-3 cm every 0.5 m (drawn from --seed)\n"
    "  --push-impulse N_S            push at the leg frame (default 0: none)\n"
    "  --push-every S                seconds between pushes (default 4)\n"
    "  --push-direction D            lateral (left or right at random, default), forward, backward\n"
    "  --speed-schedule T:V,...      goal speed V m/s at time T s, linear between, held after the\n"
    "                                last (replaces --speed; reports speed tracking)\n"
    "  --drift-window S              position drift over the last S seconds (default: second half)\n"
    "  --seed N                      (default 1)\n"
    "  --trace                       include the leg frame's path every 0.1 s\n"
    "  --json                        print one JSON document\n"
    "\n"
    "optimize options:\n"
    "  --character biped|quadruped   (default biped, or the --params file's character)\n"
    "  --params FILE                 start from this gait file (default: the preset)\n"
    "  --method greedy|cmaes         greedy stochastic search of §3.3 (default) or CMA-ES\n"
    "  --generations N               (default 20)\n"
    "  --candidates K                evaluations per generation (default 10)\n"
    "  --seed S                      (default 1): the same seed gives the same search\n"
    "  --threads T                   evaluations in parallel (default 1)\n"
    "  --out FILE                    where the best gait is written (required)\n"
    "  --seconds S                   length of each evaluation episode (default 800 steps)\n"
    "  --speeds A,B,...              goal speeds each candidate walks at, m/s (default 1.0)\n"
    "  --grounds G,...               grounds each candidate walks on (default flat): flat, slope\n"
    "                                or bumps, each optionally @HEADING (rad it starts facing;\n"
    "                                on the slope 0 climbs first, 3.14159 descends first)\n"
    "  --objective NAME=V,...        objective settings: wd wv wa wr fallPenalty warmup starts\n"
    "                                startImpulse turnRate pushImpulse pushEvery\n"
    "  --json                        print a JSON summary on stdout (progress goes to stderr)\n"
    "  Ctrl-C stops after the current generation and still writes the best so far.\n"
    "\n"
    "schema options:\n"
    "  --character biped|quadruped   only this character (default both)\n"
    "  --json                        print one JSON document\n"
    "\n"
    "options:\n"
    "  --version    print the version and exit\n"
    "  --help       print this help and exit\n";

int usageError(const std::string& message) { return api::usageError("", message); }


// --character, when given, must name a character.
bool characterOption(Options& o, std::optional<gait::Character>* out) {
  const auto it = o.values.find("--character");
  if (it == o.values.end()) return true;
  *out = gait::characterFromName(it->second);
  if (!*out) o.error = "--character: '" + it->second + "' is not biped or quadruped";
  return out->has_value();
}

// Loads a --params gait file for the character given (or the file's own when none is given).
// A refused file is reported as "gaitlab: FILE: FIELD: WHAT" (exit status 2).
int loadParamsOption(const std::string& path, std::optional<gait::Character> expected, gait::GaitFile* file) {
  if (const auto error = gait::loadGaitFile(path, expected, file)) {
    std::fprintf(stderr, "gaitlab: %s: %s\n", path.c_str(), error->describe().c_str());
    return 2;
  }
  return 0;
}

int walk(int argc, char** argv) {
  Options o(argc, argv, 2,
            {"--character", "--params", "--speed", "--turn", "--heading", "--start-push-forward",
             "--start-push-left", "--seconds", "--terrain", "--push-impulse", "--push-every", "--seed",
             "--push-direction", "--speed-schedule", "--drift-window"},
            {"--json", "--trace"});
  if (!o.error.empty()) return usageError(o.error);
  sim::WalkOptions w;
  std::optional<gait::Character> chosen;
  if (!characterOption(o, &chosen)) return usageError(o.error);
  gait::GaitFile file;
  if (o.values.count("--params")) {
    if (const int status = loadParamsOption(o.values["--params"], chosen, &file)) return status;
    chosen = file.character;
    w.params = &file.params;
  }
  const gait::Character c = chosen.value_or(gait::Character::Biped);
  const std::string character = gait::characterName(c);
  w.character = c;
  const std::string terrain = o.values.count("--terrain") ? o.values["--terrain"] : "flat";
  if (!physics::parseTerrain(terrain, &w.terrain))
    return usageError("--terrain: '" + terrain + "' is not flat, slope or bumps");
  double seed = 1;
  if (!o.number("--speed", -5, 5, 1.0, &w.speed) || !o.number("--turn", -3, 3, 0.0, &w.turnRate) ||
      !o.number("--heading", -7, 7, 0.0, &w.heading) ||
      !o.number("--start-push-forward", -1000, 1000, 0.0, &w.startImpulseForward) ||
      !o.number("--start-push-left", -1000, 1000, 0.0, &w.startImpulseLeft) ||
      !o.number("--seconds", 0.01, 3600, 20.0, &w.seconds) ||
      !o.number("--push-impulse", 0, 10000, 0.0, &w.pushImpulse) ||
      !o.number("--push-every", 0.5, 3600, 4.0, &w.pushEvery) ||
      !o.number("--seed", 0, 4294967295.0, 1, &seed) ||
      !o.number("--drift-window", 0, 3600, 0.0, &w.driftWindow))
    return usageError(o.error);
  w.seed = static_cast<uint32_t>(seed);
  const std::string direction = o.values.count("--push-direction") ? o.values["--push-direction"] : "lateral";
  if (direction == "lateral") w.pushDirection = sim::PushDirection::Lateral;
  else if (direction == "forward") w.pushDirection = sim::PushDirection::Forward;
  else if (direction == "backward") w.pushDirection = sim::PushDirection::Backward;
  else return usageError("--push-direction: '" + direction + "' is not lateral, forward or backward");
  if (o.values.count("--speed-schedule")) {
    // T:V pairs separated by commas, times increasing.
    std::stringstream list(o.values["--speed-schedule"]);
    std::string item;
    while (std::getline(list, item, ',')) {
      char* end = nullptr;
      const double t = std::strtod(item.c_str(), &end);
      const double v = *end == ':' ? std::strtod(end + 1, &end) : NAN;
      if (*end != '\0' || !std::isfinite(t) || !std::isfinite(v) || std::abs(v) > 5 ||
          (!w.speedSchedule.empty() && t <= w.speedSchedule.back().first))
        return usageError("--speed-schedule: '" + item + "' is not T:V with T increasing and |V| <= 5");
      w.speedSchedule.emplace_back(t, v);
    }
    if (w.speedSchedule.empty()) return usageError("--speed-schedule: no T:V pairs");
  }
  w.trace = o.flags.count("--trace") > 0;

  const sim::WalkResult r = sim::runWalk(w);
  json out = {
      {"character", character},
      {"terrain", physics::terrainName(w.terrain)},
      {"terrain_hash", r.terrainHash},
      {"seconds", r.seconds},
      {"fell", r.fell},
      {"fall_time_s", r.fell ? json(r.fallTime) : json(nullptr)},
      {"distance_m", r.distance},
      {"mean_speed_m_s", r.meanSpeed},
      {"goal_speed_m_s", r.goalSpeed},
      {"heading_drift_deg", r.headingDrift},
      {"yaw_rate_rad_s", r.yawRate},
      {"goal_turn_rad_s", w.turnRate},
      {"start_heading_rad", w.heading},
      {"duty_factor_measured", r.dutyMeasured},
      {"duty_factor_config", r.dutyConfig},
      {"pushes_applied", r.pushesApplied},
      {"pushes_survived", r.pushesSurvived},
      {"push_impulse_n_s", w.pushImpulse},
      {"push_direction", direction},
      {"position_drift_m", r.positionDrift},
      {"flight_fraction", r.flightFraction},
      {"controller_us_per_step", r.controllerMicrosPerStep},
      {"seed", w.seed},
      {"state_hash", r.stateHash},
  };
  if (!w.speedSchedule.empty()) {
    out["tracking"] = {{"samples", r.trackingSamples}, {"within_10pct", r.trackingWithin},
                       {"worst_relative_error", r.trackingWorst}};
  }
  if (w.trace) out["trace"] = r.trace;
  if (o.flags.count("--json")) {
    std::printf("%s\n", out.dump().c_str());
  } else {
    std::printf("%s\n", out.dump(2).c_str());
  }
  return 0;
}

volatile std::sig_atomic_t g_interrupted = 0;
extern "C" void onInterrupt(int) { g_interrupted = 1; }

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char out[32];
  std::strftime(out, sizeof(out), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return out;
}

json termsJson(const optimize::ObjectiveTerms& t) {
  return {{"total", t.total}, {"fd", t.fd}, {"fv", t.fv}, {"fa", t.fa}, {"fr", t.fr}, {"ft", t.ft},
          {"fall", t.fall}, {"fell", t.fell}, {"seconds", t.seconds}};
}

int optimizeCommand(int argc, char** argv) {
  Options o(argc, argv, 2,
            {"--character", "--params", "--method", "--generations", "--candidates", "--seed",
             "--threads", "--out", "--seconds", "--speeds", "--grounds", "--objective"},
            {"--json"});
  if (!o.error.empty()) return usageError(o.error);
  std::optional<gait::Character> chosen;
  if (!characterOption(o, &chosen)) return usageError(o.error);
  if (!o.values.count("--out")) return usageError("--out FILE is required");
  const std::string outPath = o.values["--out"];

  gait::GaitFile start;
  std::string startName = "preset";
  if (o.values.count("--params")) {
    if (const int status = loadParamsOption(o.values["--params"], chosen, &start)) return status;
    chosen = start.character;
    startName = o.values["--params"];
  }
  optimize::SearchOptions search;
  search.character = chosen.value_or(gait::Character::Biped);
  if (!o.values.count("--params")) start.params = gait::defaultParams(search.character);

  const std::string method = o.values.count("--method") ? o.values["--method"] : "greedy";
  if (!optimize::parseMethod(method, &search.method))
    return usageError("--method: '" + method + "' is not greedy or cmaes");
  double generations = 20, candidates = 10, seed = 1, threads = 1;
  if (!o.number("--generations", 1, 1e6, 20, &generations) ||
      !o.number("--candidates", optimize::kMinCandidates, optimize::kMaxCandidates, 10, &candidates) ||
      !o.number("--seed", 0, 4294967295.0, 1, &seed) ||
      !o.number("--threads", 1, 64, 1, &threads) ||
      !o.number("--seconds", 0.5, 120, search.objective.seconds, &search.objective.seconds))
    return usageError(o.error);
  search.candidates = static_cast<int>(candidates);
  search.seed = static_cast<uint64_t>(seed);
  search.threads = static_cast<int>(threads);
#ifdef __EMSCRIPTEN__
  // The WASM build pre-starts a fixed pthread pool for GL_MAX_THREADS threads (c_api.h).
  search.threads = std::min(search.threads, GL_MAX_THREADS);
#endif
  const auto given = [&](const char* name) {
    return o.values.count(name) ? std::optional<std::string>(o.values[name]) : std::nullopt;
  };
  const std::string settingsError =
      optimize::readObjectiveOptions(given("--speeds"), given("--grounds"), given("--objective"), &search.objective);
  if (!settingsError.empty()) return usageError(settingsError);

  std::string command = "gaitlab";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];

  g_interrupted = 0;
  const auto previous = std::signal(SIGINT, onInterrupt);
  auto optimizer = optimize::Optimizer::create(search, start.params);
  const int total = static_cast<int>(generations);
  json history = json::array();
  // The start's own score, for comparison (one evaluation outside the search's budget).
  const double startObjective = optimizer->score(start.params).total;
  double elapsed = 0;
  for (int g = 0; g < total && !g_interrupted; ++g) {
    const optimize::Generation gen = optimizer->step();
    elapsed += gen.seconds;
    history.push_back({{"generation", gen.index}, {"best_objective", gen.bestObjective},
                       {"evaluations", gen.evaluations}, {"seconds", gen.seconds}});
    const double left = elapsed / gen.index * (total - gen.index);
    std::fprintf(stderr, "gaitlab optimize: generation %d/%d  best %.6g%s  (%.2f s, about %.0f s left)\n",
                 gen.index, total, gen.bestObjective, gen.improved ? " *" : "", gen.seconds, left);
  }
  std::signal(SIGINT, previous);
  const bool interrupted = g_interrupted != 0;
  if (interrupted) std::fprintf(stderr, "gaitlab optimize: interrupted; writing the best so far\n");

  json meta = {{"source", "gaitlab optimize"},
               {"start_objective", startObjective},
               {"command", command},
               {"method", optimize::methodName(search.method)},
               {"seed", search.seed},
               {"objective", optimizer->bestObjective()},
               {"objective_terms", termsJson(optimizer->bestTerms())},
               {"objective_settings", json::parse(optimize::settingsJson(search.objective), nullptr, false)},
               {"start", startName},
               {"generations", optimizer->generation()},
               {"candidates", search.candidates},
               {"evaluations", optimizer->evaluations()},
               {"interrupted", interrupted},
               {"date", utcNow()}};
  {
    std::ofstream out(outPath, std::ios::binary);
    out << gait::gaitFileJson(search.character, optimizer->best(), meta);
    if (!out) {
      std::fprintf(stderr, "gaitlab: %s: cannot be written\n", outPath.c_str());
      return 1;
    }
  }
  json summary = {{"character", gait::characterName(search.character)},
                  {"method", optimize::methodName(search.method)},
                  {"seed", search.seed},
                  {"candidates", search.candidates},
                  {"threads", search.threads},
                  {"generations", optimizer->generation()},
                  {"evaluations", optimizer->evaluations()},
                  {"start_objective", startObjective},
                  {"best_objective", optimizer->bestObjective()},
                  {"best_terms", termsJson(optimizer->bestTerms())},
                  {"determinism_mismatches", optimizer->determinismMismatches()},
                  {"seconds", elapsed},
                  {"seconds_per_generation", optimizer->generation() ? elapsed / optimizer->generation() : 0.0},
                  {"interrupted", interrupted},
                  {"history", history},
                  {"out", outPath}};
  std::printf("%s\n", o.flags.count("--json") ? summary.dump().c_str() : summary.dump(2).c_str());
  return 0;
}

int schema(int argc, char** argv) {
  Options o(argc, argv, 2, {"--character"}, {"--json"});
  std::optional<gait::Character> only;
  if (!o.error.empty() || !characterOption(o, &only)) return usageError(o.error);
  const std::string text = gait::schemaJson(only);
  if (o.flags.count("--json")) {
    std::printf("%s\n", text.c_str());
  } else {
    std::printf("%s\n", nlohmann::ordered_json::parse(text, nullptr, false).dump(2).c_str());
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
  if (cmd == "schema") return schema(argc, argv);
  if (cmd == "optimize") return optimizeCommand(argc, argv);
  return usageError("unknown command '" + cmd + "'");
}

}  // namespace gaitlab::api
