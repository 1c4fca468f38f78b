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

// A new simulation: flat ground, nothing on it. `threads` is the size of the thread pool used for
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

// ---- Benchmark (the performance page, web/src/bench) ----------------------------------------
// The same measurement as `gaitlab bench` (native/src/sim/experiment.h), one point per call so
// that the page can report progress and cancel between points. Both return JSON strings that
// are parts of a bench/schema.json document; owned by the library, valid until the next call
// of either function on the same thread.

// The machine object of the document ("machine").
GL_EXPORT const char* gl_bench_machine(void);

// Runs one point and returns its element of "points". `legs` 2, 4, or 0 (mixed); `mode` 0
// serial, 1 controller, 2 full; `threads` clamped to [1, GL_MAX_THREADS]; `frames` non-zero
// keeps per-frame statistics. Returns "" for arguments out of range.
GL_EXPORT const char* gl_bench_point(int legs, int characters, int threads, int mode, int steps,
                                     int runs, int shards, double spacing, uint32_t seed,
                                     int frames);

#ifdef __cplusplus
}
#endif
