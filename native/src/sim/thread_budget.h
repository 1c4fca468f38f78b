// How many threads the process may run for its simulations, searches and benchmark points, and
// how many it uses by default: every core of the device, up to kMaxThreads.
//
// Natively a thread is made when a ThreadPool asks for one, so any count up to kMaxThreads can
// be used (more than the cores too: the results never depend on the count, docs/parallel.md).
// The WASM build cannot make a thread in the middle of a step: a pthread is a Web Worker, and a
// new Worker starts only once the thread that asked for it returns to its event loop, which the
// worker that owns the module does not do while it steps. So Emscripten pre-starts a pool of
// Workers when the module loads (PTHREAD_POOL_SIZE, native/CMakeLists.txt), sized from the
// device's cores (native/src/api/pthread_pool.pre.js.in), and every simulation, search and
// benchmark point takes its workers (threads - 1) from that pool and gives them back when it
// ends. One that would need more than are free is refused (the C ABI returns NULL or an error,
// the CLI says so): a thread beyond the pool would abort the module (PTHREAD_POOL_SIZE_STRICT=2)
// rather than hang it, so it is never asked for.
#pragma once
#include <string>

namespace gaitlab::sim {

// Most threads one simulation, search or benchmark point uses (GL_MAX_THREADS of the C ABI).
// 16: the cores of today's larger desktops; a pre-started Web Worker costs a pthread stack
// (2 MiB of the module's fixed heap, sim/capacity.h) and a JavaScript context, so the pool is
// never made larger than the device can use.
constexpr int kMaxThreads = 16;

// The device's logical cores: std::thread::hardware_concurrency natively; in the WASM build
// navigator.hardwareConcurrency (the core count in Node). At least 1.
int deviceCores();

// Most threads one simulation can use in this process: natively kMaxThreads, in the WASM build
// 1 + the pool's workers (fixed when the module loaded).
int maxThreads();

// The thread count used when none is asked for: every core, at most maxThreads().
int defaultThreads();

// Takes threads - 1 workers of the WASM build's pool, all or none; false when fewer are free.
// Natively always true. Every true must be matched by giveWorkers(threads).
bool takeWorkers(int threads);
void giveWorkers(int threads);
// Why takeWorkers(threads) said no: "threads: 8 needs 7 pool threads and only 1 of the
// module's 1 are free ...".
std::string noWorkers(int threads);

}  // namespace gaitlab::sim
