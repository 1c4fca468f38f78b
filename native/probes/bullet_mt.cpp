// Probe: Bullet's own multithreaded world (btDiscreteDynamicsWorldMt) with its tasks on gaitlab's
// thread pool, against which the physics shards of `gaitlab bench --mode full` were chosen
// (docs/parallel.md). Built only on request, natively, with Bullet compiled BT_THREADSAFE:
//
//   ninja -C build/native gaitlab_bullet_mt
//   build/native/gaitlab_bullet_mt LEGS CHARACTERS THREADS STEPS RUNS
//
// Prints one JSON object: the mean whole-step and physics times (ms), the state hash of each run,
// and how many heap allocations Bullet made per step (btAlignedAlloc) once warmed up.
#include <LinearMath/btAlignedAllocator.h>
#include <LinearMath/btThreads.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "sim/simulation.h"
#include "sim/thread_pool.h"

namespace {

using gaitlab::sim::ThreadPool;

// Bullet's task-scheduler interface over gaitlab's pool: a parallel-for is one pool loop, the
// range split in contiguous chunks like every other loop (thesis §4.3); Bullet's grain size is
// ignored. Sums are added in chunk order, so a sum does not depend on which thread finished first.
// Until a pool is attached (Bullet's Mt classes ask for a scheduler when they are constructed,
// before the simulation and its pool exist) loops run on the calling thread.
//
// Bullet numbers threads from a process-wide counter, a new number for every thread that ever
// calls it, and indexes per-thread arrays sized by getNumThreads() with it: so the scheduler
// reports the most thread numbers Bullet supports, not the pool's size.
class PoolTaskScheduler : public btITaskScheduler {
 public:
  PoolTaskScheduler() : btITaskScheduler("gaitlab pool") {}
  void attach(ThreadPool* pool) { pool_ = pool; }
  int getMaxNumThreads() const override { return BT_MAX_THREAD_COUNT; }
  int getNumThreads() const override { return BT_MAX_THREAD_COUNT; }
  void setNumThreads(int) override {}
  void parallelFor(int begin, int end, int, const btIParallelForBody& body) override {
    if (!pool_) return body.forLoop(begin, end);
    pool_->parallelFor(end - begin, [&](int b, int e, int) { body.forLoop(begin + b, begin + e); });
  }
  btScalar parallelSum(int begin, int end, int, const btIParallelSumBody& body) override {
    if (!pool_) return body.sumLoop(begin, end);
    btScalar partial[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    pool_->parallelFor(end - begin, [&](int b, int e, int t) { partial[t] = body.sumLoop(begin + b, begin + e); });
    btScalar sum = 0;
    for (btScalar p : partial) sum += p;
    return sum;
  }

 private:
  ThreadPool* pool_ = nullptr;
};

std::atomic<bool> g_counting{false};
std::atomic<long> g_allocs{0};
void* countingAlloc(size_t size, int alignment) {
  if (g_counting.load()) g_allocs.fetch_add(1);
  void* p = nullptr;
  return posix_memalign(&p, alignment < 16 ? 16 : alignment, size) == 0 ? p : nullptr;
}
void countingFree(void* p) { std::free(p); }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: gaitlab_bullet_mt LEGS CHARACTERS THREADS STEPS RUNS\n");
    return 2;
  }
  const int legs = std::atoi(argv[1]), characters = std::atoi(argv[2]), threads = std::atoi(argv[3]);
  const int steps = std::atoi(argv[4]), runs = std::atoi(argv[5]);
  btAlignedAllocSetCustomAligned(countingAlloc, countingFree);
  double stepSum = 0, physicsSum = 0, stepSq = 0;
  long warmAllocs = 0;
  std::vector<std::string> hashes;
  PoolTaskScheduler scheduler;
  btSetTaskScheduler(&scheduler);
  for (int run = 0; run < runs; ++run) {
    // One world (one shard); the controller loop in the thesis's mode, the physics inside Bullet.
    scheduler.attach(nullptr);
    gaitlab::sim::Simulation sim(threads, 1, 1);
    scheduler.attach(&sim.pool());
    sim.crowdScene(legs == 2 ? gaitlab::sim::Crowd::Bipeds : gaitlab::sim::Crowd::Quadrupeds, characters, 4.0);
    sim.setMode(gaitlab::sim::Mode::Controller);
    for (int s = 0; s < steps; ++s) {
      g_counting = s >= steps / 2;
      sim.step(1);
      const auto& t = sim.lastStep();
      stepSum += t.step * 1e3;
      stepSq += t.step * 1e3 * t.step * 1e3;
      physicsSum += t.physics * 1e3;
    }
    g_counting = false;
    warmAllocs += g_allocs.exchange(0);
    hashes.push_back(sim.stateHash());
    scheduler.attach(nullptr);
  }
  const double n = static_cast<double>(steps) * runs;
  const double mean = stepSum / n;
  std::printf("{\"design\":\"bullet-mt\",\"legs\":%d,\"characters\":%d,\"threads\":%d,\"steps\":%d,\"runs\":%d,"
              "\"step_ms\":{\"mean\":%.6f,\"sd\":%.6f},\"physics_ms\":{\"mean\":%.6f},"
              "\"bullet_allocs_per_step\":%.3f,\"state_hash\":\"%s\",\"deterministic\":%s}\n",
              legs, characters, threads, steps, runs, mean, std::sqrt(std::max(0.0, stepSq / n - mean * mean)),
              physicsSum / n, warmAllocs / (n / 2), hashes[0].c_str(),
              std::set<std::string>(hashes.begin(), hashes.end()).size() == 1 ? "true" : "false");
  return 0;
}
