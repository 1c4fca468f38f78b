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

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>

#include "api/c_api.h"
#include "api/cli_bench.h"
#include "api/options.h"
#include "body/creature.h"
#include "gait/defaults.h"
#include "gait/derived_gait.h"
#include "gait/params_io.h"
#include "gait/schema.h"
#include "optimize/optimizer.h"
#include "optimize/settings.h"
#include "sim/box_hits.h"
#include "sim/thread_budget.h"
#include "sim/walk_trial.h"

namespace gaitlab::api {

namespace {

using nlohmann::json;

// One entry of a timed list (--speed-schedule, --gait-schedule): "T:VALUE", as given and parsed.
struct TimedItem {
  std::string item;   // as given, for messages
  double time = 0;    // s
  std::string value;  // what follows the colon
};

// Splits "T:VALUE,T:VALUE,..." with T a number >= 0, increasing, and VALUE not empty. On a bad
// entry returns false with that entry last in *items (its text for the message).
bool parseTimedList(const std::string& text, std::vector<TimedItem>* items) {
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    char* end = nullptr;
    const double t = std::strtod(item.c_str(), &end);
    const bool ok = end != item.c_str() && *end == ':' && end[1] != '\0' && std::isfinite(t) && t >= 0 &&
                    (items->empty() || t > items->back().time);
    items->push_back({item, t, ok ? std::string(end + 1) : std::string()});
    if (!ok) return false;
  }
  return true;
}

const char* kWalkUsage =
    "usage: gaitlab walk [options]\n"
    "\n"
    "One character walks; prints what it achieved (speed, drift, duty factors...).\n"
    "\n"
    "  --character KIND              biped, quadruped, hexapod or octopod (default biped, or the\n"
    "                                --params file's or the --creature file's)\n"
    "  --params FILE                 gait file (public/presets/*.json format); default: preset\n"
    "                                (hexapod, octopod: the gait derived from the body)\n"
    "  --creature FILE               the character's body from a creature file\n"
    "                                (public/creatures/*.json format); default: the kind's\n"
    "                                shipped body (the insect, the spider for 6 and 8 legs). Its\n"
    "                                leg frames choose the kind: one a biped, two a quadruped,\n"
    "                                three a hexapod, four an octopod\n"
    "  --speed M_S                   goal speed, m/s, -5 to 5 (default 1.0)\n"
    "  --turn RAD_S                  goal turn rate, rad/s, -3 to 3 (default 0)\n"
    "  --heading RAD                 heading it starts facing, about +y (default 0: +z)\n"
    "  --start-phase F               gait phase it starts at, 0 to 1 (default: the gait's own)\n"
    "  --start-push-forward N_S      impulse at the leg frame at t = 0, forward (default 0)\n"
    "  --start-push-left N_S         the same, to the left (default 0)\n"
    "  --seconds S                   simulated time, 0.01 to 3600 (default 20)\n"
    "  --terrain flat|slope|bumps    ground (default flat): slope = ridges and valleys of ±5°\n"
    "                                across the walking direction, bumps = smooth random bumps\n"
    "                                of 2-3 cm every 0.5 m (drawn from --seed)\n"
    "  --push-impulse N_S            push at the leg frame (default 0: none)\n"
    "  --push-every S                seconds between pushes (default 4)\n"
    "  --push-duration S             how long each push lasts, 0 to 0.3 (default 0: the whole\n"
    "                                impulse in one step; 0.2 pushes as Yin et al. 2007 do)\n"
    "  --push-direction D            lateral (left or right at random, default), forward, backward,\n"
    "                                or any (each push one of those at random)\n"
    "  --speed-schedule T:V,...      goal speed V m/s at time T s, linear between, held after the\n"
    "                                last (replaces --speed; reports speed tracking)\n"
    "  --gait-schedule T:FILE,...   take up the gait file FILE at time T s, in mid-stride (as\n"
    "                                the demo's gait menu does); times increasing, at most 16\n"
    "  --drift-window S              position drift over the last S seconds (default: second half)\n"
    "  --box-hits N                  instead of one walk, the box-hit trial: boxes thrown as the\n"
    "                                demo throws them (0.24 m, 8.3 kg, 14 m/s or faster) at random\n"
    "                                body parts, one walking episode each, until N hit, 1 to 1000;\n"
    "                                prints the hits and how many knocked the character over\n"
    "  --get-up S                    with --box-hits: after each fall, watch S seconds more, 0 to\n"
    "                                60, for the character getting up by itself (default 0: the\n"
    "                                episode ends at the fall); counts the falls it got up from\n"
    "  --seed N                      0 to 4294967295 (default 1)\n"
    "  --trace                       include the leg frame's path every 0.1 s\n"
    "  --json                        print one JSON document\n";

const char* kOptimizeUsage =
    "usage: gaitlab optimize --out FILE [options]\n"
    "\n"
    "Searches gait parameters (thesis §3.3) and writes the best as a gait file.\n"
    "\n"
    "  --character KIND              biped, quadruped, hexapod or octopod (default biped, or the\n"
    "                                --params file's or the --creature file's)\n"
    "  --params FILE                 start from this gait file (default: the preset, or the gait\n"
    "                                derived from the body for hexapods and octopods)\n"
    "  --creature FILE               search for this body (a creature file), not the kind's\n"
    "                                shipped one; its leg frames choose the kind\n"
    "  --key M_S                     of a gait with speed keys, tune the key at this speed\n"
    "                                (default: the key nearest the goal speeds' mean, the one the\n"
    "                                episodes walk with most); episodes walk with every key\n"
    "  --hold NAME,...               parameters left as they start: schema names\n"
    "                                (frontLeft.stepTrigger) or a field every leg or leg frame\n"
    "                                has (stepTrigger: every leg's), e.g. to keep a footfall pattern;\n"
    "                                without a turnRate, maxTurnSlip and turnPlacement are held too\n"
    "  --method greedy|cmaes         greedy stochastic search of §3.3 (default) or CMA-ES\n"
    "  --step-size F                 how far a candidate moves, as a share of each parameter's\n"
    "                                range, 0.001 to 1 (default 0.1): greedy moves a parameter by\n"
    "                                up to this, CMA-ES starts with it as its step size; near a\n"
    "                                gait's edge of falling, small steps (0.03) find more\n"
    "  --perturb-probability P       greedy: the chance that each parameter moves, 0.01 to 1\n"
    "                                (default 0.2, the thesis's: a fifth of them)\n"
    "  --generations N               1 to 1000000 (default 20)\n"
    "  --candidates K                evaluations per generation, 2 to 1000 (default 10)\n"
    "  --seed S                      0 to 4294967295 (default 1): the same seed, the same search\n"
    "  --threads T                   evaluations in parallel, 1 to 16 (default: every core of the\n"
    "                                device; the result does not depend on it)\n"
    "  --out FILE                    where the best gait is written (required); checked before\n"
    "                                the search starts, written to a temporary file beside it\n"
    "                                and renamed, so a previous FILE is replaced whole or not at all\n"
    "  --seconds S                   length of each evaluation episode (default 800 steps)\n"
    "  --speeds A,B,...              goal speeds each candidate walks at, m/s (default 1.0)\n"
    "  --grounds G,...               grounds each candidate walks on (default flat): flat, slope\n"
    "                                or bumps, each optionally @HEADING (rad it starts facing;\n"
    "                                on the slope 0 climbs first, 3.14159 descends first)\n"
    "  --objective NAME=V,...        objective settings (listed below)\n"
    "  --json                        print a JSON summary on stdout (progress goes to stderr)\n"
    "  Ctrl-C stops after the current generation and still writes the best so far.\n";

const char* kSchemaUsage =
    "usage: gaitlab schema [options]\n"
    "\n"
    "Prints the gait parameter schema (names, groups, bounds, defaults, units).\n"
    "\n"
    "  --character KIND              only this kind: biped, quadruped, hexapod or octopod\n"
    "                                (default all)\n"
    "  --json                        print one JSON document\n";

const char* kUsage =
    "usage: gaitlab [--version] [--help] <command> [options]\n"
    "\n"
    "Physics-driven procedural locomotion for bipeds and quadrupeds (Bullet Physics).\n"
    "\n"
    "commands (gaitlab COMMAND --help for each one's options):\n"
    "  walk       one character walks; prints what it achieved (speed, drift, duty factors...)\n"
    "  bench      the thesis's performance experiment on crowds\n"
    "  schema     prints the gait parameter schema (names, groups, bounds, defaults, units)\n"
    "  optimize   searches gait parameters (thesis §3.3) and writes the best as a gait file\n"
    "\n"
    "Gait files (--params) are read up to 256 KiB, nested at most 16 deep (README, \"Limits\").\n"
    "\n"
    "options:\n"
    "  --version    print the version and exit\n"
    "  --help       print this help and exit\n";

// --help for a subcommand: its usage on stdout, exit status 0.
int printHelp(const char* usage) {
  std::fputs(usage, stdout);
  return 0;
}

int usageError(const std::string& message) { return api::usageError("", message); }


// --character, when given, must name a character.
bool characterOption(Options& o, std::optional<gait::Character>* out) {
  const auto it = o.values.find("--character");
  if (it == o.values.end()) return true;
  *out = gait::characterFromName(it->second);
  if (!*out) o.error = "--character: '" + it->second + "' is not biped, quadruped, hexapod or octopod";
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

// Loads a --creature file (body/creature.h); its leg frames choose the kind of character, which
// must be the one --character named, if it did: one leg frame a biped, two a quadruped, three a
// hexapod, four an octopod. A refused file is reported as "gaitlab: FILE: FIELD: WHAT" (exit
// status 2).
int loadCreatureOption(const std::string& path, std::optional<gait::Character>* chosen, body::Morphology* out) {
  const auto refuse = [&](const std::string& why) {
    std::fprintf(stderr, "gaitlab: %s: %s\n", path.c_str(), why.c_str());
    return 2;
  };
  if (const auto error = body::loadCreatureFile(path, out)) return refuse(error->describe());
  const size_t frames = out->legFrames.size();
  const gait::Character c = gait::characterOf(*out);
  if (*chosen && **chosen != c)
    return refuse("a body of " + std::to_string(frames) + " leg frame" + (frames == 1 ? "" : "s") + " walks as a " +
                  gait::characterName(c) + ", not as the " + gait::characterName(**chosen) + " --character names");
  *chosen = c;
  return 0;
}

// `gaitlab walk --box-hits N`: the box-hit trial (sim/box_hits.h) with the walk's character,
// gait, goal and ground.
int boxHits(const sim::WalkOptions& w, int hits, double getUpSeconds, bool oneLine) {
  sim::BoxHitOptions b;
  b.walk = w;
  b.hits = hits;
  b.getUpSeconds = getUpSeconds;
  const sim::BoxHitResult r = sim::runBoxHits(b);
  json list = json::array();
  for (const sim::BoxHit& h : r.hits) {
    json hit = {{"segment", h.segment}, {"throw_time_s", h.throwTime}, {"speed_m_s", h.speed}, {"fell", h.fell}};
    if (getUpSeconds > 0 && h.fell)
      hit["got_up_after_s"] = h.gotUpAfter >= 0 ? json(h.gotUpAfter) : json(nullptr);
    list.push_back(hit);
  }
  json out = {
      {"character", gait::characterName(w.character)},
      {"terrain", physics::terrainName(w.terrain)},
      {"goal_speed_m_s", w.speed},
      {"goal_turn_rad_s", w.turnRate},
      {"box_half_m", b.half},
      {"box_throws", r.throws},
      {"box_hits", static_cast<int>(r.hits.size())},
      {"box_hit_falls", r.falls()},
      {"hits", list},
      {"seed", w.seed},
  };
  if (getUpSeconds > 0) {
    out["get_up_watch_s"] = getUpSeconds;
    out["box_hit_get_ups"] = r.getUps();
  }
  std::printf("%s\n", oneLine ? out.dump().c_str() : out.dump(2).c_str());
  return 0;
}

int walk(int argc, char** argv) {
  Options o(argc, argv, 2,
            {"--character", "--params", "--creature", "--speed", "--turn", "--heading", "--start-push-forward",
             "--start-push-left", "--seconds", "--terrain", "--push-impulse", "--push-every", "--seed",
             "--push-direction", "--push-duration", "--speed-schedule", "--gait-schedule", "--drift-window", "--box-hits",
             "--start-phase", "--get-up"},
            {"--json", "--trace"});
  if (o.help) return printHelp(kWalkUsage);
  if (!o.error.empty()) return api::usageError("walk", o.error);
  sim::WalkOptions w;
  std::optional<gait::Character> chosen;
  if (!characterOption(o, &chosen)) return api::usageError("walk", o.error);
  body::Morphology creature;
  if (o.values.count("--creature")) {
    if (const int status = loadCreatureOption(o.values["--creature"], &chosen, &creature)) return status;
    w.body = &creature;
  }
  gait::GaitFile file;
  gait::Gait gait;
  if (o.values.count("--params")) {
    if (const int status = loadParamsOption(o.values["--params"], chosen, &file)) return status;
    chosen = file.character;
    gait = file.gait;
    w.gait = &gait;
  }
  const gait::Character c = chosen.value_or(gait::Character::Biped);
  const std::string character = gait::characterName(c);
  w.character = c;
  const std::string terrain = o.values.count("--terrain") ? o.values["--terrain"] : "flat";
  if (!physics::parseTerrain(terrain, &w.terrain))
    return api::usageError("walk", "--terrain: '" + terrain + "' is not flat, slope or bumps");
  long long seed = 1;
  if (!o.number("--speed", -5, 5, 1.0, &w.speed) || !o.number("--turn", -3, 3, 0.0, &w.turnRate) ||
      !o.number("--heading", -7, 7, 0.0, &w.heading) ||
      !o.number("--start-push-forward", -1000, 1000, 0.0, &w.startImpulseForward) ||
      !o.number("--start-push-left", -1000, 1000, 0.0, &w.startImpulseLeft) ||
      !o.number("--seconds", 0.01, 3600, 20.0, &w.seconds) ||
      !o.number("--push-impulse", 0, 10000, 0.0, &w.pushImpulse) ||
      !o.number("--push-every", 0.5, 3600, 4.0, &w.pushEvery) ||
      !o.number("--push-duration", 0, 0.3, 0.0, &w.pushDuration) ||
      !o.integer("--seed", 0, kMaxSeed, 1, &seed) ||
      !o.number("--drift-window", 0, 3600, 0.0, &w.driftWindow) ||
      !o.number("--start-phase", 0, 1, -1.0, &w.startPhase))
    return api::usageError("walk", o.error);
  w.seed = static_cast<uint32_t>(seed);
  if (o.values.count("--box-hits")) {
    long long hits = 0;
    double getUp = 0;
    if (!o.integer("--box-hits", 1, 1000, 50, &hits) || !o.number("--get-up", 0, 60, 0.0, &getUp))
      return api::usageError("walk", o.error);
    return boxHits(w, static_cast<int>(hits), getUp, o.flags.count("--json") > 0);
  }
  if (o.values.count("--get-up"))
    return api::usageError("walk", "--get-up watches the box-hit trial's falls: give --box-hits too");
  const std::string direction = o.values.count("--push-direction") ? o.values["--push-direction"] : "lateral";
  if (direction == "lateral") w.pushDirection = sim::PushDirection::Lateral;
  else if (direction == "forward") w.pushDirection = sim::PushDirection::Forward;
  else if (direction == "backward") w.pushDirection = sim::PushDirection::Backward;
  else if (direction == "any") w.pushDirection = sim::PushDirection::Any;
  else return api::usageError("walk", "--push-direction: '" + direction + "' is not lateral, forward, backward or any");
  if (o.values.count("--speed-schedule")) {
    // T:V pairs: the goal speed V m/s from T s.
    const auto bad = [](const std::string& item) {
      return api::usageError("walk", "--speed-schedule: '" + item + "' is not T:V with T >= 0 and increasing and |V| <= 5");
    };
    std::vector<TimedItem> items;
    if (!parseTimedList(o.values["--speed-schedule"], &items)) return bad(items.back().item);
    for (const TimedItem& x : items) {
      char* end = nullptr;
      const double v = std::strtod(x.value.c_str(), &end);
      if (*end != '\0' || !std::isfinite(v) || std::abs(v) > 5) return bad(x.item);
      w.speedSchedule.emplace_back(x.time, v);
    }
    if (w.speedSchedule.empty()) return api::usageError("walk", "--speed-schedule: no T:V pairs");
  }
  // Gait files to take up in mid-walk: T:FILE pairs separated by commas, times increasing, each
  // file for the walking character (its own or the one --character or --params chose).
  std::vector<TimedItem> gaitItems;  // the files as given, also for the report
  std::vector<gait::GaitFile> scheduled;
  if (o.values.count("--gait-schedule")) {
    constexpr size_t kMaxScheduledGaits = 16;
    if (!parseTimedList(o.values["--gait-schedule"], &gaitItems))
      return api::usageError("walk", "--gait-schedule: '" + gaitItems.back().item + "' is not T:FILE with T >= 0 and increasing");
    if (gaitItems.empty()) return api::usageError("walk", "--gait-schedule: no T:FILE pairs");
    if (gaitItems.size() > kMaxScheduledGaits)
      return api::usageError("walk", "--gait-schedule: more than " + std::to_string(kMaxScheduledGaits) + " gaits");
    scheduled.resize(gaitItems.size());  // sized once: gaitSchedule points into it
    for (size_t i = 0; i < gaitItems.size(); ++i) {
      if (const int status = loadParamsOption(gaitItems[i].value, c, &scheduled[i])) return status;
      w.gaitSchedule.emplace_back(gaitItems[i].time, &scheduled[i].gait);
    }
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
      {"footfall", gait::footfallName(r.footfall)},
      {"pushes_applied", r.pushesApplied},
      {"pushes_survived", r.pushesSurvived},
      {"push_impulse_n_s", w.pushImpulse},
      {"push_direction", direction},
      {"push_duration_s", w.pushDuration},
      {"position_drift_m", r.positionDrift},
      {"flight_fraction", r.flightFraction},
      {"standing_fraction", r.standingFraction},
      {"gait_changes", r.gaitChanges},
      {"controller_us_per_step", r.controllerMicrosPerStep},
      {"seed", w.seed},
      {"state_hash", r.stateHash},
  };
  if (!w.speedSchedule.empty()) {
    out["tracking"] = {{"samples", r.trackingSamples}, {"within_10pct", r.trackingWithin},
                       {"within_10pct_lag_1s", r.trackingWithinAtFullLag},
                       {"worst_relative_error", r.trackingWorst}};
  }
  if (!w.gaitSchedule.empty()) {
    json list = json::array();
    for (const TimedItem& x : gaitItems) list.push_back({{"time_s", x.time}, {"file", x.value}});
    out["gait_schedule"] = list;
  }
  if (w.trace) out["trace"] = r.trace;
  if (o.flags.count("--json")) {
    std::printf("%s\n", out.dump().c_str());
  } else {
    std::printf("%s\n", out.dump(2).c_str());
  }
  return 0;
}

// A file written whole or not at all: the text goes to a temporary file in the same directory,
// which is renamed over the path only once it is complete and flushed (rename(2) within one
// file system is atomic). The temporary file is made by the constructor, so that a path that
// cannot be written is known before the work whose result it is to hold; a failure at any point
// removes it and leaves whatever was at the path before untouched.
struct OutputFile {
  std::string path, temporary, error;

  explicit OutputFile(const std::string& target) : path(target) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) {
      error = "is a directory";
      return;
    }
    const size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    if (name.empty()) {
      error = "names a directory, not a file";
      return;
    }
    temporary = dir + "." + name + ".tmp-" + std::to_string(::getpid());
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) {
      error = std::string("cannot be written (") + std::strerror(errno) + ")";
      temporary.clear();
      return;
    }
    ::close(fd);
  }
  ~OutputFile() {
    if (!temporary.empty()) ::unlink(temporary.c_str());
  }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Writes `text` and renames it over the path; false (and `error`) if any step fails.
  bool commit(const std::string& text) {
    std::FILE* f = std::fopen(temporary.c_str(), "wb");
    if (!f) return fail("cannot be written");
    bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
    const int writeErrno = errno;
    if (std::fclose(f) != 0) written = false;
    else errno = writeErrno;
    if (!written) return fail("could not be written whole");
    if (::rename(temporary.c_str(), path.c_str()) != 0) return fail("could not be put in place");
    temporary.clear();
    return true;
  }

 private:
  bool fail(const std::string& what) {
    error = what + " (" + std::strerror(errno) + ")";
    return false;
  }
};

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
  json j = {{"total", t.total}, {"fell", t.fell}, {"seconds", t.seconds}};
  for (const optimize::TermName& term : optimize::kTermNames) j[term.name] = t.*term.member;
  return j;
}

