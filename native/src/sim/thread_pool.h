// A persistent pool of threads running parallel-for loops over characters (thesis §3.1:
// "parallel-for paradigm for non-intrusive data parallel execution", §4.3: contiguous chunks,
// the first N mod T chunks one larger).
//
// Hot-path rules (docs/parallel.md): threads are created once; a parallelFor does
// no heap allocation and takes no lock while the workers are awake. Idle workers spin briefly
// (yielding) and then sleep on a condition variable, so an idle simulation costs no CPU; only
// waking a sleeping worker takes the mutex.
//
// Late workers. Chunk t is meant for thread t, but a chunk is claimed (an atomic compare-and-swap
// per chunk and loop) by whichever thread gets to it first: the caller, once done with its own
// chunk, takes every chunk whose thread has not started yet. On a machine whose cores are busy
// with other work (or a browser tab in the background) a worker may not be scheduled for
// milliseconds; without this the whole loop would wait for it. The chunks themselves stay
// fixed (the thesis's partition), so the results do not depend on who ran them.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <type_traits>
#include <thread>
#include <vector>

namespace gaitlab::sim {

struct Range {
  int begin, end;
};

class ThreadPool {
 public:
  // `threads` >= 1 threads take part in each loop: the caller plus threads-1 workers.
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Chunk `t` of `n` items split over `threads` (thesis §4.3).
  static Range chunk(int n, int threads, int t);

  // Calls fn(i) once for every item i of [0, n), each item taken by whichever thread of the loop
  // is free next (an atomic counter, per loop): a load balance at the grain of one item, for
  // items of unequal or unpredictable cost (the physics shards, the optimiser's episodes). A
  // thread that starts late takes fewer items instead of holding up the loop. Which thread runs
  // an item must not change what the item computes.
  template <class F>
  void forEach(int n, F&& fn) {
    std::atomic<int> next{0};
    parallelFor(size(), [&](int, int, int) {
      for (int i = next.fetch_add(1, std::memory_order_relaxed); i < n;
           i = next.fetch_add(1, std::memory_order_relaxed))
        fn(i);
    });
  }

  // Calls fn(begin, end, t) for each chunk t of the size() contiguous chunks of [0, n), normally
  // on thread t (the caller is thread 0; see "late workers" above), and returns when every chunk
  // is done.
  template <class F>
  void parallelFor(int n, F&& fn) {
    if (size() == 1 || n <= 1) {
      if (n > 0) fn(0, n, 0);
      return;
    }
    using Fn = std::remove_reference_t<F>;
    run(n, [](void* ctx, int b, int e, int t) { (*static_cast<Fn*>(ctx))(b, e, t); },
        const_cast<void*>(static_cast<const void*>(&fn)));
  }

 private:
  using Task = void (*)(void*, int, int, int);
  void run(int n, Task task, void* ctx);
  void workerLoop(int thread);
  // Runs chunk c of loop `generation` unless another thread has claimed it already.
  void runChunk(int c, uint64_t generation);

  // The loop generation each chunk was last claimed for; a cache line each, as every thread
  // writes one.
  struct alignas(64) Claim {
    std::atomic<uint64_t> generation{0};
  };

  std::vector<std::thread> workers_;
  std::unique_ptr<Claim[]> claims_;      // one per chunk, size()
  std::atomic<uint64_t> generation_{0};  // bumped once per parallelFor
  std::atomic<int> pending_{0};          // chunks of the current loop not finished yet
  std::atomic<int> sleeping_{0};
  std::atomic<bool> stop_{false};
  Task task_ = nullptr;
  void* ctx_ = nullptr;
  int n_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace gaitlab::sim
