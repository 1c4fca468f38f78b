// The C ABI gaitlab exports to JavaScript (WASM build) and that native tests also call.
//
// Every function is prefixed `gl_`. A simulation is an opaque handle (a pointer; a number in JS).
// Strings returned are owned by the library and valid until the next call on the same handle.
#pragma once
#include <stdint.h>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#define GL_EXPORT EMSCRIPTEN_KEEPALIVE
#else
#define GL_EXPORT
#endif

#ifdef __cplusplus
extern "C" {
#endif

// Library version, "MAJOR.MINOR.PATCH".
GL_EXPORT const char* gl_version(void);

// Most threads a simulation uses: the WASM build pre-starts GL_MAX_THREADS - 1 pthread workers
// (PTHREAD_POOL_SIZE), and a thread beyond them could not start while the browser's sim worker
// is busy stepping. Thread counts above the hardware's are allowed (the thesis ran 2-4).
#define GL_MAX_THREADS 5

// A new simulation: flat ground (gl_sim_set_terrain changes it), nothing on it. `threads` is the size of the thread pool used for
// per-character work, clamped to [1, GL_MAX_THREADS] (gl_sim_threads tells the count in use).
// `seed` drives every random choice of the scene.
GL_EXPORT void* gl_sim_create(int threads, uint32_t seed);
GL_EXPORT void gl_sim_destroy(void* sim);

// Kinds of thing that can be spawned. Characters are articulated figures built from a
// morphology (native/src/body); a prop is a loose box.
enum { GL_KIND_BIPED = 0, GL_KIND_QUADRUPED = 1, GL_KIND_BOX = 2 };

// Spawns one thing standing on the ground at (x, z), facing `heading` radians (about +y, 0 = +z).
// Returns its id (>= 0), or -1 if the kind is unknown or the render buffer is full.
GL_EXPORT int gl_sim_spawn(void* sim, int kind, double x, double z, double heading);

// The speed a character of `kind` (GL_KIND_BIPED or GL_KIND_QUADRUPED) is tuned and benchmarked
// for, m/s (sim::Simulation::cruiseSpeed): the demo's start goal; 0 for any other kind.
GL_EXPORT double gl_cruise_speed(int kind);

// The foundation's demo scene: `characters` figures on a grid plus a few boxes.
GL_EXPORT void gl_sim_demo_scene(void* sim, int characters);

// Advances the simulation by `steps` fixed steps of 1/120 s, then publishes render transforms.
GL_EXPORT void gl_sim_step(void* sim, int steps);

GL_EXPORT double gl_sim_time(void* sim);           // simulated seconds
GL_EXPORT uint32_t gl_sim_step_index(void* sim);   // fixed steps taken
GL_EXPORT int gl_sim_body_count(void* sim);        // rigid bodies (instances to draw)
GL_EXPORT int gl_sim_threads(void* sim);

// Hex string of a 64-bit hash of every body's position, orientation and velocities (exact bits),
// so that two runs can be compared for bit-identical state.
GL_EXPORT const char* gl_sim_state_hash(void* sim);

// Pointer (byte offset into WASM memory) of the render buffer header, see render_buffer.h.
GL_EXPORT const void* gl_sim_render_buffer(void* sim);

// ---- Gait parameters: schema, presets, gait files (native/src/gait/schema.h, params_io.h) ----
//
// Gait files are JSON: {"format":"gaitlab-gait","version":2,"character":"biped"|"quadruped",
// "params":{"<name>": number | [4 numbers], ...},"meta":{...}} (public/presets/*.json). The
// module is the only judge of them: the page validates and migrates nothing itself.

// Error codes of the parameter functions; gl_last_error() gives the message of the last failure
// on the calling thread ("FIELD: WHAT" for a refused file).
enum {
  GL_OK = 0,
  GL_ERR_INVALID_PARAMS = 1,  // the file was refused (malformed, wrong character, bad field...)
  GL_ERR_NO_CHARACTER = 2,    // no character with that id, or none of that kind
  GL_ERR_KIND = 3,            // kind is not GL_KIND_BIPED or GL_KIND_QUADRUPED, or the
                              // character with that id is of another kind
};
GL_EXPORT const char* gl_last_error(void);

// The parameter schema: {"version":2,"characters":{"biped":[...],"quadruped":[...]},
// "morphologies":{"biped":{"kind","legFrames","legs"},...}}, an entry per parameter
// {"name","group","min","max","default","unit","description","knots","field"} plus its
// "legFrame" or "leg" ({"index","name"}) when it belongs to one (gait/schema.h).
GL_EXPORT const char* gl_schema_json(void);

// Any gait file (any schema version) validated and normalised: the current version, every
// parameter in schema order, canonical numbers, on one line, "meta" kept. NULL if it is refused
// (gl_last_error() gives "FIELD: WHAT"). Valid until the next call on the calling thread.
GL_EXPORT const char* gl_gait_normalize(const char* json);

// The shipped preset of a kind, as a gait file; NULL for a kind that is not a character.
GL_EXPORT const char* gl_preset_json(int kind);

// Validates a gait file for `kind` and gives it to the character with id `characterId` (as
// returned by gl_sim_spawn), or with characterId = -1 to every character of that kind. Nothing
// changes unless the whole file is valid. Returns GL_OK or an error code.
GL_EXPORT int gl_sim_set_params(void* sim, int characterId, int kind, const char* json);

// An edit: `patch` is a JSON object {"<name>": number | [4 numbers], ...} of some parameters and
// their new values, given to the character with id `characterId`, or with characterId = -1 to
// every character of `kind` (each keeps its other parameters). Every value is checked against
// the schema first, and nothing changes unless all are valid. Returns GL_OK or an error code
// (GL_ERR_INVALID_PARAMS with gl_last_error() "NAME: WHAT" for a refused value).
GL_EXPORT int gl_sim_patch_params(void* sim, int characterId, int kind, const char* patch);

// The gait parameters a character is using, as a gait file; NULL if there is no such character.
GL_EXPORT const char* gl_sim_get_params(void* sim, int characterId);

// ---- Optimisation, one generation at a time (native/src/optimize/optimizer.h) ----------------
//
// For the browser's optimize panel: create a search, call gl_opt_step once per generation (each
// runs `candidates` evaluations, a few tenths of a second to seconds), read the best so far.

// A new search. `kind` is GL_KIND_BIPED or GL_KIND_QUADRUPED; `method` 0 = greedy (thesis §3.3),
// 1 = CMA-ES; `start_json` a gait file to start from, or NULL for the preset; `settings_json`
// NULL or an object of objective settings ({"seconds":4,"speeds":[0.5,1],"wr":2,
// "grounds":["flat","slope@3.14159"],...}, see
// optimize/objective.h). `threads` is clamped to [1, GL_MAX_THREADS]. Returns NULL on error
// (gl_last_error() says why).
GL_EXPORT void* gl_opt_create(int kind, int method, int candidates, uint32_t seed, int threads,
                              const char* start_json, const char* settings_json);
GL_EXPORT void gl_opt_destroy(void* opt);
// The objective settings gl_opt_create accepts, for forms that check them before a search:
// {"settings":[{"name","min","max","default","unit","description","integer"},...],
//  "speeds":{"min","max","default":[...],"unit","description"},
//  "grounds":{"default":["flat"],"terrains":["flat","slope","bumps"],"description"}}
// (optimize/objective.h).
GL_EXPORT const char* gl_opt_settings_json(void);
// Runs one generation; returns the best objective so far.
GL_EXPORT double gl_opt_step(void* opt);
GL_EXPORT int gl_opt_generation(void* opt);
GL_EXPORT int gl_opt_evaluations(void* opt);
// The best parameters so far as a gait file (meta: method, seed, objective, its terms,
// generations, evaluations). Valid until the next call on this handle.
GL_EXPORT const char* gl_opt_best_json(void* opt);

// ---- Interaction: the demo page's commands (issue 5) --------------------------------------------
// Characters are named by the id gl_sim_spawn returned. The sim worker calls these between
// fixed steps only (it queues the page's commands and applies them at the start of the next
// step), so each acts at a known step index. Functions returning int give 0 on success and -1
// if no character has that id.

// Steering goal of character `id`, or of every character with id = -1: forward speed (m/s) and
// turn rate (rad/s, about +y, positive = left).
GL_EXPORT int gl_sim_set_goal(void* sim, int id, double speed, double turn_rate);

// Throws a box of half size `half` (m) from (x, y, z) with velocity (vx, vy, vz) m/s. It collides
// with characters, props and the ground; the oldest thrown box goes once there are 32. Returns
// its id, or -1 if the render buffer is full.
GL_EXPORT int gl_sim_throw_box(void* sim, double x, double y, double z, double vx, double vy,
                               double vz, double half);

// Holds point (lx, ly, lz) of segment `segment` of character `id` (segment body frame, metres;
// the segment is the character's n-th body in the render buffer) on a spring towards the world
// point (tx, ty, tz), every step until gl_sim_end_drag. Calling it again moves the target.
GL_EXPORT int gl_sim_drag(void* sim, int id, int segment, double lx, double ly, double lz,
                          double tx, double ty, double tz);
GL_EXPORT void gl_sim_end_drag(void* sim);

// Replaces character `id` by a fresh one standing where it is, same gait and goal.
GL_EXPORT int gl_sim_reset_character(void* sim, int id);
GL_EXPORT int gl_sim_remove_character(void* sim, int id);

// Characters fallen for `seconds` (leg frame below half its standing height or tilted over 60°)
// are reset automatically; 0 turns it off.
GL_EXPORT void gl_sim_set_auto_reset(void* sim, double seconds);

GL_EXPORT int gl_sim_character_count(void* sim);

// Fields per character written by gl_sim_character_info, in this order.
enum {
  GL_INFO_ID, GL_INFO_KIND, GL_INFO_X, GL_INFO_Y, GL_INFO_Z,  // root leg frame's centre, m
  GL_INFO_HEADING,        // rad about +y, 0 = +z
  GL_INFO_SPEED,          // horizontal speed of the root leg frame, m/s
  GL_INFO_FALLEN,         // 1 or 0
  GL_INFO_FALLEN_SECONDS, // how long it has been down
  GL_INFO_GOAL_SPEED, GL_INFO_GOAL_TURN,
  GL_INFO_PHASE,          // gait phase in [0, 1)
  GL_INFO_FIELDS
};
// Writes GL_INFO_FIELDS doubles per character for at most `capacity` characters into `out`;
// returns the number of characters (which may exceed `capacity`).
GL_EXPORT int gl_sim_character_info(void* sim, double* out, int capacity);

// ---- Terrain: the ground (native/src/physics/terrain.h; issue 5's ground choice) ---------------
// A terrain is a square grid of height samples joined by triangles, with a flat plane beyond it.
// The page draws its ground from the same samples the physics collides with.

enum { GL_TERRAIN_FLAT = 0, GL_TERRAIN_SLOPE = 1, GL_TERRAIN_BUMPS = 2 };

// Sets the ground of every physics shard: flat, a ±5° ridge-and-valley slope across +z, or
// 2-3 cm bumps drawn from the simulation's seed. Characters already in the scene are re-placed
// standing on the new ground where they are (same gait and goal), props lifted out of it.
// Returns 0, or -1 for an unknown kind (nothing changes).
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
// Writes GL_GRID_FIELDS doubles describing the terrain's grid into `out`.
GL_EXPORT void gl_sim_terrain_grid(void* sim, double* out);

// The samples: columns × rows floats, row-major (sample (c, r) at index r·columns + c, at
// x = origin_x + c·spacing, z = origin_z + r·spacing). Each grid cell is two triangles split along
// the diagonal from (c+1, r) to (c, r+1), as Bullet's heightfield splits it. NULL when flat.
// Owned by the simulation; valid until the terrain changes or the simulation is destroyed.
GL_EXPORT const float* gl_sim_terrain_heights(void* sim);

// Height of the ground under (x, z) as the controller sees it: a ray cast against the terrain.
GL_EXPORT double gl_sim_ground_height(void* sim, double x, double z);

// ---- Benchmark (the performance page, web/src/bench) ----------------------------------------
// The same measurement as `gaitlab bench` (native/src/sim/experiment.h), one point per call so
// that the page can report progress and cancel between points. Both return JSON strings that
// are parts of a bench/schema.json document; owned by the library, valid until the next call
// of either function on the same thread.

// The machine object of the document ("machine").
GL_EXPORT const char* gl_bench_machine(void);

// Untimed warm-up before a grid (sim::warmUp): 10 characters of `legs` (2, 4, or 0 for mixed),
// 1 s, full mode on `threads` threads.
GL_EXPORT void gl_bench_warm_up(int legs, int threads);

// The largest crowd of `legs` (2, 4, or 0 for mixed) one simulation holds.
GL_EXPORT int gl_bench_max_characters(int legs);

// Runs one point and returns its element of "points". `legs` 2, 4, or 0 (mixed); `mode` 0
// serial, 1 controller, 2 full; `threads` clamped to [1, GL_MAX_THREADS]; `frames` non-zero
// keeps per-frame statistics. Returns "" for arguments out of range (more characters than
// gl_bench_max_characters included).
GL_EXPORT const char* gl_bench_point(int legs, int characters, int threads, int mode, int steps,
                                     int runs, int shards, double spacing, uint32_t seed,
                                     int frames);

#ifdef __cplusplus
}
#endif
