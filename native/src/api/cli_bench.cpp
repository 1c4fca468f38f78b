#include "api/cli_bench.h"

#include "api/c_api.h"
#include "api/options.h"
#include "body/creature.h"
#include "sim/thread_budget.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <thread>
#include <vector>

#if defined(__EMSCRIPTEN__)
#include <emscripten/emscripten.h>
#else
#include <sys/utsname.h>
#endif

namespace gaitlab::api {

namespace {

using nlohmann::json;

const char* kBenchUsage =
    "usage: gaitlab bench [options]\n"
    "\n"
    "The thesis's performance experiment (Chapter 4): crowds of characters on a grid, each point\n"
    "simulated RUNS times for STEPS fixed steps of 1/120 s, every step timed (controller, physics,\n"
    "whole step). Lists are comma separated; a range is A-B or A-B:STEP.\n"
    "\n"
    "  --legs 2|4|mixed[,...]        bipeds, quadrupeds, or both alternating (default 2)\n"
    "  --creature FILE,...           instead of --legs: a crowd of these creature files' bodies\n"
    "                                (public/creatures/*.json) in turn, each walking at its\n"
    "                                kind's cruise speed (0.4 m/s but for one leg frame's 1 m/s)\n"
    "  --characters LIST             crowd sizes, e.g. 1-100:10 or 1,50,100 (default 1-100:11)\n"
    "  --threads LIST                thread counts, e.g. 1,2,3,4, up to 16 (default 1 and every\n"
    "                                core of the device, e.g. 1,8; in WebAssembly at most the\n"
    "                                module's pthread pool, sized from the cores when it loads)\n"
    "  --mode serial|controller|full[,...]   execution modes (default serial,controller,full)\n"
    "                                serial runs with one thread whatever --threads says\n"
    "  --steps N                     fixed steps per run (default 800, as the thesis)\n"
    "  --runs N                      runs per point (default 20, as the thesis)\n"
    "  --shards N                    physics shards: independent Bullet worlds, 1 to 64; the\n"
    "                                result does not depend on the threads (default 16, fewer\n"
    "                                for a crowd of fewer: one each)\n"
    "  --spacing M                   metres between grid neighbours (default 4)\n"
    "  --seed N                      0 to 4294967295 (default 1)\n"
    "  --frames                      include per-frame mean/sd (thesis Figures 5.1, 5.2)\n"
    "  --json                        print one JSON document (bench/schema.json)\n"
    "  --csv                         print one CSV row per point\n"
    "Progress goes to stderr.\n";

int benchError(const std::string& message) { return usageError("bench", message); }

bool parseInt(const std::string& s, long lo, long hi, long* out) {
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < lo || v > hi) return false;
  *out = v;
  return true;
}

// "1-100:10,150" -> 1, 11, ..., 91, 150 (a range always ends with its last value: 1..91 then 100).
bool parseList(const std::string& text, long lo, long hi, std::vector<int>* out, std::string* error) {
  size_t start = 0;
  while (start <= text.size()) {
    size_t comma = text.find(',', start);
    if (comma == std::string::npos) comma = text.size();
    const std::string item = text.substr(start, comma - start);
    start = comma + 1;
    const size_t dash = item.find('-', 1);
    long a, b, step = 1;
    if (dash == std::string::npos) {
      if (!parseInt(item, lo, hi, &a)) return *error = "'" + item + "' is not a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", false;
      out->push_back(static_cast<int>(a));
      continue;
    }
    const size_t colon = item.find(':', dash);
    const std::string from = item.substr(0, dash);
    const std::string to = item.substr(dash + 1, colon == std::string::npos ? std::string::npos : colon - dash - 1);
    if (!parseInt(from, lo, hi, &a) || !parseInt(to, lo, hi, &b) || b < a ||
        (colon != std::string::npos && !parseInt(item.substr(colon + 1), 1, hi, &step)))
      return *error = "'" + item + "' is not a range A-B[:STEP] within [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", false;
    for (long v = a; v <= b; v += step) out->push_back(static_cast<int>(v));
    if (out->back() != b) out->push_back(static_cast<int>(b));
  }
  return true;
}

// The default --threads: one thread (the thesis's baseline) and every core of the device.
std::string defaultThreadList() {
  const int all = sim::defaultThreads();
  return all == 1 ? "1" : "1," + std::to_string(all);
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

std::string cpuModel() {
  std::FILE* f = std::fopen("/proc/cpuinfo", "r");
  if (!f) return "";
  char line[512];
  std::string model;
  while (std::fgets(line, sizeof line, f)) {
    std::string l = line;
    if (l.rfind("model name", 0) == 0) {
      const size_t colon = l.find(':');
      model = l.substr(colon + 2);
      while (!model.empty() && (model.back() == '\n' || model.back() == ' ')) model.pop_back();
      break;
    }
  }
  std::fclose(f);
  return model;
}

// The 1-minute load average when the benchmark starts (Linux; -1 elsewhere): on a shared
// machine, other processes competing for the cores distort every thread-scaling figure.
double loadAverage() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (!f) return -1;
  double l = -1;
  if (std::fscanf(f, "%lf", &l) != 1) l = -1;
  std::fclose(f);
  return l;
}

#if defined(__EMSCRIPTEN__)
// Which JavaScript host runs the module, and its version: Node's process.version or the
// browser's user agent. Returned in malloc'd memory.
EM_JS(char*, gl_js_host, (), {
  var s = (typeof process === 'object' && process.versions && process.versions.node)
              ? 'node ' + process.version
              : 'browser ' + (typeof navigator === 'object' ? navigator.userAgent : '?');
  var n = lengthBytesUTF8(s) + 1;
  var p = _malloc(n);
  stringToUTF8(s, p, n);
  return p;
});
#endif

json stat(const sim::Stat& s) { return {{"mean", s.mean}, {"sd", s.sd}}; }

json frames(const std::vector<sim::Stat>& f) {
  json mean = json::array(), sd = json::array();
  for (const auto& s : f) {
    mean.push_back(s.mean);
    sd.push_back(s.sd);
  }
  return {{"mean", mean}, {"sd", sd}};
}

std::string legsName(int legs) { return legs == sim::kMixed ? "mixed" : std::to_string(legs); }

// A crowd of creatures as the bench JSON names it: their files' names in turn, "insect+spider".
std::string creatureNames(const std::vector<const body::Morphology*>& creatures) {
  std::string names;
  for (const body::Morphology* m : creatures) names += (names.empty() ? "" : "+") + m->name;
  return names;
}
std::string creatureNames(const std::vector<body::Morphology>& creatures) {
  std::vector<const body::Morphology*> pointers;
  for (const body::Morphology& m : creatures) pointers.push_back(&m);
  return creatureNames(pointers);
}

const char* kCsvHeader =
    "legs,characters,threads,mode,shards,steps,runs,controller_ms_mean,controller_ms_sd,"
    "physics_ms_mean,physics_ms_sd,step_ms_mean,step_ms_sd,step_ms_p50,step_ms_p99,step_ms_max,"
    "step_ms_p99_median_over_runs,controller_us_per_character,heap_bytes,scene_heap_bytes,rss_bytes,state_hash,deterministic";

std::string csvRow(const json& p) {
  char buf[1024];
  const json& m = p["memory"];
  std::snprintf(buf, sizeof buf,
                "%s,%d,%d,%s,%d,%d,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%lld,%lld,%s,%s,%s",
                p["legs"].is_string() ? p["legs"].get<std::string>().c_str()
                                      : std::to_string(p["legs"].get<int>()).c_str(),
                p["characters"].get<int>(), p["threads"].get<int>(),
                p["mode"].get<std::string>().c_str(), p["shards"].get<int>(), p["steps"].get<int>(),
                p["runs"].get<int>(), p["controller_ms"]["mean"].get<double>(),
                p["controller_ms"]["sd"].get<double>(), p["physics_ms"]["mean"].get<double>(),
                p["physics_ms"]["sd"].get<double>(), p["step_ms"]["mean"].get<double>(),
                p["step_ms"]["sd"].get<double>(), p["step_ms"]["p50"].get<double>(),
                p["step_ms"]["p99"].get<double>(), p["step_ms"]["max"].get<double>(),
                p["step_ms"]["p99_median_over_runs"].get<double>(),
                p["controller_us_per_character"].get<double>(),
                static_cast<long long>(m["heap_bytes"].get<int64_t>()),
                static_cast<long long>(m["scene_heap_bytes"].get<int64_t>()),
                m["rss_bytes"].is_null() ? "" : std::to_string(m["rss_bytes"].get<int64_t>()).c_str(),
                p["state_hash"].get<std::string>().c_str(),
                p["deterministic"].get<bool>() ? "true" : "false");
  return buf;
}

}  // namespace

