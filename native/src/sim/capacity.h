// What a simulation can still afford: the capacity checks that let the module refuse a spawn
// before any allocation can fail. The WASM build has a fixed heap (native/CMakeLists.txt:
// INITIAL_MEMORY, no growth) that every simulation, the optimiser and the page's strings share;
// a character or a box that does not fit would abort the module in the middle of an allocation
// (Emscripten's "OOM"), taking the page's scene with it. So each thing is charged the heap it
// will use, measured (README, "Limits"; tests/wasm/limits.test.mjs checks the figures still
// hold), and a spawn is refused while the heap left is less than that plus a reserve for
// everything else.
//
// Natively the heap is the machine's: the render buffer (RenderPublisher::kCapacity bodies) and
// api/limits.h's kMaxBoxes bound a simulation there, and heapHeadroom() says "no limit".
#pragma once
#include <cstdint>

namespace gaitlab::sim {

// Heap one more thing costs in the WASM build: its bodies, joints and collision shapes in the
// Bullet world, its controller and its buffers, its render entries, and its share of the world's
// contact, island and solver buffers once it walks among others. Measured (README, "Limits") and
// rounded up.
constexpr int64_t kBipedBytes = 160 * 1024;
constexpr int64_t kQuadrupedBytes = 200 * 1024;
constexpr int64_t kBoxBytes = 16 * 1024;
// A new simulation before anything is in it: its render buffer (16384 bodies, 2.5 MB), the
// Bullet world and its ground, the thread pool's threads (stacks included).
constexpr int64_t kSimulationBytes = 8 * 1024 * 1024;
// Heap kept free for everything a running page needs besides the scene: a step's scratch
// buffers, gait files being parsed, the optimiser's candidates, the strings the ABI returns.
constexpr int64_t kHeapReserve = 24 * 1024 * 1024;

// Bytes the heap can still give before kHeapReserve is touched; -1 when there is no fixed heap
// (the native build).
int64_t heapHeadroom();

}  // namespace gaitlab::sim
