#include "sim/thread_pool.h"

#include <chrono>

namespace gaitlab::sim {

namespace {
// How long an idle worker keeps polling for the next loop before it sleeps. Long enough to
// bridge the serial physics step between two controller loops at crowd sizes we run, short
// enough that a paused simulation does not burn a core.
constexpr auto kSpin = std::chrono::milliseconds(5);

// One turn of a busy wait. Natively, hand the core to another runnable thread: on a machine with
// few cores shared with other work, a spinning thread would otherwise hold a core that the thread
// it waits for needs. In WebAssembly there is no yield: Emscripten's sched_yield instead drains
// the thread's proxied-call queue (a lock and a call out to JavaScript), which made every
// parallel-for of the WASM build cost milliseconds (measured: 7 ms for 2 quadrupeds on
// 2 threads in Node), so there the loop spins on the atomic alone.
inline void relax() {
#if !defined(__EMSCRIPTEN__)
  std::this_thread::yield();
#endif
}
}  // namespace

Range ThreadPool::chunk(int n, int threads, int t) {
  const int base = n / threads, rest = n % threads;
  const int begin = t * base + (t < rest ? t : rest);
  return {begin, begin + base + (t < rest ? 1 : 0)};
}

ThreadPool::ThreadPool(int threads) {
  if (threads < 1) threads = 1;
  claims_ = std::make_unique<Claim[]>(threads);
  workers_.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) workers_.emplace_back([this, t] { workerLoop(t); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true);
  }
  wake_.notify_all();
  for (std::thread& w : workers_) w.join();
}

void ThreadPool::run(int n, Task task, void* ctx) {
  task_ = task;
  ctx_ = ctx;
  n_ = n;
  pending_.store(size());
  const uint64_t generation = generation_.fetch_add(1) + 1;  // seq_cst: publishes the loop
  if (sleeping_.load() > 0) {
    std::lock_guard<std::mutex> lock(mutex_);
    wake_.notify_all();
  }
  // Chunk 0, then any chunk whose thread has not claimed it yet (late workers, see the header).
  for (int c = 0; c < size(); ++c) runChunk(c, generation);
  while (pending_.load(std::memory_order_acquire) != 0) relax();
}

void ThreadPool::runChunk(int c, uint64_t generation) {
  // Every chunk of the previous loop was claimed before that loop returned, so an unclaimed
  // chunk holds generation - 1. A thread that read an old generation fails here and touches
  // nothing of the current loop.
  uint64_t expected = generation - 1;
  if (!claims_[c].generation.compare_exchange_strong(expected, generation)) return;
  const Range r = chunk(n_, size(), c);
  if (r.begin < r.end) task_(ctx_, r.begin, r.end, c);
  pending_.fetch_sub(1, std::memory_order_release);
}

void ThreadPool::workerLoop(int thread) {
  uint64_t seen = 0;
  for (;;) {
    // Wait for a new loop: spin first, then sleep.
    const auto spinUntil = std::chrono::steady_clock::now() + kSpin;
    for (unsigned spins = 1; generation_.load() == seen && !stop_.load(); ++spins) {
      // The clock is read every 64 turns only: in WebAssembly it is a call out to JavaScript.
      if (spins % 64 != 0 || std::chrono::steady_clock::now() < spinUntil) {
        relax();
        continue;
      }
      std::unique_lock<std::mutex> lock(mutex_);
      sleeping_.fetch_add(1);
      wake_.wait(lock, [&] { return generation_.load() != seen || stop_.load(); });
      sleeping_.fetch_sub(1);
    }
    if (stop_.load()) return;
    seen = generation_.load();
    runChunk(thread, seen);
  }
}

}  // namespace gaitlab::sim
