// The C ABI (c_api.h) over sim::Simulation, optimize::Optimizer and sim::runPoint. Every refusal
// goes through refuse(), which sets gl_last_error's message; see the contract in c_api.h.
#include "api/c_api.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "api/cli_bench.h"
#include "api/handles.h"
#include "api/limits.h"
#include "body/creature.h"
#include "body/morphology.h"
#include "sim/capacity.h"
#include "gait/defaults.h"
#include "gait/derived_gait.h"
#include "gait/heading.h"
#include "gait/params_io.h"
#include "gait/schema.h"
#include "optimize/optimizer.h"
#include "optimize/settings.h"
#include "peers/morphology_json.h"
#include "peers/reference_scene.h"
#include "sim/simulation.h"
#include "sim/thread_budget.h"

using gaitlab::api::SimHandle;
using gaitlab::gait::Character;
using gaitlab::sim::Simulation;

namespace {

thread_local std::string g_error;  // gl_last_error()

// A refusal: the message names what was refused; the value is what the function returns then
// (a negative GL_ERR_* code, nullptr, or NaN).
template <class T>
T refuse(T value, std::string message) {
  g_error = std::move(message);
  return value;
}
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

SimHandle* handle(void* h) { return static_cast<SimHandle*>(h); }
Simulation* sim(void* h) { return &handle(h)->simulation; }

int clampThreads(int threads) { return std::clamp(threads, 1, GL_MAX_THREADS); }

bool isFinite(double v) { return std::isfinite(v); }

std::string str(int v) { return std::to_string(v); }
// nlohmann writes NaN and infinity as null: say what they are.
std::string str(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
  return nlohmann::json(v).dump();
}
std::string str(const double (&v)[3]) { return "(" + str(v[0]) + ", " + str(v[1]) + ", " + str(v[2]) + ")"; }

// A number a command carries, checked where it enters (api/limits.h): finite, and |v| <= max.
// Returns the refusal's message ("NAME: VALUE is not finite" / "... is outside [-MAX, MAX]"), or
// an empty string.
std::string outOfRange(const std::string& name, double v, double max) {
  if (!isFinite(v)) return name + ": " + str(v) + " is not finite";
  if (std::abs(v) > max) return name + ": " + str(v) + " is outside [" + str(-max) + ", " + str(max) + "]";
  return "";
}
std::string outOfRange(const std::string& name, const double (&v)[3], double max) {
  for (double x : v) {
    if (!isFinite(x)) return name + ": " + str(v) + " is not finite";
  }
  for (double x : v) {
    if (std::abs(x) > max) return name + ": " + str(v) + " has a coordinate outside [" + str(-max) + ", " + str(max) + "]";
  }
  return "";
}

// Threads: every simulation, search and benchmark point takes its workers from the WASM build's
// pthread pool and gives them back when it ends (sim/thread_budget.h).
using gaitlab::sim::giveWorkers;
using gaitlab::sim::noWorkers;
using gaitlab::sim::takeWorkers;
static_assert(GL_MAX_THREADS == gaitlab::sim::kMaxThreads, "one most-threads figure");

// The message of a spawn refused for want of room: what is full.
std::string noRoom(void* s, int kind) {
  return "no room: " + handle(s)->simulation.fullReason(gaitlab::gait::characterFromKind(kind));
}

// Character types are numbered once (gait::kindNumber); the ABI's numbers say the same.
static_assert(GL_KIND_BIPED == gaitlab::gait::kindNumber(Character::Biped) &&
              GL_KIND_QUADRUPED == gaitlab::gait::kindNumber(Character::Quadruped) &&
              GL_KIND_HEXAPOD == gaitlab::gait::kindNumber(Character::Hexapod) &&
              GL_KIND_OCTOPOD == gaitlab::gait::kindNumber(Character::Octopod));

bool characterKind(int kind, gaitlab::gait::Character* c) {
  const auto character = gaitlab::gait::characterFromKind(kind);
  if (character) *c = *character;
  return character.has_value();
}
std::string notACharacter(int kind) {
  return "kind: " + str(kind) + " is not a character's (GL_KIND_BIPED, GL_KIND_QUADRUPED, GL_KIND_HEXAPOD or GL_KIND_OCTOPOD)";
}
std::string notAThing(int kind) { return "kind: " + str(kind) + " is neither a character's nor GL_KIND_BOX"; }
std::string noCharacter(int id) { return "id: no character has id " + str(id); }
// A creature file's text read into `body`: "" or the refusal's message, "creature: FIELD: WHAT".
std::string readCreature(const char* json, gaitlab::body::Morphology* body) {
  const auto error = gaitlab::body::parseCreatureFile(json ? json : "", body);
  return error ? "creature: " + error->describe() : "";
}
std::string noRoomForCreature(const gaitlab::body::Morphology& body) {
  return "no room for the creature's " + str(static_cast<int>(body.segments.size())) + " bodies";
}
// A thrown box's half size (api/limits.h), or the refusal's message.
std::string outOfHalf(double half) {
  using namespace gaitlab::limits;
  if (half >= kMinThrowHalf && half <= kMaxThrowHalf) return "";
  return "half: " + str(half) + " is outside [" + str(kMinThrowHalf) + ", " + str(kMaxThrowHalf) + "] m";
}

bool benchLegs(int legs) { return legs == GL_LEGS_MIXED || legs == GL_LEGS_BIPED || legs == GL_LEGS_QUADRUPED; }
std::string notLegs(int legs) { return "legs: " + str(legs) + " is not 0 (mixed), 2 or 4"; }

// The largest crowd of `legs` a new simulation holds: the render buffer's room, and in the WASM
// build what the heap left can afford (sim/capacity.h) beside the simulation itself, so that
// gl_bench_max_characters agrees with gl_sim_room.
int benchMaxCharacters(int legs) {
  using namespace gaitlab::sim;
  const int render = maxCharacters(legs);
  const int64_t headroom = heapHeadroom();
  if (headroom < 0) return render;
  const int64_t left = std::max<int64_t>(0, headroom - kSimulationBytes);
  const int biped = static_cast<int>(gaitlab::body::makeBiped().segments.size());
  const int quadruped = static_cast<int>(gaitlab::body::makeQuadruped().segments.size());
  const int64_t heap = legs == GL_LEGS_BIPED ? affordable(left, kBipedBytes, biped, 0)
                       : legs == GL_LEGS_QUADRUPED ? affordable(left, kQuadrupedBytes, quadruped, 0)
                                                   : 2 * affordable(left, kBipedBytes + kQuadrupedBytes, biped + quadruped, 0);
  return static_cast<int>(std::min<int64_t>(render, heap));
}

// The characters a parameter call addresses: the one with id `characterId`, or with -1 every
// character of `kind` (whose gait::Character goes to `out`). Returns GL_OK or the refusal.
int targetsOf(const Simulation& simulation, int characterId, int kind, gaitlab::gait::Character* out,
              std::vector<int>* targets) {
  using namespace gaitlab::gait;
  if (!characterKind(kind, out)) return refuse(GL_ERR_KIND, notACharacter(kind));
  const Character c = *out;
  if (characterId < 0) {
    for (int i = 0; i < simulation.characterCount(); ++i) {
      if (characterOf(simulation.character(i).morphology()) == c) targets->push_back(i);
    }
    if (targets->empty()) return refuse(GL_ERR_NO_CHARACTER, std::string("id: -1, and no ") + characterName(c) + " is in the simulation");
    return GL_OK;
  }
  const int i = simulation.characterIndex(characterId);
  if (i < 0) return refuse(GL_ERR_NO_CHARACTER, noCharacter(characterId));
  if (characterOf(simulation.character(i).morphology()) != c)
    return refuse(GL_ERR_KIND, "kind: character " + str(characterId) + " is not a " + characterName(c));
  targets->push_back(i);
  return GL_OK;
}

}  // namespace

