#include "sim/thread_budget.h"

#include <algorithm>
#include <atomic>
#include <limits>
#include <thread>

#ifdef __EMSCRIPTEN__
#include <emscripten/emscripten.h>
#include <emscripten/threading.h>
#endif

namespace gaitlab::sim {
namespace {

#ifdef __EMSCRIPTEN__
// The Workers Emscripten pre-started for this module: all are unused before the first thread
// starts. Read once, by the module's static initialisation, which runs on the thread that owns
// the module (a pthread's JavaScript context has no pool of its own).
EM_JS(int, gaitlab_pool_workers, (), { return PThread.unusedWorkers.length + PThread.runningWorkers.length; });
const int kPoolWorkers = std::min(gaitlab_pool_workers(), kMaxThreads - 1);
#else
constexpr int kPoolWorkers = std::numeric_limits<int>::max();
#endif

std::atomic<int> g_workersInUse{0};

}  // namespace

int deviceCores() {
#ifdef __EMSCRIPTEN__
  const int cores = emscripten_num_logical_cores();
#else
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
#endif
  return std::max(1, cores);
}

int maxThreads() { return kPoolWorkers >= kMaxThreads - 1 ? kMaxThreads : 1 + kPoolWorkers; }

int defaultThreads() { return std::clamp(deviceCores(), 1, maxThreads()); }

bool takeWorkers(int threads) {
  const int want = threads - 1;
  int used = g_workersInUse.load();
  do {
    if (want > kPoolWorkers - used) return false;
  } while (!g_workersInUse.compare_exchange_weak(used, used + want));
  return true;
}

void giveWorkers(int threads) { g_workersInUse -= threads - 1; }

std::string noWorkers(int threads) {
  const std::string s = std::to_string(threads);
  return "threads: " + s + " needs " + std::to_string(threads - 1) + " pool threads and only " +
         std::to_string(kPoolWorkers - g_workersInUse.load()) + " of the module's " + std::to_string(kPoolWorkers) +
         " are free (the pool is sized from the device's cores when the module loads; other simulations or searches "
         "use the rest)";
}

}  // namespace gaitlab::sim
