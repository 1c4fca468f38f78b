// The C ABI gaitlab exports to JavaScript (the WASM build) and that the native tests also call.
// web/src/sim/gaitlab-wasm.ts is its one TypeScript binding.
//
// The contract, for every `gl_` function:
//
//   Failure.   A call that refuses its arguments changes nothing and says so by its return value:
//              - a function returning a pointer (a handle or a string) returns NULL;
//              - a function returning an int returns a negative GL_ERR_* code (success is >= 0:
//                GL_OK, an id or a count);
//              - a function returning a double returns NaN.
//              Functions returning void, and the other doubles and ints documented as never
//              failing, cannot refuse anything. After every refusal gl_last_error() is a message
//              that names what was refused ("kind: 7 is not GL_KIND_BIPED or
//              GL_KIND_QUADRUPED", "id: no character has id 12", "period: 99.0 is outside
//              [0.2, 2]"). It is per thread and only meaningful right after a refusal:
//              successful calls leave it as it was.
//   Checked.   Ids, kinds, counts, enum values, numbers and JSON text are checked: numbers for
//              finiteness and against api/limits.h's ranges, JSON text against its limits on
//              bytes, nesting depth and string and array lengths. Thread counts
//              are clamped to [1, GL_MAX_THREADS] (gl_sim_threads tells the count in use),
//              then refused if the WASM build's pthread pool has too few free workers.
//              Handles and output arrays are not checked: a handle must come from its create
//              function and not be destroyed yet, an output array must be as large as the
//              function says.
//   Strings.   Returned strings are owned by the library, UTF-8, NUL-terminated. Their lifetime:
//              - strings that never change (gl_version, gl_schema_json, gl_preset_json,
//                gl_opt_settings_json, gl_bench_machine, gl_morphology_json) are static: valid for the module's
//                lifetime, the same pointer every call;
//              - a simulation's strings (gl_sim_state_hash, gl_sim_get_params) live in that
//                simulation: valid until the next of those two calls on the same simulation, or
//                gl_sim_destroy. Calls on other simulations never touch them;
//              - an optimiser's string (gl_opt_best_json) likewise, until the next
//                gl_opt_best_json on the same optimiser or gl_opt_destroy;
//              - gl_bench_point's result, until the next gl_bench_point on the same thread;
//              - gl_last_error's message, until the next refusal on the same thread.
//   Settings.  Calls with many arguments take a settings struct: fill it with its gl_*_defaults
//              function, change the fields wanted, pass its address. Their layouts are pinned by
//              the static_asserts at the end of this file and mirrored in
//              web/src/sim/gaitlab-wasm.ts (tests/web/sim/gaitlab-wasm.test.ts compares them).
#pragma once
#include <stdint.h>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#define GL_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define GL_EXPORT
#endif

// Most threads a simulation, a search or a benchmark point uses: 16, the cores of today's larger
// desktops. The WASM build pre-starts a pool of pthread workers when the module loads, sized
// from the device (native/src/api/pthread_pool.pre.js.in: navigator.hardwareConcurrency, in Node
// the core count, or the loader's `poolThreads` option; at least 1 and at most GL_MAX_THREADS - 1
// workers), since a thread's pool holds the calling thread plus threads - 1 workers, and a
// pthread beyond the pool would need a new Worker, which cannot start while the browser's worker
// that owns the module is blocked in a step (sim/thread_budget.h). gl_pool_threads() is what
// this module can use, gl_default_threads() the count to use when none is asked for. Thread
// counts above the hardware's are allowed (the thesis ran 2-4; the results never depend on the
// count). The page's copy (MAX_THREADS, web/src/sim/gaitlab-wasm.ts) is checked against this
// line by a test and against gl_max_threads() when the module loads; native/CMakeLists.txt
// reads it too.
#define GL_MAX_THREADS 16