extern "C" {

const char* gl_last_error(void) { return g_error.c_str(); }

const char* gl_version(void) { return GAITLAB_VERSION; }

int gl_max_threads(void) { return GL_MAX_THREADS; }

int gl_pool_threads(void) { return gaitlab::sim::maxThreads(); }

int gl_default_threads(void) { return gaitlab::sim::defaultThreads(); }

// ---- Simulation ----------------------------------------------------------------------------

void* gl_sim_create(int threads, uint32_t seed) {
  threads = clampThreads(threads);
  const int64_t headroom = gaitlab::sim::heapHeadroom();
  const int64_t needs = gaitlab::sim::kSimulationBytes + std::max(0, threads - 2) * gaitlab::sim::kWorkerStackBytes;
  if (headroom >= 0 && headroom < needs)
    return refuse<void*>(nullptr, "memory: a simulation on " + str(threads) + " threads needs " + str(static_cast<int>(needs >> 20)) +
                                      " MiB and the module has " + str(static_cast<int>(headroom >> 20)) + " MiB left beside its reserve");
  if (!takeWorkers(threads)) return refuse<void*>(nullptr, noWorkers(threads));
  return new SimHandle(threads, seed);
}

void gl_sim_destroy(void* s) {
  if (!s) return;
  const int threads = sim(s)->threads();
  delete handle(s);
  giveWorkers(threads);
}

int gl_sim_room(void* s, int kind) {
  Character c;
  if (characterKind(kind, &c)) return sim(s)->characterRoom(c);
  if (kind == GL_KIND_BOX) return sim(s)->boxRoom();
  return refuse(GL_ERR_ARGUMENT, notAThing(kind));
}

int gl_sim_spawn(void* s, int kind, double x, double z, double heading) {
  Character c;
  const bool character = characterKind(kind, &c);
  if (!character && kind != GL_KIND_BOX) return refuse(GL_ERR_ARGUMENT, notAThing(kind));
  using namespace gaitlab::limits;
  for (const std::string& e : {outOfRange("x", x, kMaxCoordinate), outOfRange("z", z, kMaxCoordinate),
                               outOfRange("heading", heading, kMaxHeading)}) {
    if (!e.empty()) return refuse(GL_ERR_ARGUMENT, e);
  }
  if (gl_sim_room(s, kind) < 1) return refuse(GL_ERR_FULL, noRoom(s, kind));
  const int id = character ? sim(s)->spawn(c, x, z, heading) : sim(s)->spawnBox(x, z, heading);
  if (id < 0) return refuse(GL_ERR_FULL, noRoom(s, kind));
  return id;
}

double gl_top_speed(int kind) {
  Character c;
  if (!characterKind(kind, &c)) return refuse(kNaN, notACharacter(kind));
  return gaitlab::gait::defaultGait(c).keys.back().speed;
}

double gl_cruise_speed(int kind) {
  Character c;
  if (!characterKind(kind, &c)) return refuse(kNaN, notACharacter(kind));
  return Simulation::cruiseSpeed(c);
}

int gl_sim_add_characters(void* s, int kind, int count) {
  if (count < 0) return refuse(GL_ERR_ARGUMENT, "count: " + str(count) + " is negative");
  if (kind == GL_LAYOUT_ALTERNATING) return sim(s)->addCharacters(gaitlab::sim::Crowd::Mixed, count);
  if (kind == GL_KIND_BIPED) return sim(s)->addCharacters(gaitlab::sim::Crowd::Bipeds, count);
  if (kind == GL_KIND_QUADRUPED) return sim(s)->addCharacters(gaitlab::sim::Crowd::Quadrupeds, count);
  if (kind == GL_KIND_HEXAPOD) return sim(s)->addCharacters(gaitlab::sim::Crowd::Hexapods, count);
  if (kind == GL_KIND_OCTOPOD) return sim(s)->addCharacters(gaitlab::sim::Crowd::Octopods, count);
  return refuse(GL_ERR_ARGUMENT, "kind: " + str(kind) + " is neither a character's nor GL_LAYOUT_ALTERNATING");
}

int gl_sim_add_apart(void* s, int kind) {
  Character c;
  if (!characterKind(kind, &c)) return refuse(GL_ERR_ARGUMENT, notACharacter(kind));
  const int id = sim(s)->addApart(c);
  if (id < 0) return refuse(GL_ERR_FULL, noRoom(s, kind));
  return id;
}

int gl_sim_spawn_creature(void* s, const char* creatureJson, double x, double z, double heading) {
  using namespace gaitlab::limits;
  for (const std::string& e : {outOfRange("x", x, kMaxCoordinate), outOfRange("z", z, kMaxCoordinate),
                               outOfRange("heading", heading, kMaxHeading)}) {
    if (!e.empty()) return refuse(GL_ERR_ARGUMENT, e);
  }
  gaitlab::body::Morphology body;
  if (const std::string error = readCreature(creatureJson, &body); !error.empty()) return refuse(GL_ERR_ARGUMENT, error);
  const int id = sim(s)->spawnCreature(body, x, z, heading);
  if (id < 0) return refuse(GL_ERR_FULL, noRoomForCreature(body));
  return id;
}

int gl_sim_add_apart_creature(void* s, const char* creatureJson) {
  gaitlab::body::Morphology body;
  if (const std::string error = readCreature(creatureJson, &body); !error.empty()) return refuse(GL_ERR_ARGUMENT, error);
  const int id = sim(s)->addApartCreature(body);
  if (id < 0) return refuse(GL_ERR_FULL, noRoomForCreature(body));
  return id;
}

int gl_sim_demo_scene(void* s, int characters) {
  if (characters < 0) return refuse(GL_ERR_ARGUMENT, "characters: " + str(characters) + " is negative");
  sim(s)->demoScene(characters);
  return GL_OK;
}

int gl_sim_step(void* s, int steps) {
  if (steps < 0 || steps > gaitlab::limits::kMaxStepsPerCall)
    return refuse(GL_ERR_ARGUMENT, "steps: " + str(steps) + " is outside [0, " + str(gaitlab::limits::kMaxStepsPerCall) + "]");
  sim(s)->step(steps);
  return GL_OK;
}

double gl_sim_time(void* s) { return sim(s)->time(); }

uint32_t gl_sim_step_index(void* s) { return sim(s)->stepIndex(); }

int gl_sim_body_count(void* s) { return sim(s)->bodyCount(); }

int gl_sim_threads(void* s) { return sim(s)->threads(); }

const char* gl_sim_state_hash(void* s) {
  handle(s)->text = sim(s)->stateHash();
  return handle(s)->text.c_str();
}

const void* gl_sim_render_buffer(void* s) { return sim(s)->renderBuffer(); }

// ---- Gait parameters -------------------------------------------------------------------------

const char* gl_schema_json(void) {
  static const std::string schema = gaitlab::gait::schemaJson();
  return schema.c_str();
}

const char* gl_preset_json(int kind) {
  gaitlab::gait::Character c;
  if (!characterKind(kind, &c)) return refuse<const char*>(nullptr, notACharacter(kind));
  return gaitlab::gait::presetText(c);
}

int gl_sim_set_params(void* s, int characterId, int kind, const char* text) {
  using namespace gaitlab::gait;
  Character c;
  std::vector<int> targets;
  if (const int code = targetsOf(*sim(s), characterId, kind, &c, &targets)) return code;
  Simulation& simulation = *sim(s);
  GaitFile file;
  if (const auto error = parseGaitFile(text ? text : "", c, &file))
    return refuse(GL_ERR_INVALID_PARAMS, error->describe());
  for (int i : targets) simulation.controller(i).setGait(file.gait);
  return GL_OK;
}

const char* gl_gait_normalize(const char* text) {
  thread_local std::string normalized;
  if (const auto error = gaitlab::gait::normalizeGaitFile(text ? text : "", &normalized))
    return refuse<const char*>(nullptr, error->describe());
  return normalized.c_str();
}

int gl_sim_patch_params(void* s, int characterId, int kind, const char* patch) {
  using namespace gaitlab::gait;
  Character c;
  std::vector<int> targets;
  if (const int code = targetsOf(*sim(s), characterId, kind, &c, &targets)) return code;
  Simulation& simulation = *sim(s);
  // The values are checked once, against the schema, before any character changes: the patch
  // is applied to a scratch copy first, then to each character's own parameters.
  // A patch edits each character's primary key (its gait file's "params") and, when it names
  // them, that key's speed and the other speed keys (gait/params_io.h, applyGaitPatch).
  const std::string text = patch ? patch : "";
  Gait scratch = defaultGait(c);  // checked once even when no character is targeted
  if (const auto error = applyGaitPatch(c, text, &scratch)) return refuse(GL_ERR_INVALID_PARAMS, error->describe());
  std::vector<Gait> patched;
  for (int i : targets) {
    patched.push_back(simulation.controller(i).gait());
    if (const auto error = applyGaitPatch(c, text, &patched.back())) return refuse(GL_ERR_INVALID_PARAMS, error->describe());
  }
  for (size_t t = 0; t < targets.size(); ++t) simulation.controller(targets[t]).setGait(patched[t]);
  return GL_OK;
}

const char* gl_sim_get_params(void* s, int characterId) {
  using namespace gaitlab::gait;
  const Simulation& simulation = *sim(s);
  const int i = simulation.characterIndex(characterId);
  if (i < 0) return refuse<const char*>(nullptr, noCharacter(characterId));
  handle(s)->text = gaitFileJson(characterOf(simulation.character(i).morphology()), simulation.controller(i).gait());
  return handle(s)->text.c_str();
}

// ---- Interaction: the demo page's commands --------------------------------------------------

int gl_sim_set_goal(void* s, int id, double speed, double turn_rate) {
  for (const std::string& e : {outOfRange("goal speed", speed, gaitlab::limits::kMaxGoalSpeed),
                               outOfRange("goal turn rate", turn_rate, gaitlab::limits::kMaxGoalTurn)}) {
    if (!e.empty()) return refuse(GL_ERR_ARGUMENT, e);
  }
  const gaitlab::gait::Goal goal{speed, turn_rate};
  if (id == -1) {
    sim(s)->setGoal(-1, goal);
    return GL_OK;
  }
  const int i = sim(s)->indexOf(id);
  if (i < 0) return refuse(GL_ERR_NO_CHARACTER, noCharacter(id));
  sim(s)->setGoal(i, goal);
  return GL_OK;
}

void gl_throw_defaults(gl_throw_settings* t) { *t = gl_throw_settings{{0, 1, 0}, {0, 0, 0}, 0.12}; }

int gl_sim_throw_box(void* s, const gl_throw_settings* t) {
  using namespace gaitlab::limits;
  for (const std::string& e : {outOfRange("from", t->from, kMaxCoordinate), outOfRange("velocity", t->velocity, kMaxThrowSpeed)}) {
    if (!e.empty()) return refuse(GL_ERR_ARGUMENT, e);
  }
  if (std::hypot(t->velocity[0], t->velocity[1], t->velocity[2]) > kMaxThrowSpeed)
    return refuse(GL_ERR_ARGUMENT, "velocity: " + str(t->velocity) + " is faster than " + str(kMaxThrowSpeed) + " m/s");
  if (const std::string e = outOfHalf(t->half); !e.empty()) return refuse(GL_ERR_ARGUMENT, e);
  const int id = sim(s)->throwBox({t->from[0], t->from[1], t->from[2]},
                                  {t->velocity[0], t->velocity[1], t->velocity[2]}, t->half);
  if (id < 0) return refuse(GL_ERR_FULL, noRoom(s, GL_KIND_BOX));
  return id;
}

void gl_throw_at_defaults(gl_throw_at_settings* t) { *t = gl_throw_at_settings{-1, 0, {0, 1, 0}, {0, 0, 0}, 14, 0.12}; }

int gl_sim_throw_at(void* s, const gl_throw_at_settings* t) {
  using namespace gaitlab::limits;
  for (const std::string& e : {outOfRange("from", t->from, kMaxCoordinate), outOfRange("local", t->local, kMaxDragLocal),
                               outOfRange("speed", t->speed, kMaxThrowSpeed), outOfHalf(t->half)}) {
    if (!e.empty()) return refuse(GL_ERR_ARGUMENT, e);
  }
  if (!(t->speed >= kMinAimSpeed))
    return refuse(GL_ERR_ARGUMENT, "speed: " + str(t->speed) + " is outside [" + str(kMinAimSpeed) + ", " + str(kMaxThrowSpeed) + "] m/s");
  const int i = sim(s)->indexOf(t->id);
  if (i < 0) return refuse(GL_ERR_NO_CHARACTER, noCharacter(t->id));
  if (t->segment < 0 || t->segment >= sim(s)->character(i).segmentCount())
    return refuse(GL_ERR_ARGUMENT, "segment: character " + str(t->id) + " has no segment " + str(t->segment));
  const Eigen::Vector3d from(t->from[0], t->from[1], t->from[2]);
  const auto aim = sim(s)->aimAt(i, t->segment, {t->local[0], t->local[1], t->local[2]}, from, t->speed);
  // A long flight at a low speed needs a steep lob; one faster than any throw is refused.
  if (!(aim.velocity.norm() <= kMaxThrowSpeed))
    return refuse(GL_ERR_ARGUMENT, "speed: the throw at character " + str(t->id) + " needs " + str(aim.velocity.norm()) +
                                       " m/s, faster than " + str(kMaxThrowSpeed) + " m/s (it is too far for a throw at " +
                                       str(t->speed) + " m/s)");
  const int id = sim(s)->throwBox(from, aim.velocity, t->half);
  if (id < 0) return refuse(GL_ERR_FULL, noRoom(s, GL_KIND_BOX));
  return id;
}

void gl_drag_defaults(gl_drag_settings* d) { *d = gl_drag_settings{-1, 0, {0, 0, 0}, {0, 0, 0}}; }

int gl_sim_drag(void* s, const gl_drag_settings* d) {
  for (const std::string& e : {outOfRange("local", d->local, gaitlab::limits::kMaxDragLocal),
                               outOfRange("target", d->target, gaitlab::limits::kMaxCoordinate)}) {
    if (!e.empty()) return refuse(GL_ERR_ARGUMENT, e);
  }
  if (sim(s)->indexOf(d->id) < 0) return refuse(GL_ERR_NO_CHARACTER, noCharacter(d->id));
  if (!sim(s)->drag(d->id, d->segment, {d->local[0], d->local[1], d->local[2]},
                    {d->target[0], d->target[1], d->target[2]}))
    return refuse(GL_ERR_ARGUMENT, "segment: character " + str(d->id) + " has no segment " + str(d->segment));
  return GL_OK;
}

void gl_sim_end_drag(void* s) { sim(s)->endDrag(); }

int gl_sim_reset_character(void* s, int id) {
  return sim(s)->resetCharacter(id) ? GL_OK : refuse(GL_ERR_NO_CHARACTER, noCharacter(id));
}

int gl_sim_remove_character(void* s, int id) {
  return sim(s)->removeCharacter(id) ? GL_OK : refuse(GL_ERR_NO_CHARACTER, noCharacter(id));
}

int gl_sim_set_auto_reset(void* s, double seconds) {
  if (!(seconds >= 0) || !(seconds <= gaitlab::limits::kMaxAutoReset))
    return refuse(GL_ERR_ARGUMENT, "seconds: " + str(seconds) + " is outside [0, " + str(gaitlab::limits::kMaxAutoReset) + "]");
  sim(s)->setAutoReset(seconds);
  return GL_OK;
}

int gl_sim_character_count(void* s) { return sim(s)->characterCount(); }

int gl_sim_set_wander(void* s, int id, double arena_radius) {
  if (!isFinite(arena_radius) || (arena_radius != 0 && (arena_radius < 2 || arena_radius > 10000)))
    return refuse(GL_ERR_ARGUMENT, "arena_radius: " + str(arena_radius) + " is not 0 or in [2, 10000]");
  if (!sim(s)->setWander(id, arena_radius)) return refuse(GL_ERR_NO_CHARACTER, noCharacter(id));
  return GL_OK;
}

int gl_sim_character_info(void* s, double* out, int capacity) {
  if (capacity < 0) return refuse(GL_ERR_ARGUMENT, "capacity: " + str(capacity) + " is negative");
  Simulation& S = *sim(s);
  const int n = S.characterCount();
  for (int i = 0; i < std::min(n, capacity); ++i) {
    const gaitlab::physics::Character& c = S.character(i);
    const auto root = c.segmentState(c.morphology().legFrames[0]);
    double* o = out + i * GL_INFO_FIELDS;
    o[GL_INFO_ID] = S.idOf(i);
    o[GL_INFO_KIND] = gaitlab::gait::kindNumber(S.kindOf(i));
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
    o[GL_INFO_LEGS] = static_cast<double>(S.character(i).morphology().legs.size());
  }
  return n;
}

// ---- Terrain --------------------------------------------------------------------------------

int gl_sim_set_terrain(void* s, int kind) {
  if (kind < GL_TERRAIN_FLAT || kind > GL_TERRAIN_BUMPS)
    return refuse(GL_ERR_ARGUMENT, "kind: " + str(kind) + " is not GL_TERRAIN_FLAT, GL_TERRAIN_SLOPE or GL_TERRAIN_BUMPS");
  sim(s)->setTerrain(static_cast<gaitlab::physics::TerrainKind>(kind));
  return GL_OK;
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

double gl_sim_ground_height(void* s, double x, double z) {
  if (!isFinite(x) || !isFinite(z)) return refuse(kNaN, "point: (" + str(x) + ", " + str(z) + ") is not finite");
  return sim(s)->groundHeight(x, z);
}

}  // extern "C"

// ---- Optimisation, one generation at a time ---------------------------------------------------

namespace {
struct OptHandle {
  std::unique_ptr<gaitlab::optimize::Optimizer> optimizer;
  gaitlab::gait::Character character;
  std::string text;  // gl_opt_best_json's result
};
OptHandle* opt(void* handle) { return static_cast<OptHandle*>(handle); }
}  // namespace

extern "C" {

void gl_opt_defaults(gl_opt_settings* o) {
  const gaitlab::optimize::SearchOptions d;
  *o = gl_opt_settings{GL_KIND_BIPED, GL_METHOD_GREEDY, d.candidates, d.threads, static_cast<uint32_t>(d.seed)};
}

void* gl_opt_create(const gl_opt_settings* settings, const char* startJson, const char* objectiveJson) {
  return gl_opt_create_creature(settings, startJson, objectiveJson, nullptr);
}

void* gl_opt_create_creature(const gl_opt_settings* settings, const char* startJson, const char* objectiveJson,
                             const char* creatureJson) {
  using namespace gaitlab;
  gait::Character c;
  if (!characterKind(settings->kind, &c)) return refuse<void*>(nullptr, notACharacter(settings->kind));
  std::optional<body::Morphology> body;
  if (creatureJson) {
    body.emplace();
    if (const std::string error = readCreature(creatureJson, &*body); !error.empty()) return refuse<void*>(nullptr, error);
    const gait::Character made = gait::characterOf(*body);
    if (made != c)
      return refuse<void*>(nullptr, "kind: " + str(settings->kind) + " is the " + gait::characterName(c) +
                                        "'s, and the creature's " + str(static_cast<int>(body->legFrames.size())) +
                                        " leg frames make a " + gait::characterName(made));
  }
  if (settings->method != GL_METHOD_GREEDY && settings->method != GL_METHOD_CMAES)
    return refuse<void*>(nullptr, "method: " + str(settings->method) + " is not GL_METHOD_GREEDY or GL_METHOD_CMAES");
  if (settings->candidates < optimize::kMinCandidates || settings->candidates > optimize::kMaxCandidates)
    return refuse<void*>(nullptr, "candidates: " + str(settings->candidates) + " is outside [" +
                                      str(optimize::kMinCandidates) + ", " + str(optimize::kMaxCandidates) + "]");
  optimize::SearchOptions o;
  o.character = c;
  o.body = body;
  o.method = settings->method == GL_METHOD_CMAES ? optimize::Method::CmaEs : optimize::Method::Greedy;
  o.candidates = settings->candidates;
  o.seed = settings->seed;
  o.threads = clampThreads(settings->threads);
  gait::GaitFile start;
  start.gait = gait::Gait::single(gait::defaultParams(c));
  if (startJson) {
    if (const auto error = gait::parseGaitFile(startJson, c, &start))
      return refuse<void*>(nullptr, "start: " + error->describe());
  }
  // The search tunes the start's key nearest the goal speeds (optimize::tunedKey); its other speed
  // keys walk with it. A creature starts from what it walks when spawned (sim::Simulation::spawnBody).
  o.gait = startJson ? start.gait
           : body && gait::derivesGait(c) ? gait::Gait::single(gait::derivedGait(*body), gait::kDerivedFromSpeed)
                                          : gait::defaultGait(c);
  if (objectiveJson) {
    if (const auto error = gait::checkJsonText(objectiveJson))
      return refuse<void*>(nullptr, "objective settings: " + error->describe());
    const nlohmann::json j = nlohmann::json::parse(objectiveJson, nullptr, false);
    const std::string error = j.is_discarded() ? "objective settings: expected a JSON object"
                                               : optimize::readObjectiveSettings(j, &o.objective);
    if (!error.empty()) return refuse<void*>(nullptr, error);
  }
  o.key = optimize::tunedKey(o.gait, o.objective.speeds);
  if (!takeWorkers(o.threads)) return refuse<void*>(nullptr, noWorkers(o.threads));
  return new OptHandle{optimize::Optimizer::create(o, o.gait.keys[o.key].params), c, {}};
}

const char* gl_opt_settings_json(void) {
  static const std::string table = gaitlab::optimize::objectiveSettingsTableJson();
  return table.c_str();
}

void gl_opt_destroy(void* h) {
  if (!h) return;
  const int threads = opt(h)->optimizer->options().threads;
  delete opt(h);
  giveWorkers(threads);
}

double gl_opt_step(void* h) { return opt(h)->optimizer->step().bestObjective; }

int gl_opt_generation(void* h) { return opt(h)->optimizer->generation(); }

int gl_opt_evaluations(void* h) { return opt(h)->optimizer->evaluations(); }

const char* gl_opt_best_json(void* h) {
  using namespace gaitlab;
  const optimize::Optimizer& o = *opt(h)->optimizer;
  const optimize::ObjectiveTerms& t = o.bestTerms();
  nlohmann::json terms = nlohmann::json::object();
  for (const optimize::TermName& term : optimize::kTermNames) terms[term.name] = t.*term.member;
  const nlohmann::json meta = {
      {"source", "gaitlab optimize (gl_opt)"},
      {"method", optimize::methodName(o.options().method)},
      {"seed", o.options().seed},
      {"objective", o.bestObjective()},
      {"objective_terms", terms},
      {"generations", o.generation()},
      {"evaluations", o.evaluations()}};
  opt(h)->text = gait::gaitFileJson(opt(h)->character, o.gaitWith(o.best()), o.generation() ? meta : nlohmann::json::object());
  return opt(h)->text.c_str();
}

// ---- Benchmark ------------------------------------------------------------------------------

const char* gl_bench_machine(void) {
  static const std::string machine = gaitlab::api::benchJsonMachine().dump();
  return machine.c_str();
}

int gl_bench_max_characters(int legs) {
  if (!benchLegs(legs)) return refuse(GL_ERR_ARGUMENT, notLegs(legs));
  return benchMaxCharacters(legs);
}

int gl_bench_warm_up(int legs, int threads) {
  if (!benchLegs(legs)) return refuse(GL_ERR_ARGUMENT, notLegs(legs));
  threads = clampThreads(threads);
  if (!takeWorkers(threads)) return refuse(GL_ERR_ARGUMENT, noWorkers(threads));
  gaitlab::sim::warmUp({legs}, threads);
  giveWorkers(threads);
  return GL_OK;
}

void gl_bench_defaults(gl_bench_settings* b) {
  const gaitlab::sim::PointSpec d;
  *b = gl_bench_settings{d.legs, d.characters, d.threads, static_cast<int32_t>(d.mode), d.steps, d.runs,
                         d.shards, d.seed, d.spacing, d.frames ? 1 : 0};
}

const char* gl_bench_point(const gl_bench_settings* b) {
  thread_local std::string point;
  const auto maxCharacters = benchMaxCharacters;
  using namespace gaitlab::limits;
  if (!benchLegs(b->legs)) return refuse<const char*>(nullptr, notLegs(b->legs));
  if (b->characters < 1 || b->characters > maxCharacters(b->legs))
    return refuse<const char*>(nullptr, "characters: " + str(b->characters) + " is outside [1, " +
                                            str(maxCharacters(b->legs)) + "] (the most a simulation holds)");
  if (b->mode < GL_MODE_SERIAL || b->mode > GL_MODE_FULL)
    return refuse<const char*>(nullptr, "mode: " + str(b->mode) + " is not GL_MODE_SERIAL, GL_MODE_CONTROLLER or GL_MODE_FULL");
  if (b->steps < 1 || b->steps > kMaxBenchSteps)
    return refuse<const char*>(nullptr, "steps: " + str(b->steps) + " is outside [1, " + str(kMaxBenchSteps) + "]");
  if (b->runs < 1 || b->runs > kMaxBenchRuns)
    return refuse<const char*>(nullptr, "runs: " + str(b->runs) + " is outside [1, " + str(kMaxBenchRuns) + "]");
  if (static_cast<long>(b->steps) * b->runs > kMaxBenchSamples)
    return refuse<const char*>(nullptr, "steps × runs: " + str(b->steps) + " × " + str(b->runs) + " is more than " +
                                            std::to_string(kMaxBenchSamples) + " timed steps");
  if (b->shards < 1 || b->shards > 64) return refuse<const char*>(nullptr, "shards: " + str(b->shards) + " is outside [1, 64]");
  if (!(b->spacing >= 2.5) || !isFinite(b->spacing))
    return refuse<const char*>(nullptr, "spacing: " + str(b->spacing) + " is not a distance >= 2.5 m");
  gaitlab::sim::PointSpec s;
  s.legs = b->legs;
  s.characters = b->characters;
  s.threads = clampThreads(b->threads);
  s.mode = static_cast<gaitlab::sim::Mode>(b->mode);
  s.steps = b->steps;
  s.runs = b->runs;
  s.shards = b->shards;
  s.spacing = b->spacing;
  s.seed = b->seed;
  s.frames = b->frames != 0;
  if (!takeWorkers(s.threads)) return refuse<const char*>(nullptr, noWorkers(s.threads));
  const gaitlab::sim::PointResult result = gaitlab::sim::runPoint(s);
  giveWorkers(s.threads);
  if (!result.error.empty()) return refuse<const char*>(nullptr, result.error);
  point = gaitlab::api::benchJsonPoint(result).dump();
  return point.c_str();
}

// ---- The peer benchmark's reference scene ---------------------------------------------------

const char* gl_morphology_json(int kind) {
  static const std::string biped = gaitlab::peers::morphologyJson(Character::Biped);
  static const std::string quadruped = gaitlab::peers::morphologyJson(Character::Quadruped);
  if (kind == GL_KIND_BIPED) return biped.c_str();
  if (kind == GL_KIND_QUADRUPED) return quadruped.c_str();
  return refuse<const char*>(nullptr, "kind: " + str(kind) + " is not GL_KIND_BIPED or GL_KIND_QUADRUPED");
}

void* gl_peer_scene_create(int kind, int characters, int threads) {
  // The peer benchmark times the biped's and the quadruped's ragdolls only.
  if (kind != GL_KIND_BIPED && kind != GL_KIND_QUADRUPED)
    return refuse<void*>(nullptr, "kind: " + str(kind) + " is not GL_KIND_BIPED or GL_KIND_QUADRUPED");
  const Character c = *gaitlab::gait::characterFromKind(kind);
  if (characters < 1 || characters > gaitlab::peers::kMaxCharacters)
    return refuse<void*>(nullptr, "characters: " + str(characters) + " is outside [1, " +
                                      str(gaitlab::peers::kMaxCharacters) + "]");
  // Charged as the simulation charges its characters (sim/capacity.h), all in one world.
  const int64_t headroom = gaitlab::sim::heapHeadroom();
  const bool biped = c == Character::Biped;
  const int bodies = static_cast<int>((biped ? gaitlab::body::makeBiped() : gaitlab::body::makeQuadruped()).segments.size());
  if (headroom >= 0 &&
      gaitlab::sim::affordable(headroom - gaitlab::sim::kSimulationBytes,
                               biped ? gaitlab::sim::kBipedBytes : gaitlab::sim::kQuadrupedBytes, bodies, 0) < characters)
    return refuse<void*>(nullptr, "characters: " + str(characters) + " do not fit in the module's memory now");
  // Its pool is not charged to the module's pthread pool (the peer benchmark runs alone), but
  // it may not need more workers than the pool holds: a thread beyond it would abort the module.
  threads = clampThreads(threads);
  if (threads > gaitlab::sim::maxThreads())
    return refuse<void*>(nullptr, "threads: " + str(threads) + " is more than the module's pool serves (" +
                                      str(gaitlab::sim::maxThreads()) + ", gl_pool_threads)");
  return new gaitlab::peers::ReferenceScene(c, characters, threads);
}

void gl_peer_scene_destroy(void* scene) { delete static_cast<gaitlab::peers::ReferenceScene*>(scene); }

int gl_peer_scene_step(void* scene, int steps) {
  if (steps < 0 || steps > gaitlab::limits::kMaxStepsPerCall)
    return refuse(GL_ERR_ARGUMENT, "steps: " + str(steps) + " is outside [0, " + str(gaitlab::limits::kMaxStepsPerCall) + "]");
  static_cast<gaitlab::peers::ReferenceScene*>(scene)->step(steps);
  return GL_OK;
}

double gl_peer_scene_root_height(void* scene) {
  return static_cast<gaitlab::peers::ReferenceScene*>(scene)->meanRootHeight();
}

}  // extern "C"
