// The C ABI (c_api.h) over sim::Simulation.
#include "api/c_api.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "api/cli_bench.h"
#include "gait/defaults.h"
#include "gait/heading.h"
#include "gait/params_io.h"
#include "gait/schema.h"
#include "optimize/optimizer.h"
#include "sim/simulation.h"

using gaitlab::sim::Kind;
using gaitlab::sim::Simulation;

namespace {
Simulation* sim(void* handle) { return static_cast<Simulation*>(handle); }
thread_local std::string g_string;  // backing store for returned strings
}  // namespace

extern "C" {

const char* gl_version(void) { return GAITLAB_VERSION; }

void* gl_sim_create(int threads, uint32_t seed) {
  if (threads < 1) threads = 1;
  if (threads > GL_MAX_THREADS) threads = GL_MAX_THREADS;
  return new Simulation(threads, seed);
}

void gl_sim_destroy(void* s) { delete sim(s); }

int gl_sim_spawn(void* s, int kind, double x, double z, double heading) {
  if (kind < GL_KIND_BIPED || kind > GL_KIND_BOX) return -1;
  return sim(s)->spawn(static_cast<Kind>(kind), x, z, heading);
}

double gl_cruise_speed(int kind) {
  if (kind != GL_KIND_BIPED && kind != GL_KIND_QUADRUPED) return 0.0;
  return Simulation::cruiseSpeed(static_cast<Kind>(kind));
}

void gl_sim_demo_scene(void* s, int characters) { sim(s)->demoScene(characters); }

void gl_sim_step(void* s, int steps) { sim(s)->step(steps); }

double gl_sim_time(void* s) { return sim(s)->time(); }

uint32_t gl_sim_step_index(void* s) { return sim(s)->stepIndex(); }

int gl_sim_body_count(void* s) { return sim(s)->bodyCount(); }

int gl_sim_threads(void* s) { return sim(s)->threads(); }

const char* gl_sim_state_hash(void* s) {
  g_string = sim(s)->stateHash();
  return g_string.c_str();
}

const void* gl_sim_render_buffer(void* s) { return sim(s)->renderBuffer(); }

// ---- Interaction: the demo page's commands (issue 5) --------------------------------------------

int gl_sim_set_goal(void* s, int id, double speed, double turn_rate) {
  const gaitlab::gait::Goal goal{speed, turn_rate};
  if (id == -1) {
    sim(s)->setGoal(-1, goal);
    return 0;
  }
  const int i = sim(s)->indexOf(id);
  if (i < 0) return -1;
  sim(s)->setGoal(i, goal);
  return 0;
}

int gl_sim_throw_box(void* s, double x, double y, double z, double vx, double vy, double vz,
                     double half) {
  half = std::clamp(half, 0.03, 0.5);
  return sim(s)->throwBox({x, y, z}, {vx, vy, vz}, half);
}

int gl_sim_drag(void* s, int id, int segment, double lx, double ly, double lz, double tx,
                double ty, double tz) {
  return sim(s)->drag(id, segment, {lx, ly, lz}, {tx, ty, tz}) ? 0 : -1;
}

void gl_sim_end_drag(void* s) { sim(s)->endDrag(); }

int gl_sim_reset_character(void* s, int id) { return sim(s)->resetCharacter(id) ? 0 : -1; }

int gl_sim_remove_character(void* s, int id) { return sim(s)->removeCharacter(id) ? 0 : -1; }

void gl_sim_set_auto_reset(void* s, double seconds) {
  sim(s)->setAutoReset(std::max(0.0, seconds));
}

int gl_sim_character_count(void* s) { return sim(s)->characterCount(); }

int gl_sim_character_info(void* s, double* out, int capacity) {
  Simulation& S = *sim(s);
  const int n = S.characterCount();
  for (int i = 0; i < std::min(n, capacity); ++i) {
    const gaitlab::physics::Character& c = S.character(i);
    const auto root = c.segmentState(c.morphology().legFrames[0]);
    double* o = out + i * GL_INFO_FIELDS;
    o[GL_INFO_ID] = S.idOf(i);
    o[GL_INFO_KIND] = static_cast<int>(S.kindOf(i));
    o[GL_INFO_X] = root.position.x();
    o[GL_INFO_Y] = root.position.y();
    o[GL_INFO_Z] = root.position.z();
    o[GL_INFO_HEADING] = gaitlab::gait::headingOf(root.orientation);
    o[GL_INFO_SPEED] = std::hypot(root.linearVelocity.x(), root.linearVelocity.z());
    o[GL_INFO_FALLEN] = S.fallen(i) ? 1 : 0;
    o[GL_INFO_FALLEN_SECONDS] = S.fallenSeconds(i);
    o[GL_INFO_GOAL_SPEED] = S.controller(i).goal().speed;
    o[GL_INFO_GOAL_TURN] = S.controller(i).goal().turnRate;
    o[GL_INFO_PHASE] = S.controller(i).player().phase();
  }
  return n;
}

// ---- Terrain --------------------------------------------------------------------------------

int gl_sim_set_terrain(void* s, int kind) {
  if (kind < GL_TERRAIN_FLAT || kind > GL_TERRAIN_BUMPS) return -1;
  sim(s)->setTerrain(static_cast<gaitlab::physics::TerrainKind>(kind));
  return 0;
}

void gl_sim_terrain_grid(void* s, double* out) {
  const gaitlab::physics::Terrain& t = sim(s)->terrain();
  out[GL_GRID_KIND] = static_cast<int>(t.kind());
  out[GL_GRID_COLUMNS] = t.columns();
  out[GL_GRID_ROWS] = t.rows();
  out[GL_GRID_SPACING] = t.spacing();
  out[GL_GRID_ORIGIN_X] = t.originX();
  out[GL_GRID_ORIGIN_Z] = t.originZ();
  out[GL_GRID_PLANE] = t.planeHeight();
}

const float* gl_sim_terrain_heights(void* s) {
  const gaitlab::physics::Terrain& t = sim(s)->terrain();
  return t.flat() ? nullptr : t.heights().data();
}

double gl_sim_ground_height(void* s, double x, double z) { return sim(s)->groundHeight(x, z); }

}  // extern "C"