#ifdef __cplusplus
extern "C" {
#endif

// Error codes: negative, as every int-returning function's refusal.
enum {
  GL_OK = 0,
  GL_ERR_ARGUMENT = -1,        // an argument out of range, not finite, or not one of its values
  GL_ERR_KIND = -2,            // a kind that is not a character, or a character of another kind
  GL_ERR_NO_CHARACTER = -3,    // no character with that id, or none of that kind
  GL_ERR_INVALID_PARAMS = -4,  // a refused gait file or settings object (malformed, bad field...)
  GL_ERR_FULL = -5,            // the simulation's render buffer has no room left
};

// The message of the last refusal on the calling thread (see the contract above); never NULL.
GL_EXPORT const char* gl_last_error(void);

// Library version, "MAJOR.MINOR.PATCH". Static.
GL_EXPORT const char* gl_version(void);

// GL_MAX_THREADS, for JavaScript.
GL_EXPORT int gl_max_threads(void);

// Most threads one simulation, search or benchmark point can use in this module: natively
// GL_MAX_THREADS, in the WASM build 1 + the workers of its pthread pool (sized when it loaded).
GL_EXPORT int gl_pool_threads(void);

// The thread count to use when none is asked for: the device's logical cores, at most
// gl_pool_threads().
GL_EXPORT int gl_default_threads(void);

// ---- Simulation ----------------------------------------------------------------------------

// A new simulation: flat ground (gl_sim_set_terrain changes it), nothing on it. `threads` is the
// size of the thread pool used for per-character work (clamped). `seed` drives every random
// choice of the scene. NULL when the WASM build cannot afford it: its heap is nearly full, or
// its pthread pool (gl_pool_threads() - 1 workers, shared by every simulation, search and
// benchmark point of the module) has fewer than threads - 1 free.
GL_EXPORT void* gl_sim_create(int threads, uint32_t seed);
GL_EXPORT void gl_sim_destroy(void* sim);  // NULL is allowed

// Kinds of thing that can be spawned. Characters are articulated figures built from a
// morphology (native/src/body): the biped, the quadruped, and the six- and eight-legged kinds
// (their shipped bodies the insect and the spider, public/creatures/), which walk a gait derived
// from the body (gait/derived_gait.h); a prop is a loose box. (3 is GL_LAYOUT_ALTERNATING.)
enum { GL_KIND_BIPED = 0, GL_KIND_QUADRUPED = 1, GL_KIND_BOX = 2, GL_KIND_HEXAPOD = 4, GL_KIND_OCTOPOD = 5 };

// Spawns one thing standing on the ground at (x, z), facing `heading` radians (about +y,
// 0 = +z). Returns its id (>= 0); GL_ERR_ARGUMENT for an unknown kind or a position or heading
// that is not finite or beyond api/limits.h's (|x|, |z| <= 1000 m, |heading| <= 1000 rad),
// GL_ERR_FULL when gl_sim_room(sim, kind) is 0 (the message says what is full).
GL_EXPORT int gl_sim_spawn(void* sim, int kind, double x, double z, double heading);

// How many more things of `kind` (GL_KIND_*) the simulation can take now: the least of the
// render buffer's room, the free ids, for boxes the most a scene holds (64, boxes of every
// origin counted), and in the WASM build what its fixed heap can still afford at the measured
// cost of each (sim/capacity.h). Every spawn refuses with GL_ERR_FULL, before allocating, when
// this is 0. GL_ERR_ARGUMENT for another kind.
GL_EXPORT int gl_sim_room(void* sim, int kind);

// The speed a character of `kind` is tuned and benchmarked for, m/s (sim::Simulation::
// cruiseSpeed): the demo's start goal. NaN for a kind that is not a character.
GL_EXPORT double gl_cruise_speed(int kind);

// The fastest speed a character of `kind`'s preset gait is tuned for, m/s: its fastest speed key
// (native/src/gait/speed_keys.h). The demo's steering offers goals from 0 up to it. NaN for a kind
// that is not a character.
GL_EXPORT double gl_top_speed(int kind);

// The demo page's scene layout (native/src/sim/scene_layout.h): a grid facing +z, 2.5 m across
// and 3 m deep, centred on the origin. The first call sizes the grid for its `count`; later calls
// continue in the next free places, in rows behind the first (−z). `kind` is a character's kind
// or GL_LAYOUT_ALTERNATING (biped and quadruped in turn, a biped first); each
// character starts walking forward at its kind's cruise speed (gl_cruise_speed). Returns how many
// were added (fewer than `count` once the render buffer is full; they are the last characters of
// gl_sim_character_info); GL_ERR_ARGUMENT if the kind is not one of those or `count` is negative.
enum { GL_LAYOUT_ALTERNATING = 3 };
GL_EXPORT int gl_sim_add_characters(void* sim, int kind, int count);

// Adds one character of `kind` (a character's GL_KIND_*) at the layout's place apart,
// 5 m left (−x) of the grid level with its middle row, where it can be watched alone (the
// optimize panel's learner). No goal is set. Returns its id, or an error as gl_sim_spawn.
GL_EXPORT int gl_sim_add_apart(void* sim, int kind);

// Spawns a character whose body is the creature file `creatureJson` (body/creature.h,
// public/creatures/*.json) standing at (x, z), facing `heading`: a body of one or two leg frames
// walks the biped's or the quadruped's preset, one of three or four the gait derived from it
// (gait/derived_gait.h). It is a character of the kind its leg frames make (1 biped,
// 2 quadruped, 3 hexapod, 4 octopod) and takes that kind's gait files. No goal is set. Returns its id; GL_ERR_ARGUMENT for a refused file (the
// message names the field, "creature: legFrames[1].mass: ...") or a position or heading as
// gl_sim_spawn refuses them, GL_ERR_FULL when there is no room for its bodies.
GL_EXPORT int gl_sim_spawn_creature(void* sim, const char* creatureJson, double x, double z, double heading);
// The same at the layout's place apart (gl_sim_add_apart): the optimize panel's learner when it
// learns for a creature's body. Returns its id, or an error as gl_sim_spawn_creature.
GL_EXPORT int gl_sim_add_apart_creature(void* sim, const char* creatureJson);

// The demo page's scene: gl_sim_add_characters(sim, GL_LAYOUT_ALTERNATING, characters) on a new
// simulation, plus a few boxes dropped at places drawn from the seed. GL_OK, or GL_ERR_ARGUMENT
// for a negative count.
GL_EXPORT int gl_sim_demo_scene(void* sim, int characters);

// Advances the simulation by `steps` (0 to 12000, 100 s) fixed steps of 1/120 s, then publishes
// render transforms (0 steps publishes the scene as it is). GL_OK, or GL_ERR_ARGUMENT for a count
// outside that range. A character whose state stops being finite in a step (a physics blow-up)
// counts as fallen (GL_INFO_FALLEN), its bodies leave the simulation where it last stood, and
// every reset (gl_sim_reset_character, the automatic reset, gl_sim_set_terrain) rebuilds it
// standing there.
GL_EXPORT int gl_sim_step(void* sim, int steps);

// Never fail.
GL_EXPORT double gl_sim_time(void* sim);           // simulated seconds
GL_EXPORT uint32_t gl_sim_step_index(void* sim);   // fixed steps taken
GL_EXPORT int gl_sim_body_count(void* sim);        // rigid bodies (instances to draw)
GL_EXPORT int gl_sim_threads(void* sim);

// Hex string of a 64-bit hash of every body's position, orientation and velocities (exact bits),
// so that two runs can be compared for bit-identical state. The simulation's string.
GL_EXPORT const char* gl_sim_state_hash(void* sim);

// Pointer (byte offset into WASM memory) of the render buffer header, see
// native/src/sim/render_buffer.h. Valid until gl_sim_destroy. Never fails.
GL_EXPORT const void* gl_sim_render_buffer(void* sim);

// ---- Gait parameters: schema, presets, gait files (native/src/gait/schema.h, params_io.h) ----
//
// Gait files are JSON: {"format":"gaitlab-gait","version":2,"character":"biped"|"quadruped",
// "params":{"<name>": number | [4 numbers], ...},"meta":{...}} (public/presets/*.json). The
// module is the only judge of them: the page validates and migrates nothing itself.

// The parameter schema: {"version":2,"characters":{"biped":[...],"quadruped":[...]},
// "morphologies":{"biped":{"kind","legFrames","legs"},...}}, an entry per parameter
// {"name","group","min","max","default","unit","description","knots","field"} plus its
// "legFrame" or "leg" ({"index","name"}) when it belongs to one (gait/schema.h). Static.
GL_EXPORT const char* gl_schema_json(void);

// Any gait file (any schema version) validated and normalised: the current version, every
// parameter in schema order, canonical numbers, on one line, "meta" kept. NULL if it is refused
// (gl_last_error() gives "FIELD: WHAT"). Valid until the next gl_gait_normalize on the same
// thread.
GL_EXPORT const char* gl_gait_normalize(const char* json);

// The shipped preset of a kind, as a gait file. Static; NULL for a kind that is not a character.
GL_EXPORT const char* gl_preset_json(int kind);

// Validates a gait file for `kind` and gives it to the character with id `characterId` (as
// returned by gl_sim_spawn), or with characterId = -1 to every character of that kind. Nothing
// changes unless the whole file is valid. GL_OK; GL_ERR_KIND, GL_ERR_NO_CHARACTER, or
// GL_ERR_INVALID_PARAMS ("FIELD: WHAT" for a refused file). A creature (gl_sim_spawn_creature) is
// a character of the kind its leg frames make.
GL_EXPORT int gl_sim_set_params(void* sim, int characterId, int kind, const char* json);

// An edit: `patch` is a JSON object {"<name>": number | [4 numbers], ...} of some parameters and
// their new values, given to the character with id `characterId`, or with characterId = -1 to
// every character of `kind` (each keeps its other parameters). Every value is checked against
// the schema first, and nothing changes unless all are valid. The patch edits the primary speed
// key (the gait file's "params"); it may also hold "speed" and "keys" as in a gait file, which set
// that key's speed and replace the other speed keys. Returns GL_OK or a negative error
// code (GL_ERR_INVALID_PARAMS with gl_last_error() "NAME: WHAT" for a refused value).
GL_EXPORT int gl_sim_patch_params(void* sim, int characterId, int kind, const char* patch);

// The gait parameters a character is using, as a gait file of its kind. The simulation's string;
// NULL if no character has that id.
GL_EXPORT const char* gl_sim_get_params(void* sim, int characterId);

// ---- Interaction: the demo page's commands --------------------------------------------------
// Characters are named by the id gl_sim_spawn returned. The sim worker calls these between
// fixed steps only (it queues the page's commands and applies them at the start of the next
// step), so each acts at a known step index.

// Steering goal of character `id`, or of every character with id = -1: forward speed (m/s) and
// turn rate (rad/s, about +y, positive = left). GL_OK; GL_ERR_NO_CHARACTER, or GL_ERR_ARGUMENT
// for a speed or a turn rate that is not finite or is beyond ±5 m/s or ±3 rad/s.
GL_EXPORT int gl_sim_set_goal(void* sim, int id, double speed, double turn_rate);

// A box thrown into the scene: from `from` (m) with `velocity` (m/s), half size `half` (m).
typedef struct gl_throw_settings {
  double from[3];      // default (0, 1, 0)
  double velocity[3];  // default (0, 0, 0)
  double half;         // default 0.12; must lie in [0.03, 0.5]
} gl_throw_settings;
GL_EXPORT void gl_throw_defaults(gl_throw_settings* settings);

// Throws a box. It collides with characters, props and the ground; the oldest thrown box goes
// once there are 32, or when the scene holds the most boxes it takes. Returns its id (>= 0);
// GL_ERR_ARGUMENT for a half size out of range, a value that is not finite, `from` beyond
// 1000 m or a velocity over 100 m/s; GL_ERR_FULL when gl_sim_room(sim, GL_KIND_BOX) is 0 and no
// thrown box can make way.
GL_EXPORT int gl_sim_throw_box(void* sim, const gl_throw_settings* settings);

// A box thrown at a character (the page's shift-click on one): aimed by the simulation, from the
// character's state when the call is made, at where point `local` of its segment `segment` will
// be when the box arrives (Simulation::aimAt: the character carried by its centre of mass's
// velocity, turning at its goal's turn rate; the box's ballistic flight as the physics integrates
// it, covering the straight distance at `speed`). The page picks the character and the point on
// the frame it shows, which is a frame time and a worker round trip old; aiming here, from the
// state the box is thrown into, makes the throw meet the character where it really will be.
typedef struct gl_throw_at_settings {
  int32_t id;        // default -1 (none: must be set)
  int32_t segment;   // default 0; the character's n-th body in the render buffer
  double from[3];    // default (0, 1, 0)
  double local[3];   // default (0, 0, 0); segment body frame, m
  double speed;      // default 14 m/s; must lie in [1, 100]
  double half;       // default 0.12; must lie in [0.03, 0.5]
} gl_throw_at_settings;
GL_EXPORT void gl_throw_at_defaults(gl_throw_at_settings* settings);

// Throws it. Returns the box's id (>= 0); GL_ERR_NO_CHARACTER; GL_ERR_ARGUMENT for a segment the
// character does not have, a value that is not finite, `from` beyond 1000 m, `local` beyond
// 10 m, a speed or half size out of range, or an aim that needs a throw over 100 m/s (a far
// target at a slow speed: the flight's rise grows with its time); GL_ERR_FULL as
// gl_sim_throw_box.
GL_EXPORT int gl_sim_throw_at(void* sim, const gl_throw_at_settings* settings);

// A drag: point `local` of segment `segment` of character `id` (segment body frame, metres; the
// segment is the character's n-th body in the render buffer) held on a spring towards the world
// point `target`.
typedef struct gl_drag_settings {
  int32_t id;        // default -1 (none: must be set)
  int32_t segment;   // default 0
  double local[3];   // default (0, 0, 0)
  double target[3];  // default (0, 0, 0)
} gl_drag_settings;
GL_EXPORT void gl_drag_defaults(gl_drag_settings* settings);

// Starts a drag, applied every step until gl_sim_end_drag; calling it again moves the target.
// GL_OK; GL_ERR_NO_CHARACTER, or GL_ERR_ARGUMENT for a segment the character does not have or a
// point that is not finite (or `local` beyond 10 m, `target` beyond 1000 m).
GL_EXPORT int gl_sim_drag(void* sim, const gl_drag_settings* settings);
GL_EXPORT void gl_sim_end_drag(void* sim);

// Replaces character `id` by a fresh one standing where it is, same gait and goal; removes it.
// GL_OK, or GL_ERR_NO_CHARACTER.
GL_EXPORT int gl_sim_reset_character(void* sim, int id);
GL_EXPORT int gl_sim_remove_character(void* sim, int id);

// Characters fallen for `seconds` (leg frame below half its standing height or tilted over 60°)
// are reset automatically; 0 turns it off. GL_OK, or GL_ERR_ARGUMENT for a time outside
// [0, 3600].
GL_EXPORT int gl_sim_set_auto_reset(void* sim, double seconds);

// Arena wandering (native/src/sim/wander.h): character `id`, or every character now in the scene
// with id = -1, wanders inside a circle of `arena_radius` metres about the origin (one arena for
// all wanderers: the last radius given), keeping its goal's speed while wandering chooses its
// turn rate (turning away from the arena's edge and from neighbours, within ±0.3 rad/s);
// `arena_radius` = 0 stops it (it keeps its last goal). A goal given with gl_sim_set_goal sets
// the speed; wandering replaces its turn rate at the next tenth of a second. GL_OK;
// GL_ERR_NO_CHARACTER, or GL_ERR_ARGUMENT for a radius that is not 0 or in [2, 10000].
GL_EXPORT int gl_sim_set_wander(void* sim, int id, double arena_radius);

GL_EXPORT int gl_sim_character_count(void* sim);  // never fails

// Fields per character written by gl_sim_character_info, in this order.
enum {
  GL_INFO_ID, GL_INFO_KIND, GL_INFO_X, GL_INFO_Y, GL_INFO_Z,  // root leg frame's centre, m
  GL_INFO_HEADING,        // rad about +y, 0 = +z
  GL_INFO_SPEED,          // horizontal speed of the root leg frame, m/s
  GL_INFO_FALLEN,         // 1 or 0
  GL_INFO_FALLEN_SECONDS, // how long it has been down
  GL_INFO_GOAL_SPEED, GL_INFO_GOAL_TURN,
  GL_INFO_PHASE,          // gait phase in [0, 1)
  GL_INFO_LEGS,           // its number of legs: 2, 4, or a creature's (gl_sim_spawn_creature)
  GL_INFO_FIELDS
};
// Writes GL_INFO_FIELDS doubles per character for at most `capacity` characters into `out`;
// returns the number of characters (which may exceed `capacity`), or GL_ERR_ARGUMENT for a
// negative capacity.
GL_EXPORT int gl_sim_character_info(void* sim, double* out, int capacity);

// ---- Terrain: the ground (native/src/physics/terrain.h) ---------------------------------------
// A terrain is a square grid of height samples joined by triangles, with a flat plane beyond it.
// The page draws its ground from the same samples the physics collides with.

enum { GL_TERRAIN_FLAT = 0, GL_TERRAIN_SLOPE = 1, GL_TERRAIN_BUMPS = 2 };

// Sets the ground of every physics shard: flat, a ±5° ridge-and-valley slope across +z, or
// 2-3 cm bumps drawn from the simulation's seed. Characters already in the scene are re-placed
// standing on the new ground where they are (same gait and goal), props lifted out of it.
// GL_OK, or GL_ERR_ARGUMENT for an unknown kind.
GL_EXPORT int gl_sim_set_terrain(void* sim, int kind);

// Fields written by gl_sim_terrain_grid, in this order.
enum {
  GL_GRID_KIND,      // GL_TERRAIN_*
  GL_GRID_COLUMNS,   // samples along +x (0 when flat)
  GL_GRID_ROWS,      // samples along +z (0 when flat)
  GL_GRID_SPACING,   // metres between samples
  GL_GRID_ORIGIN_X,  // x of column 0, metres
  GL_GRID_ORIGIN_Z,  // z of row 0, metres
  GL_GRID_PLANE,     // height of the flat ground beyond the grid (everywhere when flat)
  GL_GRID_FIELDS
};
// Writes GL_GRID_FIELDS doubles describing the terrain's grid into `out`. Never fails.
GL_EXPORT void gl_sim_terrain_grid(void* sim, double* out);

// The samples: columns × rows floats, row-major (sample (c, r) at index r·columns + c, at
// x = origin_x + c·spacing, z = origin_z + r·spacing). Each grid cell is two triangles split along
// the diagonal from (c+1, r) to (c, r+1), as Bullet's heightfield splits it. Owned by the
// simulation; valid until the terrain changes or the simulation is destroyed. NULL when flat
// (there are no samples: this is not a refusal).
GL_EXPORT const float* gl_sim_terrain_heights(void* sim);

// Height of the ground under (x, z) as the controller sees it: a ray cast against the terrain.
// NaN for a point that is not finite.
GL_EXPORT double gl_sim_ground_height(void* sim, double x, double z);

// ---- Optimisation, one generation at a time (native/src/optimize/optimizer.h) ----------------
//
// For the browser's optimize panel: create a search, call gl_opt_step once per generation (each
// runs `candidates` evaluations, a few tenths of a second to seconds), read the best so far.

enum { GL_METHOD_GREEDY = 0, GL_METHOD_CMAES = 1 };

// The search's own settings; the objective's are a JSON object (gl_opt_create).
typedef struct gl_opt_settings {
  int32_t kind;        // a character's GL_KIND_* (default GL_KIND_BIPED)
  int32_t method;      // GL_METHOD_GREEDY (default, thesis §3.3) or GL_METHOD_CMAES
  int32_t candidates;  // evaluations per generation, [2, 1000]; default 10
  int32_t threads;     // evaluations in parallel (clamped); default 1
  uint32_t seed;       // the same seed gives the same search; default 1
} gl_opt_settings;
GL_EXPORT void gl_opt_defaults(gl_opt_settings* settings);

// A new search. `start_json` a gait file to start from, or NULL for the preset; `objective_json`
// NULL or an object of objective settings ({"seconds":4,"speeds":[0.5,1],"wr":2,
// "grounds":["flat","slope@3.14159"],...}, read by optimize::readObjectiveSettings,
// native/src/optimize/settings.h). NULL on refusal, including a `threads` the WASM build's
// pthread pool cannot supply now (gl_sim_create).
GL_EXPORT void* gl_opt_create(const gl_opt_settings* settings, const char* start_json,
                              const char* objective_json);
// The same for the body of a creature file (`creature_json`, as gl_sim_spawn_creature reads it)
// rather than the kind's shipped one: every episode walks that body, and with `start_json` NULL
// the search starts from the gait the body walks when spawned (for three or four leg frames, the
// one derived from it). settings->kind must be the kind its leg frames make ("kind: ..." names
// both otherwise); a refused file is "creature: FIELD: WHAT". NULL `creature_json` is
// gl_opt_create.
GL_EXPORT void* gl_opt_create_creature(const gl_opt_settings* settings, const char* start_json,
                                       const char* objective_json, const char* creature_json);
GL_EXPORT void gl_opt_destroy(void* opt);  // NULL is allowed
// The objective settings gl_opt_create accepts, for forms that check them before a search:
// {"settings":[{"name","min","max","default","unit","description","integer"},...],
//  "speeds":{"min","max","default":[...],"unit","description"},
//  "grounds":{"default":["flat"],"terrains":["flat","slope","bumps"],"description"}}
// (optimize/objective.h). Static.
GL_EXPORT const char* gl_opt_settings_json(void);
// Runs one generation; returns the best objective so far. Never fails.
GL_EXPORT double gl_opt_step(void* opt);
GL_EXPORT int gl_opt_generation(void* opt);   // never fails
GL_EXPORT int gl_opt_evaluations(void* opt);  // never fails
// The best parameters so far as a gait file (meta: method, seed, objective, its terms,
// generations, evaluations). The optimiser's string.
GL_EXPORT const char* gl_opt_best_json(void* opt);

// ---- Benchmark (the performance page, web/src/bench) ----------------------------------------
// The same measurement as `gaitlab bench` (native/src/sim/experiment.h), one point per call so
// that the page can report progress and cancel between points. The JSON strings are parts of a
// bench/schema.json document.

// The machine object of the document ("machine"), as measured at the first call (its load
// average then; null in a browser, which has no /proc/loadavg). Static.
GL_EXPORT const char* gl_bench_machine(void);

enum { GL_LEGS_MIXED = 0, GL_LEGS_BIPED = 2, GL_LEGS_QUADRUPED = 4 };
enum { GL_MODE_SERIAL = 0, GL_MODE_CONTROLLER = 1, GL_MODE_FULL = 2 };

// Untimed warm-up before a grid (sim::warmUp): 10 characters of `legs` (GL_LEGS_*), 1 s, full
// mode on `threads` threads (clamped). GL_OK, or GL_ERR_ARGUMENT for unknown legs.
GL_EXPORT int gl_bench_warm_up(int legs, int threads);

// The largest crowd of `legs` (GL_LEGS_*) a new simulation holds, as gl_sim_room counts (the
// render buffer, and in the WASM build the heap left now), or GL_ERR_ARGUMENT.
GL_EXPORT int gl_bench_max_characters(int legs);

// One point of the experiment (sim::PointSpec; the defaults are its defaults).
typedef struct gl_bench_settings {
  int32_t legs;        // GL_LEGS_*; default GL_LEGS_BIPED
  int32_t characters;  // [1, gl_bench_max_characters(legs)]; default 1
  int32_t threads;     // clamped; default 1
  int32_t mode;        // GL_MODE_*; default GL_MODE_SERIAL
  int32_t steps;       // fixed steps per run, [1, 100000]; default 800 (the thesis's)
  int32_t runs;        // [1, 1000], steps × runs <= 2,000,000; default 20 (the thesis's)
  int32_t shards;      // physics shards, [1, 64]; default 16 (sim::kCrowdShards)
  uint32_t seed;       // default 1
  double spacing;      // metres between grid neighbours, >= 2.5; default 4
  int32_t frames;      // non-zero keeps per-frame statistics; default 0
} gl_bench_settings;
GL_EXPORT void gl_bench_defaults(gl_bench_settings* settings);

// Runs one point and returns its element of "points"; NULL on refusal (an argument out of
// range, more characters than gl_bench_max_characters included, or a crowd that the memory left
// could not hold after all: gl_bench_max_characters is an estimate, the scene counts). Valid
// until the next gl_bench_point on the same thread.
GL_EXPORT const char* gl_bench_point(const gl_bench_settings* settings);

// ---- The peer benchmark's reference scene (native/src/peers/reference_scene.h) -------------
// Ragdolls of one character type holding their standing pose with motors, ground-only contact,
// no controller: the physics alone, for timing side by side with another engine.

// The morphology of GL_KIND_BIPED or GL_KIND_QUADRUPED as JSON (peers/morphology_json.h), for
// another engine to build the same ragdoll; static. NULL for another kind.
GL_EXPORT const char* gl_morphology_json(int kind);
// `characters` (1 to 400) ragdolls of `kind` on the crowd benchmark's grid, stepped by `threads`
// threads (clamped to [1, GL_MAX_THREADS]; refused above gl_pool_threads()). NULL on refusal.
GL_EXPORT void* gl_peer_scene_create(int kind, int characters, int threads);
GL_EXPORT void gl_peer_scene_destroy(void* scene);
// `steps` (0 to 12000, as gl_sim_step) fixed steps of 1/120 s. GL_OK, or GL_ERR_ARGUMENT.
GL_EXPORT int gl_peer_scene_step(void* scene, int steps);
// Mean height of the ragdolls' root segments, m (never fails).
GL_EXPORT double gl_peer_scene_root_height(void* scene);

#ifdef __cplusplus
}  // extern "C"

