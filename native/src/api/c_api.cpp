// The C ABI (c_api.h) over sim::Simulation.
#include "api/c_api.h"

#include <string>

#include "api/cli_bench.h"
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

// ---- Benchmark ------------------------------------------------------------------------------

const char* gl_bench_machine(void) {
  g_string = gaitlab::api::benchJsonMachine().dump();
  return g_string.c_str();
}

const char* gl_bench_point(int legs, int characters, int threads, int mode, int steps, int runs,
                           int shards, double spacing, uint32_t seed, int frames) {
  g_string.clear();
  if ((legs != 0 && legs != 2 && legs != 4) || characters < 1 || characters > 2000 || mode < 0 ||
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
