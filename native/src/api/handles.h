// What the C ABI's opaque handles are (api/c_api.h): a simulation handle owns its Simulation and
// the one string its calls return, so that a string from one simulation survives calls on
// another. C++ callers (the native tests) reach the Simulation through simulationOf.
#pragma once
#include <string>

#include "sim/simulation.h"

namespace gaitlab::api {

struct SimHandle {
  // The demo's crowd grows at run time: its physics is split as the benchmark's crowds are
  // (sim::kCrowdShards, physics_shards.h), each character added to the least populated shard.
  SimHandle(int threads, uint32_t seed) : simulation(threads, seed, sim::kCrowdShards) {}
  sim::Simulation simulation;
  std::string text;  // gl_sim_state_hash's and gl_sim_get_params's result
};

inline sim::Simulation& simulationOf(void* handle) { return static_cast<SimHandle*>(handle)->simulation; }

}  // namespace gaitlab::api