// The settings structs' layouts, mirrored in web/src/sim/gaitlab-wasm.ts (STRUCTS). The same in
// the native and the WASM build: fixed-width fields only, no pointers.
#include <cstddef>
static_assert(offsetof(gl_throw_settings, from) == 0, "layout");
static_assert(offsetof(gl_throw_settings, velocity) == 24, "layout");
static_assert(offsetof(gl_throw_settings, half) == 48, "layout");
static_assert(sizeof(gl_throw_settings) == 56, "layout");
static_assert(offsetof(gl_throw_at_settings, id) == 0, "layout");
static_assert(offsetof(gl_throw_at_settings, segment) == 4, "layout");
static_assert(offsetof(gl_throw_at_settings, from) == 8, "layout");
static_assert(offsetof(gl_throw_at_settings, local) == 32, "layout");
static_assert(offsetof(gl_throw_at_settings, speed) == 56, "layout");
static_assert(offsetof(gl_throw_at_settings, half) == 64, "layout");
static_assert(sizeof(gl_throw_at_settings) == 72, "layout");
static_assert(offsetof(gl_drag_settings, id) == 0, "layout");
static_assert(offsetof(gl_drag_settings, segment) == 4, "layout");
static_assert(offsetof(gl_drag_settings, local) == 8, "layout");
static_assert(offsetof(gl_drag_settings, target) == 32, "layout");
static_assert(sizeof(gl_drag_settings) == 56, "layout");
static_assert(offsetof(gl_opt_settings, kind) == 0, "layout");
static_assert(offsetof(gl_opt_settings, method) == 4, "layout");
static_assert(offsetof(gl_opt_settings, candidates) == 8, "layout");
static_assert(offsetof(gl_opt_settings, threads) == 12, "layout");
static_assert(offsetof(gl_opt_settings, seed) == 16, "layout");
static_assert(sizeof(gl_opt_settings) == 20, "layout");
static_assert(offsetof(gl_bench_settings, legs) == 0, "layout");
static_assert(offsetof(gl_bench_settings, characters) == 4, "layout");
static_assert(offsetof(gl_bench_settings, threads) == 8, "layout");
static_assert(offsetof(gl_bench_settings, mode) == 12, "layout");
static_assert(offsetof(gl_bench_settings, steps) == 16, "layout");
static_assert(offsetof(gl_bench_settings, runs) == 20, "layout");
static_assert(offsetof(gl_bench_settings, shards) == 24, "layout");
static_assert(offsetof(gl_bench_settings, seed) == 28, "layout");
static_assert(offsetof(gl_bench_settings, spacing) == 32, "layout");
static_assert(offsetof(gl_bench_settings, frames) == 40, "layout");
static_assert(sizeof(gl_bench_settings) == 48, "layout");
#endif