// ---- Gait parameters: schema, presets, gait files ----------------------------------------------

namespace {
thread_local std::string g_error;  // gl_last_error()

int fail(int code, std::string message) {
  g_error = std::move(message);
  return code;
}

// The kinds are numbered once (gait::Character); the ABI's numbers and the simulation's say the same.
static_assert(GL_KIND_BIPED == static_cast<int>(gaitlab::gait::Character::Biped) &&
              GL_KIND_QUADRUPED == static_cast<int>(gaitlab::gait::Character::Quadruped));
static_assert(GL_KIND_BIPED == static_cast<int>(Kind::Biped) && GL_KIND_QUADRUPED == static_cast<int>(Kind::Quadruped) &&
              GL_KIND_BOX == static_cast<int>(Kind::Box));

bool characterKind(int kind, gaitlab::gait::Character* c) {
  const auto character = gaitlab::gait::characterFromKind(kind);
  if (character) *c = *character;
  return character.has_value();
}

thread_local std::string g_normalized;  // gl_gait_normalize()

// The characters a parameter call addresses: the one with id `characterId`, or with -1 every
// character of `c`. Returns GL_OK or the error (message set).
int targetsOf(const Simulation& simulation, int characterId, gaitlab::gait::Character c, std::vector<int>* targets) {
  using namespace gaitlab::gait;
  if (characterId < 0) {
    for (int i = 0; i < simulation.characterCount(); ++i) {
      if (characterOf(simulation.character(i).morphology()) == c) targets->push_back(i);
    }
    if (targets->empty()) return fail(GL_ERR_NO_CHARACTER, std::string("no ") + characterName(c) + " in the simulation");
    return GL_OK;
  }
  const int i = simulation.characterIndex(characterId);
  if (i < 0) return fail(GL_ERR_NO_CHARACTER, "no character with id " + std::to_string(characterId));
  if (characterOf(simulation.character(i).morphology()) != c)
    return fail(GL_ERR_KIND, "character " + std::to_string(characterId) + " is not a " + characterName(c));
  targets->push_back(i);
  return GL_OK;
}
}  // namespace