int optimizeCommand(int argc, char** argv) {
  Options o(argc, argv, 2,
            {"--character", "--params", "--creature", "--method", "--generations", "--candidates", "--seed",
             "--threads", "--out", "--seconds", "--speeds", "--grounds", "--objective", "--key", "--hold",
             "--step-size", "--perturb-probability"},
            {"--json"});
  if (o.help) {
    // The settings come from the table that parses them, so the help cannot leave one out.
    std::fputs(kOptimizeUsage, stdout);
    std::fputs("\nObjective settings (--objective NAME=V): range, default, meaning\n", stdout);
    optimize::ObjectiveSettings defaults;
    optimize::forEachSetting(defaults, [](const optimize::SettingSpec& spec, double& value) {
      const bool unitless = std::strcmp(spec.unit, "1") == 0;
      std::printf("  %-13s %g to %g%s%s, default %g: %s\n", spec.name, spec.min, spec.max, unitless ? "" : " ",
                  unitless ? "" : spec.unit, value, spec.description);
    });
    return 0;
  }
  if (!o.error.empty()) return api::usageError("optimize", o.error);
  std::optional<gait::Character> chosen;
  if (!characterOption(o, &chosen)) return api::usageError("optimize", o.error);
  if (!o.values.count("--out")) return api::usageError("optimize", "--out FILE is required");
  const std::string outPath = o.values["--out"];

  optimize::SearchOptions search;
  if (o.values.count("--creature")) {
    body::Morphology creature;
    if (const int status = loadCreatureOption(o.values["--creature"], &chosen, &creature)) return status;
    search.body = creature;
  }
  gait::GaitFile start;
  std::string startName = "preset";
  if (o.values.count("--params")) {
    if (const int status = loadParamsOption(o.values["--params"], chosen, &start)) return status;
    chosen = start.character;
    startName = o.values["--params"];
  }
  search.character = chosen.value_or(gait::Character::Biped);
  if (o.values.count("--params")) {
    search.gait = start.gait;
  } else if (search.body && gait::derivesGait(search.character)) {
    // What the body walks when it is spawned (sim::Simulation::spawnBody): its own derived gait.
    search.gait = gait::Gait::single(gait::derivedGait(*search.body), gait::kDerivedFromSpeed);
    startName = "derived";
  } else {
    search.gait = gait::defaultGait(search.character);
    if (gait::derivesGait(search.character)) startName = "derived";
  }
  // The key tuned: the one --key names, else (once the goal speeds are read) optimize::tunedKey.
  std::optional<int> namedKey;
  if (o.values.count("--key")) {
    double speed = 0;
    if (!o.number("--key", 0, 5, 0.0, &speed)) return api::usageError("optimize", o.error);
    namedKey = search.gait.keyAt(speed);
    if (*namedKey < 0) {
      std::string speeds;
      for (const gait::SpeedKey& k : search.gait.keys) speeds += (speeds.empty() ? "" : ", ") + json(k.speed).dump();
      return api::usageError("optimize", "--key: the gait has no key at " + json(speed).dump() +
                                             " m/s; its keys are at " + speeds + " m/s");
    }
  }
  if (o.values.count("--hold")) {
    std::string list = o.values["--hold"];
    for (size_t at = 0; at <= list.size();) {
      const size_t comma = std::min(list.find(',', at), list.size());
      const std::string name = list.substr(at, comma - at);
      if (name.empty()) return api::usageError("optimize", "--hold: expected NAME,... (an empty name in '" + list + "')");
      search.held.push_back(name);
      at = comma + 1;
    }
    std::vector<bool> mask;
    const std::string error = optimize::heldCoordinates(search.character, search.held, &mask);
    if (!error.empty()) return api::usageError("optimize", "--hold: " + error);
  }

  const std::string method = o.values.count("--method") ? o.values["--method"] : "greedy";
  if (!optimize::parseMethod(method, &search.method))
    return api::usageError("optimize", "--method: '" + method + "' is not greedy or cmaes");
  long long generations = 20, candidates = 10, seed = 1, threads = sim::defaultThreads();
  if (!o.integer("--generations", 1, 1000000, 20, &generations) ||
      !o.integer("--candidates", optimize::kMinCandidates, optimize::kMaxCandidates, 10, &candidates) ||
      !o.integer("--seed", 0, kMaxSeed, 1, &seed) ||
      !o.integer("--threads", 1, sim::kMaxThreads, sim::defaultThreads(), &threads) ||
      !o.number("--seconds", 0.5, 120, search.objective.seconds, &search.objective.seconds) ||
      !o.number("--step-size", 0.001, 1, search.stepScale, &search.stepScale) ||
      !o.number("--perturb-probability", 0.01, 1, search.perturbProbability, &search.perturbProbability))
    return api::usageError("optimize", o.error);
  search.cmaSigma = search.stepScale;  // one step size, as a share of the range, for both methods
  search.candidates = static_cast<int>(candidates);
  search.seed = static_cast<uint64_t>(seed);
  search.threads = static_cast<int>(threads);
  // The WASM build's pthread pool is sized from the device's cores (sim/thread_budget.h); a
  // search on more threads than it holds would abort the module. Natively this is kMaxThreads.
  search.threads = std::min(search.threads, sim::maxThreads());
  const auto given = [&](const char* name) {
    return o.values.count(name) ? std::optional<std::string>(o.values[name]) : std::nullopt;
  };
  const std::string settingsError =
      optimize::readObjectiveOptions(given("--speeds"), given("--grounds"), given("--objective"), &search.objective);
  if (!settingsError.empty()) return api::usageError("optimize", settingsError);
  search.key = namedKey.value_or(optimize::tunedKey(search.gait, search.objective.speeds));
  const gait::GaitParams tuned = search.gait.keys[search.key].params;

  std::string command = "gaitlab";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];

  // The output is checked before the search, not after it: its temporary file is made now, beside
  // it, so that a directory that does not exist or cannot be written, or a name the system
  // refuses, is said at once. The result goes there and is renamed over --out at the end.
  OutputFile output(outPath);
  if (!output.error.empty()) {
    std::fprintf(stderr, "gaitlab optimize: %s: %s; nothing was searched\n", outPath.c_str(), output.error.c_str());
    return 1;
  }

  g_interrupted = 0;
  const auto previous = std::signal(SIGINT, onInterrupt);
  auto optimizer = optimize::Optimizer::create(search, tuned);
  const int total = static_cast<int>(generations);
  json history = json::array();
  // The start's own score, for comparison (one evaluation outside the search's budget).
  const double startObjective = optimizer->startTerms().total;
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
               {"creature", o.values.count("--creature") ? json(o.values["--creature"]) : json(nullptr)},
               {"generations", optimizer->generation()},
               {"candidates", search.candidates},
               {"evaluations", optimizer->evaluations()},
               {"interrupted", interrupted},
               {"date", utcNow()}};
  // Ctrl-C stays caught until the file is in place: a second one while it is written changes
  // nothing (the write is short), rather than leaving the temporary file behind.
  const bool committed = output.commit(gait::gaitFileJson(search.character, optimizer->gaitWith(optimizer->best()), meta));
  std::signal(SIGINT, previous);
  if (!committed) {
    std::fprintf(stderr,
                 "gaitlab optimize: %s: %s; any previous file there is left as it was (best objective "
                 "%.6g, not saved)\n",
                 outPath.c_str(), output.error.c_str(), optimizer->bestObjective());
    return 1;
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
  // Strings from the command line may not be UTF-8: written as U+FFFD rather than aborting.
  const auto replace = json::error_handler_t::replace;
  std::printf("%s\n", summary.dump(o.flags.count("--json") ? -1 : 2, ' ', false, replace).c_str());
  return 0;
}

int schema(int argc, char** argv) {
  Options o(argc, argv, 2, {"--character"}, {"--json"});
  if (o.help) return printHelp(kSchemaUsage);
  std::optional<gait::Character> only;
  if (!o.error.empty() || !characterOption(o, &only)) return api::usageError("schema", o.error);
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