json benchJsonMachine() {
  json m;
  const std::string cpu = cpuModel();
  m["cpu"] = cpu.empty() ? json(nullptr) : json(cpu);
  m["cores"] = static_cast<int>(std::thread::hardware_concurrency());
#if defined(__EMSCRIPTEN__)
  char* host = gl_js_host();
  const std::string h = host;
  std::free(host);
  const bool node = h.rfind("node ", 0) == 0;
  m["runtime"] = node ? "wasm-node" : "wasm-browser";
  m["runtime_version"] = h.substr(h.find(' ') + 1);
  m["os"] = nullptr;
#else
  m["runtime"] = "native";
  m["runtime_version"] = nullptr;
  struct utsname u;
  m["os"] = uname(&u) == 0 ? json(std::string(u.sysname) + " " + u.release + " " + u.machine)
                           : json(nullptr);
#endif
  const double load = loadAverage();
  m["load_average"] = load < 0 ? json(nullptr) : json(load);
  m["compiler"] = __VERSION__;
  m["gaitlab"] = GAITLAB_VERSION;
  return m;
}

json benchJsonPoint(const sim::PointResult& r) {
  const sim::PointSpec& s = r.spec;
  json p = {
      {"legs", s.legs == sim::kMixed ? json("mixed") : json(s.legs)},
      {"characters", s.characters},
      {"threads", s.threads},
      {"mode", sim::modeName(s.mode)},
      {"shards", r.shards},
      {"steps", s.steps},
      {"runs", s.runs},
      {"controller_ms", stat(r.controller)},
      {"physics_ms", stat(r.physics)},
      {"step_ms",
       {{"mean", r.step.mean}, {"sd", r.step.sd}, {"p50", r.stepMedian}, {"p99", r.stepP99},
        {"max", r.stepMax}, {"p99_median_over_runs", r.stepP99MedianOverRuns}}},
      {"controller_us_per_character", r.controller.mean * 1e3 / s.characters},
      {"memory",
       {{"heap_bytes", r.heapBytes},
        {"scene_heap_bytes", r.sceneHeapBytes},
        {"rss_bytes", r.rssBytes < 0 ? json(nullptr) : json(r.rssBytes)}}},
      {"state_hash", r.stateHash},
      {"deterministic", r.deterministic},
  };
  if (!s.creatures.empty()) p["creature"] = creatureNames(s.creatures);
  if (s.frames) {
    p["frames"] = {{"controller_ms", frames(r.frameController)},
                   {"physics_ms", frames(r.framePhysics)},
                   {"step_ms", frames(r.frameStep)}};
  }
  return p;
}

