// What the C ABI's opaque handles are (api/c_api.h): a simulation handle owns its Simulation and
// the one string its calls return, so that a string from one simulation survives calls on
// another. C++ callers (the native tests) reach the Simulation through simulationOf.
#pragma once
#include <string>

#include "sim/simulation.h"

namespace gaitlab::api {

struct SimHandle {
  SimHandle(int threads, uint32_t seed) : simulation(threads, seed) {}
  sim::Simulation simulation;
  std::string text;  // gl_sim_state_hash's and gl_sim_get_params's result
};

inline sim::Simulation& simulationOf(void* handle) { return static_cast<SimHandle*>(handle)->simulation; }

}  // namespace gaitlab::api
