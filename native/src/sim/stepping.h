// The fixed step (thesis §3.2: 120 Hz) and how it uses the thread pool: the execution modes, the
// order of a step's phases, and their timing.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

#include "physics/world.h"
#include "sim/thread_pool.h"

namespace gaitlab::sim {

// How a fixed step uses the thread pool (chosen at run time; docs/parallel.md):
//   Serial      everything on the calling thread;
//   Controller  the thesis's mode (§3.1, §4.1): the controller loop is a parallel-for over the
//               characters in T contiguous chunks, the first N mod T one larger (§4.3); physics
//               is serial;
//   Full        the controller loop as above, then the physics shards in parallel, each shard
//               taken by the next free thread (ThreadPool::forEach).
enum class Mode { Serial = 0, Controller = 1, Full = 2 };
const char* modeName(Mode mode);
bool parseMode(const std::string& name, Mode* out);

// Wall-clock seconds of one fixed step. `controller` is the thesis's measure (§4.1: "from before
// the start of the first thread until all threads have finished"), `physics` the same for the
// Bullet step and contact update, `step` the whole fixed step (both, plus moving props between
// shards), render publishing excluded as the thesis excluded rendering.
struct StepTiming {
  double controller = 0, physics = 0, step = 0;
};

// The stepping loop: the step count, the execution mode and the thread pool, the timing.
class Stepping {
 public:
  explicit Stepping(int threads) : pool_(threads) {}

  Mode mode() const { return mode_; }
  void setMode(Mode mode) { mode_ = mode; }
  ThreadPool& pool() { return pool_; }
  int threads() const { return pool_.size(); }

  uint32_t stepIndex() const { return stepIndex_; }
  double time() const { return stepIndex_ * physics::kFixedStep; }
  const StepTiming& lastStep() const { return lastStep_; }
  double controllerSeconds() const { return controllerSeconds_; }
  double physicsSeconds() const { return physicsSeconds_; }

  // `steps` fixed steps, each in the order of Algorithm 1 (thesis §3.1):
  //   control(i)      the controller of character i of `characters` (the parallel-for);
  //   forces()        external forces for this step (the pointer's drag spring);
  //   physics(s)      the physics of shard s of `shards`;
  //   settle()        after the step index has advanced: between-step bookkeeping (props
  //                   change shards, fallen characters are noted and perhaps reset).
  // Callables rather than std::function: nothing here may allocate (the hot-path test).
  template <class Control, class Forces, class Physics, class Settle>
  void run(int steps, int characters, int shards, Control&& control, Forces&& forces,
           Physics&& physics, Settle&& settle) {
    using Clock = std::chrono::steady_clock;
    const auto seconds = [](Clock::time_point a, Clock::time_point b) {
      return std::chrono::duration<double>(b - a).count();
    };
    const auto controlChunk = [&](int begin, int end, int) {
      for (int i = begin; i < end; ++i) control(i);
    };
    for (int s = 0; s < steps; ++s) {
      // The controller loop is the parallel-for (thesis §3.1, §4.3), timed from before the
      // first thread starts until the last is done (§4.1).
      const auto t0 = Clock::now();
      if (mode_ == Mode::Serial) {
        controlChunk(0, characters, 0);
      } else {
        pool_.parallelFor(characters, controlChunk);
      }
      const auto t1 = Clock::now();
      forces();
      // Physics: the shards one after another, or (full mode) each shard taken by the next
      // free thread (ThreadPool::forEach: shards differ in cost, and on a shared machine a
      // thread may start late; docs/parallel.md). Each shard computes the same thing either
      // way; only the thread that runs it differs.
      if (mode_ == Mode::Full) {
        pool_.forEach(shards, physics);
      } else {
        for (int shard = 0; shard < shards; ++shard) physics(shard);
      }
      const auto t2 = Clock::now();
      ++stepIndex_;
      settle();
      const auto t3 = Clock::now();
      lastStep_ = {seconds(t0, t1), seconds(t1, t2), seconds(t0, t3)};
      controllerSeconds_ += lastStep_.controller;
      physicsSeconds_ += lastStep_.physics;
    }
  }

 private:
  ThreadPool pool_;
  Mode mode_ = Mode::Controller;
  uint32_t stepIndex_ = 0;
  StepTiming lastStep_;
  double controllerSeconds_ = 0, physicsSeconds_ = 0;
};

}  // namespace gaitlab::sim