int runBenchCli(int argc, char** argv) {
  std::vector<int> legs, characters, threads;
  std::vector<sim::Mode> modes;
  sim::PointSpec base;
  bool asJson = false, asCsv = false;
  std::string error;
  Options o(argc, argv, 2,
            {"--legs", "--creature", "--characters", "--threads", "--mode", "--steps", "--runs", "--shards",
             "--spacing", "--seed"},
            {"--json", "--csv", "--frames"});
  if (o.help) {
    std::fputs(kBenchUsage, stdout);
    return 0;
  }
  if (!o.error.empty()) return benchError(o.error);
  asJson = o.flags.count("--json") > 0;
  asCsv = o.flags.count("--csv") > 0;
  base.frames = o.flags.count("--frames") > 0;
  const auto text = [&](const char* name, const char* fallback) {
    const auto it = o.values.find(name);
    return it == o.values.end() ? std::string(fallback) : it->second;
  };
  const std::string legsText = text("--legs", "2"), charactersText = text("--characters", "1-100:11"),
                    threadsText = text("--threads", defaultThreadList().c_str()),
                    modesText = text("--mode", "serial,controller,full");
  long long steps, runs, shards, seed;
  if (!o.integer("--steps", 1, 100000, base.steps, &steps) ||
      !o.integer("--runs", 1, 1000, base.runs, &runs) ||
      !o.integer("--shards", 1, 64, base.shards, &shards) ||
      !o.integer("--seed", 0, kMaxSeed, base.seed, &seed) ||
      !o.number("--spacing", 2.5, 100, base.spacing, &base.spacing))
    return benchError(o.error);
  base.steps = static_cast<int>(steps);
  base.runs = static_cast<int>(runs);
  base.shards = static_cast<int>(shards);
  base.seed = static_cast<uint32_t>(seed);
  if (asJson && asCsv) return benchError("--json and --csv are exclusive");
  // Leg counts and modes are words; the rest numbers.
  // A crowd of creatures (body/creature.h): their leg count stands for --legs ("mixed" when it
  // differs among them).
  std::vector<body::Morphology> creatures;
  const bool ofCreature = o.values.count("--creature") > 0;
  if (ofCreature) {
    if (o.values.count("--legs")) return benchError("--creature and --legs: give one of them");
    const std::string list = o.values["--creature"];
    for (size_t start = 0; start <= list.size();) {
      const size_t comma = std::min(list.find(',', start), list.size());
      const std::string file = list.substr(start, comma - start);
      start = comma + 1;
      if (file.empty()) return benchError("--creature: expected FILE,... (an empty name in '" + list + "')");
      creatures.emplace_back();
      if (const auto e = body::loadCreatureFile(file, &creatures.back())) return benchError("--creature: " + file + ": " + e->describe());
    }
  }
  for (size_t start = 0; start <= legsText.size() && !ofCreature;) {
    size_t c = legsText.find(',', start);
    if (c == std::string::npos) c = legsText.size();
    const std::string item = legsText.substr(start, c - start);
    start = c + 1;
    if (item == "2") legs.push_back(sim::kBiped);
    else if (item == "4") legs.push_back(sim::kQuadruped);
    else if (item == "mixed") legs.push_back(sim::kMixed);
    else return benchError("--legs: '" + item + "' is not 2, 4 or mixed");
  }
  for (size_t start = 0; start <= modesText.size();) {
    size_t c = modesText.find(',', start);
    if (c == std::string::npos) c = modesText.size();
    const std::string item = modesText.substr(start, c - start);
    start = c + 1;
    sim::Mode m;
    if (!sim::parseMode(item, &m)) return benchError("--mode: '" + item + "' is not serial, controller or full");
    modes.push_back(m);
  }
  if (ofCreature) {
    const int first = static_cast<int>(creatures.front().legs.size());
    const bool alike = std::all_of(creatures.begin(), creatures.end(), [&](const body::Morphology& m) {
      return static_cast<int>(m.legs.size()) == first;
    });
    legs = {alike ? first : sim::kMixed};
  }
  if (!parseList(charactersText, 1, 2000, &characters, &error)) return benchError("--characters: " + error);
  if (ofCreature) {
    // As many as the render buffer holds of its bodies; in the WASM build a crowd the heap cannot
    // hold is refused when it is built (the point's error).
    size_t segments = 0;  // of the largest body
    for (const body::Morphology& m : creatures) segments = std::max(segments, m.segments.size());
    const int most = sim::Simulation::kRenderCapacity / static_cast<int>(segments);
    if (*std::max_element(characters.begin(), characters.end()) > most)
      return benchError("--characters: more than a simulation holds of " + creatureNames(creatures) + " (" +
                        std::to_string(most) + ")");
  }
  for (int l : legs) {
    if (ofCreature) break;
    // One simulation's render buffer bounds its bodies (Simulation::kRenderCapacity), and in
    // the WASM build its fixed heap (gl_bench_max_characters, as gl_sim_room counts).
    const int most = gl_bench_max_characters(l), largest = *std::max_element(characters.begin(), characters.end());
    if (largest > most)
      return benchError("--characters: " + std::to_string(largest) + " " + (l == sim::kMixed ? std::string("mixed characters") : l == 2 ? "bipeds" : "quadrupeds") +
                        " is more than a simulation holds (" + std::to_string(most) + ")");
  }
  // The WASM build pre-starts a pthread pool sized from the device's cores (sim/thread_budget.h):
  // a point on more threads than it holds would abort the module, so it is refused here.
  // Natively the limit is GL_MAX_THREADS, as for the page on the largest devices.
  if (!parseList(threadsText, 1, sim::maxThreads(), &threads, &error))
    return benchError("--threads: " + error + " (this module's pthread pool serves at most " +
                      std::to_string(sim::maxThreads()) + " threads)");

  // The grid. Serial mode ignores the thread count, so it is measured once, with 1 thread.
  std::vector<sim::PointSpec> grid;
  for (int l : legs)
    for (sim::Mode m : modes)
      for (int t : threads) {
        if (m == sim::Mode::Serial && t != threads.front()) continue;
        for (int n : characters) {
          sim::PointSpec s = base;
          s.legs = l;
          for (const body::Morphology& m : creatures) s.creatures.push_back(&m);
          s.mode = m;
          s.threads = m == sim::Mode::Serial ? 1 : t;
          s.characters = n;
          grid.push_back(s);
        }
      }

  json doc;
  doc["schema"] = kBenchSchema;
  doc["date"] = utcNow();
  doc["machine"] = benchJsonMachine();
  json legsJson = json::array(), modesJson = json::array();
  for (int l : legs) legsJson.push_back(l == sim::kMixed ? json("mixed") : json(l));
  for (sim::Mode m : modes) modesJson.push_back(sim::modeName(m));
  doc["inputs"] = {{"legs", legsJson},         {"characters", characters}, {"threads", threads},
                   {"modes", modesJson},       {"steps", base.steps},      {"runs", base.runs},
                   {"shards", base.shards},    {"spacing_m", base.spacing}, {"seed", base.seed},
                   {"step_hz", 120},           {"frames", base.frames}};
  if (ofCreature) doc["inputs"]["creature"] = creatureNames(creatures);
  doc["points"] = json::array();

  if (asCsv) {
    std::printf("# %s\n# inputs %s\n%s\n", doc["machine"].dump().c_str(), doc["inputs"].dump().c_str(),
                kCsvHeader);
  } else if (!asJson) {
    std::printf("machine: %s\ninputs: %s\n", doc["machine"].dump().c_str(), doc["inputs"].dump().c_str());
    std::printf("%-6s %5s %3s %-10s %12s %12s %12s %10s %10s\n", "legs", "N", "T", "mode",
                "controller", "physics", "step", "step p99", "us/char");
  }
  std::fprintf(stderr, "bench: warming up (untimed)\n");
  sim::warmUp(legs, *std::max_element(threads.begin(), threads.end()));
  for (size_t i = 0; i < grid.size(); ++i) {
    const sim::PointSpec& s = grid[i];
    std::fprintf(stderr, "bench %zu/%zu: legs %s, %d characters, %d threads, %s\n", i + 1,
                 grid.size(), legsName(s.legs).c_str(), s.characters, s.threads, sim::modeName(s.mode));
    const sim::PointResult result = sim::runPoint(s);
    if (!result.error.empty()) return benchError(result.error);
    const json p = benchJsonPoint(result);
    if (!p["deterministic"].get<bool>())
      std::fprintf(stderr, "gaitlab bench: runs of the same point ended in different states\n");
    if (asCsv) {
      std::printf("%s\n", csvRow(p).c_str());
      std::fflush(stdout);
    } else if (!asJson) {
      std::printf("%-6s %5d %3d %-10s %9.4f ms %9.4f ms %9.4f ms %7.3f ms %10.3f\n",
                  legsName(s.legs).c_str(), s.characters, s.threads, sim::modeName(s.mode),
                  p["controller_ms"]["mean"].get<double>(), p["physics_ms"]["mean"].get<double>(),
                  p["step_ms"]["mean"].get<double>(), p["step_ms"]["p99"].get<double>(),
                  p["controller_us_per_character"].get<double>());
      std::fflush(stdout);
    }
    doc["points"].push_back(p);
  }
  if (asJson) std::printf("%s\n", doc.dump().c_str());
  return 0;
}

}  // namespace gaitlab::api