extern "C" {

const char* gl_last_error(void) { return g_error.c_str(); }

const char* gl_schema_json(void) {
  static const std::string schema = gaitlab::gait::schemaJson();
  return schema.c_str();
}

const char* gl_preset_json(int kind) {
  gaitlab::gait::Character c;
  return characterKind(kind, &c) ? gaitlab::gait::presetText(c) : nullptr;
}

int gl_sim_set_params(void* s, int characterId, int kind, const char* text) {
  using namespace gaitlab::gait;
  Character c;
  if (!characterKind(kind, &c)) return fail(GL_ERR_KIND, "kind " + std::to_string(kind) + " is not a character");
  Simulation& simulation = *sim(s);
  std::vector<int> targets;
  if (const int code = targetsOf(simulation, characterId, c, &targets)) return code;
  GaitFile file;
  if (const auto error = parseGaitFile(text ? text : "", c, &file))
    return fail(GL_ERR_INVALID_PARAMS, error->describe());
  for (int i : targets) simulation.controller(i).setParams(file.params);
  g_error.clear();
  return GL_OK;
}

const char* gl_gait_normalize(const char* text) {
  if (const auto error = gaitlab::gait::normalizeGaitFile(text ? text : "", &g_normalized)) {
    fail(GL_ERR_INVALID_PARAMS, error->describe());
    return nullptr;
  }
  g_error.clear();
  return g_normalized.c_str();
}

int gl_sim_patch_params(void* s, int characterId, int kind, const char* patch) {
  using namespace gaitlab::gait;
  Character c;
  if (!characterKind(kind, &c)) return fail(GL_ERR_KIND, "kind " + std::to_string(kind) + " is not a character");
  Simulation& simulation = *sim(s);
  std::vector<int> targets;
  if (const int code = targetsOf(simulation, characterId, c, &targets)) return code;
  // The values are checked once, against the schema, before any character changes: the patch
  // is applied to a scratch copy first, then to each character's own parameters.
  GaitParams scratch = defaultParams(c);
  const std::string text = patch ? patch : "";
  if (const auto error = applyParamsPatch(c, text, &scratch)) return fail(GL_ERR_INVALID_PARAMS, error->describe());
  for (int i : targets) {
    GaitParams params = simulation.controller(i).params();
    applyParamsPatch(c, text, &params);
    simulation.controller(i).setParams(params);
  }
  g_error.clear();
  return GL_OK;
}

const char* gl_sim_get_params(void* s, int characterId) {
  using namespace gaitlab::gait;
  const Simulation& simulation = *sim(s);
  const int i = simulation.characterIndex(characterId);
  if (i < 0) return nullptr;
  g_string = gaitFileJson(characterOf(simulation.character(i).morphology()), simulation.controller(i).params());
  return g_string.c_str();
}

}  // extern "C"

// ---- Optimisation, one generation at a time ---------------------------------------------------

namespace {
struct OptHandle {
  std::unique_ptr<gaitlab::optimize::Optimizer> optimizer;
  gaitlab::gait::Character character;
  std::string text;  // gl_opt_best_json's backing store
};
OptHandle* opt(void* handle) { return static_cast<OptHandle*>(handle); }
}  // namespace

