// `gaitlab bench`: the thesis's performance experiment (Chapter 4) over a grid of leg counts,
// crowd sizes, thread counts and execution modes (sim/experiment.h). Its JSON document follows
// bench/schema.json, whatever the runtime (native, WASM in Node, WASM in the browser page, which
// builds the same document from benchJsonMachine / benchJsonPoint through the C API).
#pragma once
#include <nlohmann/json.hpp>

#include "sim/experiment.h"

namespace gaitlab::api {

// Version of the result document; bump when bench/schema.json changes incompatibly.
constexpr const char* kBenchSchema = "gaitlab-bench/1";

int runBenchCli(int argc, char** argv);

// The machine that measures: CPU model, logical cores, runtime and its version, compiler.
nlohmann::json benchJsonMachine();
// One point of the experiment, as an element of the document's "points".
nlohmann::json benchJsonPoint(const sim::PointResult& r);

}  // namespace gaitlab::api
