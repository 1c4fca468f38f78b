// The per-step hot path allocates nothing (docs/parallel.md; the original allocated inside its
// parallel region every step: defect 10 of the original implementation,
// docs/original-implementation.md). Counted here: C++ operator new
// (our code, Eigen, std::) and Bullet's btAlignedAlloc, over steps after a warm-up in which Bullet's
// contact pools and arrays have grown to the scene's size, in every execution mode.
#include <gtest/gtest.h>

#include <LinearMath/btAlignedAllocator.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "sim/simulation.h"

namespace {
std::atomic<long> g_news{0};
std::atomic<long> g_bulletAllocs{0};
std::atomic<bool> g_counting{false};

void* countingAlignedAlloc(size_t size, int alignment) {
  if (g_counting.load()) g_bulletAllocs.fetch_add(1);
  void* p = nullptr;
  if (posix_memalign(&p, alignment < static_cast<int>(sizeof(void*)) ? sizeof(void*) : alignment, size) != 0) return nullptr;
  return p;
}
void countingAlignedFree(void* p) { std::free(p); }
}  // namespace

void* operator new(size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_news.fetch_add(1);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }

using gaitlab::sim::Crowd;
using gaitlab::gait::Character;
using gaitlab::sim::Mode;
using gaitlab::sim::Simulation;

TEST(HotPath, StepsAllocateNothingInAnyMode) {
  btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree);
  for (Mode mode : {Mode::Serial, Mode::Controller, Mode::Full}) {
    Simulation sim(2, 3, 3);
    sim.crowdScene(Crowd::Mixed, 6, 4.0);
    sim.setMode(mode);
    sim.step(240);  // warm-up: the characters settle, Bullet's arrays reach their size
    g_news = 0;
    g_bulletAllocs = 0;
    g_counting = true;
    for (int i = 0; i < 60; ++i) sim.step(1);
    g_counting = false;
    EXPECT_EQ(g_news.load(), 0) << "operator new in " << gaitlab::sim::modeName(mode) << " mode";
    EXPECT_EQ(g_bulletAllocs.load(), 0) << "btAlignedAlloc in " << gaitlab::sim::modeName(mode) << " mode";
  }
  btAlignedAllocSetCustomAligned(nullptr, nullptr);
}

// A gait of several speed keys blends its parameters every step while the desired speed ramps
// (gait/speed_keys.h): that too allocates nothing.
TEST(HotPath, BlendingSpeedKeysAllocatesNothing) {
  Simulation sim(1, 3, 1);
  const int id = sim.spawn(Character::Biped, 0, 0, 0);
  ASSERT_GE(id, 0);
  gaitlab::gait::Gait gait = gaitlab::gait::Gait::single(sim.controller(0).params(), 0.0);
  gaitlab::gait::SpeedKey fast{1.0, sim.controller(0).params()};
  fast.params.period *= 0.9;
  gait.keys.push_back(fast);
  sim.controller(0).setGait(gait);
  sim.setGoal(0, {1.0, 0.0});
  sim.step(12);  // the first steps set up the controller's per-leg state
  g_news = 0;
  g_counting = true;
  for (int i = 0; i < 60; ++i) sim.step(1);  // v_d ramps from ~0 towards 1 m/s: a blend each step
  g_counting = false;
  EXPECT_EQ(g_news.load(), 0);
  const double vd = sim.controller(0).desiredVelocity().z();
  ASSERT_GT(vd, 0.05);
  ASSERT_LT(vd, 1.0);
  EXPECT_DOUBLE_EQ(sim.controller(0).params().period,
                   gait.keys[0].params.period + (fast.params.period - gait.keys[0].params.period) * vd);
}
