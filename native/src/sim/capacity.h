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

// Heap one more thing costs in the WASM build once it has walked among others: its bodies,
// joints and collision shapes, its controller and buffers, its render entries, its contacts.
// Measured with 20 of a kind after 2 s of walking (bench/wasm.mjs bench, the scene heap):
// 86 KiB a biped, 244 KiB a quadruped (natively 96 and 273); a box 17 KiB among others and 65 KiB
// when 64 are dropped on one spot (every box touching every other). Rounded up.
constexpr int64_t kBipedBytes = 128 * 1024;
constexpr int64_t kQuadrupedBytes = 320 * 1024;
constexpr int64_t kBoxBytes = 96 * 1024;
// And while it is added: the physics world's constraint-solver pools are sized for all of its
// bodies (physics/world.cpp, reserveFor: about 36 solver rows of ~160 bytes and their order
// indices per body) and grow by reallocation, so for a moment the old pools and the new ones
// are both held. A spawn into a world of B bodies therefore needs this much per body free on
// top of its own cost; without it the module aborted (OOM) at 1216 bipeds with 110 MB "free".
constexpr int64_t kSolverBytesPerBody = 8 * 1024;
// A new simulation before anything is in it: its render buffer (16384 bodies, 2.5 MB), the
// Bullet world and its ground, the thread pool's threads (stacks included): 6.7 MB measured.
constexpr int64_t kSimulationBytes = 8 * 1024 * 1024;
// And each of its pool's workers beyond the first: a pthread's stack comes from the same heap
// (Emscripten's default, 2 MiB), and the pool may now hold up to 15 of them (sim/thread_budget.h).
constexpr int64_t kWorkerStackBytes = 2 * 1024 * 1024;
// Heap kept free for everything a running page needs besides the scene: a step's scratch
// buffers, gait files being parsed, the optimiser's candidates, the strings the ABI returns.
constexpr int64_t kHeapReserve = 24 * 1024 * 1024;

// Bytes the heap can still give before kHeapReserve is touched; -1 when there is no fixed heap
// (the native build).
int64_t heapHeadroom();

// How many things of `bytes` each, with `bodies` bodies each, fit in `headroom` bytes when the
// world they join already has `worldBodies` bodies (kSolverBytesPerBody). The k-th one needs
// bytes + kSolverBytesPerBody * (worldBodies + k * bodies) free after the first k - 1 took
// theirs; this is the largest count for which every one of them has it.
int64_t affordable(int64_t headroom, int64_t bytes, int bodies, int worldBodies);

}  // namespace gaitlab::sim
