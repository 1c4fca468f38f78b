// The state hash: two runs compared for bit-identical state (every execution mode and thread
// count must give the same, docs/parallel.md), as 16 hex digits.
#pragma once
#include <string>

#include "sim/render_publisher.h"

namespace gaitlab::sim {

// 64-bit FNV-1a over the exact bits of every body's transform and velocities, in render order
// (the order bodies were added to the scene, so the same scene always hashes the same way).
std::string stateHash(const RenderPublisher& bodies);

}  // namespace gaitlab::sim