extern "C" {

void* gl_opt_create(int kind, int method, int candidates, uint32_t seed, int threads,
                    const char* startJson, const char* settingsJson) {
  using namespace gaitlab;
  gait::Character c;
  if (!characterKind(kind, &c)) {
    fail(GL_ERR_KIND, "kind " + std::to_string(kind) + " is not a character");
    return nullptr;
  }
  optimize::SearchOptions o;
  o.character = c;
  o.method = method == 1 ? optimize::Method::CmaEs : optimize::Method::Greedy;
  o.candidates = candidates < 2 ? 2 : candidates;
  o.seed = seed;
  o.threads = threads < 1 ? 1 : threads > GL_MAX_THREADS ? GL_MAX_THREADS : threads;
  gait::GaitFile start;
  start.params = gait::defaultParams(c);
  if (startJson) {
    if (const auto error = gait::parseGaitFile(startJson, c, &start)) {
      fail(GL_ERR_INVALID_PARAMS, error->describe());
      return nullptr;
    }
  }
  if (settingsJson) {
    const nlohmann::json j = nlohmann::json::parse(settingsJson, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
      fail(GL_ERR_INVALID_PARAMS, "objective settings: expected a JSON object");
      return nullptr;
    }
    for (const auto& item : j.items()) {
      if (item.key() == "speeds") {
        o.objective.speeds.clear();
        for (const auto& v : item.value()) {
          if (!v.is_number()) {
            fail(GL_ERR_INVALID_PARAMS, "speeds: expected numbers");
            return nullptr;
          }
          const double speed = v.get<double>();
          if (speed < optimize::kMinGoalSpeed || speed > optimize::kMaxGoalSpeed) {
            fail(GL_ERR_INVALID_PARAMS, "speeds: " + v.dump() + " is outside [-5, 5] m/s");
            return nullptr;
          }
          o.objective.speeds.push_back(speed);
        }
        if (!item.value().is_array() || o.objective.speeds.empty()) {
          fail(GL_ERR_INVALID_PARAMS, "speeds: expected a non-empty array of numbers");
          return nullptr;
        }
        continue;
      }
      if (item.key() == "grounds") {
        o.objective.grounds.clear();
        for (const auto& v : item.value()) {
          optimize::Ground g;
          const std::string error = v.is_string() ? optimize::parseGround(v.get<std::string>(), &g)
                                                  : "grounds: expected strings such as \"slope@3.14159\"";
          if (!error.empty()) {
            fail(GL_ERR_INVALID_PARAMS, error);
            return nullptr;
          }
          o.objective.grounds.push_back(g);
        }
        if (!item.value().is_array() || o.objective.grounds.empty()) {
          fail(GL_ERR_INVALID_PARAMS, "grounds: expected a non-empty array of strings");
          return nullptr;
        }
        continue;
      }
      const std::string error = item.value().is_number()
                                    ? optimize::setSetting(o.objective, item.key(), item.value().get<double>())
                                    : item.key() + ": expected a number";
      if (!error.empty()) {
        fail(GL_ERR_INVALID_PARAMS, error);
        return nullptr;
      }
    }
  }
  g_error.clear();
  return new OptHandle{optimize::Optimizer::create(o, start.params), c, {}};
}

const char* gl_opt_settings_json(void) {
  using namespace gaitlab::optimize;
  ObjectiveSettings defaults;
  nlohmann::ordered_json settings = nlohmann::ordered_json::array();
  forEachSetting(defaults, [&](const SettingSpec& spec, double& value) {
    settings.push_back({{"name", spec.name}, {"min", spec.min}, {"max", spec.max}, {"default", value},
                        {"unit", spec.unit}, {"description", spec.description}, {"integer", spec.integer}});
  });
  const nlohmann::ordered_json j = {
      {"settings", settings},
      {"speeds", {{"min", kMinGoalSpeed}, {"max", kMaxGoalSpeed}, {"default", defaults.speeds}, {"unit", "m/s"},
                  {"description", "goal speeds: every candidate walks an episode at each"}}},
      {"grounds", {{"default", nlohmann::ordered_json::array({"flat"})},
                   {"terrains", nlohmann::ordered_json::array({"flat", "slope", "bumps"})},
                   {"description", "grounds: every candidate walks an episode on each, written TERRAIN or "
                                   "TERRAIN@HEADING (rad it starts facing)"}}}};
  g_string = j.dump();
  return g_string.c_str();
}

void gl_opt_destroy(void* h) { delete opt(h); }

double gl_opt_step(void* h) { return opt(h)->optimizer->step().bestObjective; }

int gl_opt_generation(void* h) { return opt(h)->optimizer->generation(); }

int gl_opt_evaluations(void* h) { return opt(h)->optimizer->evaluations(); }

const char* gl_opt_best_json(void* h) {
  using namespace gaitlab;
  const optimize::Optimizer& o = *opt(h)->optimizer;
  const optimize::ObjectiveTerms& t = o.bestTerms();
  const nlohmann::json meta = {
      {"source", "gaitlab optimize (gl_opt)"},
      {"method", optimize::methodName(o.options().method)},
      {"seed", o.options().seed},
      {"objective", o.bestObjective()},
      {"objective_terms", {{"fd", t.fd}, {"fv", t.fv}, {"fa", t.fa}, {"fr", t.fr}, {"ft", t.ft}, {"fall", t.fall}}},
      {"generations", o.generation()},
      {"evaluations", o.evaluations()}};
  opt(h)->text = gait::gaitFileJson(opt(h)->character, o.best(), o.generation() ? meta : nlohmann::json::object());
  return opt(h)->text.c_str();
}

// ---- Benchmark ------------------------------------------------------------------------------

const char* gl_bench_machine(void) {
  g_string = gaitlab::api::benchJsonMachine().dump();
  return g_string.c_str();
}

int gl_bench_max_characters(int legs) { return gaitlab::sim::maxCharacters(legs); }

void gl_bench_warm_up(int legs, int threads) {
  if (legs != 0 && legs != 2 && legs != 4) return;
  gaitlab::sim::warmUp({legs}, threads < 1 ? 1 : threads > GL_MAX_THREADS ? GL_MAX_THREADS : threads);
}

const char* gl_bench_point(int legs, int characters, int threads, int mode, int steps, int runs,
                           int shards, double spacing, uint32_t seed, int frames) {
  g_string.clear();
  if ((legs != 0 && legs != 2 && legs != 4) || characters < 1 ||
      characters > gaitlab::sim::maxCharacters(legs) || mode < 0 ||
      mode > 2 || steps < 1 || runs < 1 || shards < 1 || shards > 64 || !(spacing >= 2.5))
    return g_string.c_str();
  gaitlab::sim::PointSpec s;
  s.legs = legs;
  s.characters = characters;
  s.threads = threads < 1 ? 1 : threads > GL_MAX_THREADS ? GL_MAX_THREADS : threads;
  s.mode = static_cast<gaitlab::sim::Mode>(mode);
  s.steps = steps;
  s.runs = runs;
  s.shards = shards;
  s.spacing = spacing;
  s.seed = seed;
  s.frames = frames != 0;
  g_string = gaitlab::api::benchJsonPoint(gaitlab::sim::runPoint(s)).dump();
  return g_string.c_str();
}

}  // extern "C"
