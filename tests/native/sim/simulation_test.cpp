// The foundation's simulation: bodies fall under Bullet onto the ground, the render buffer is
// published, and the state hash is the same for the same inputs whatever the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include "api/c_api.h"
#include "sim/simulation.h"

using gaitlab::gait::Character;
using gaitlab::sim::Simulation;

TEST(Simulation, FiguresFallAndComeToRestOnTheGround) {
  Simulation sim(1, 7);
  sim.demoScene(4);
  ASSERT_GT(sim.bodyCount(), 4);
  sim.step(240);
  EXPECT_NEAR(sim.time(), 2.0, 1e-9);
  for (int c = 0; c < sim.characterCount(); ++c) {
    const auto& ch = sim.character(c);
    for (int s = 0; s < ch.segmentCount(); ++s) {
      const auto st = ch.segmentState(s);
      // Centres stay above the ground, up to the solver's contact penetration (a few cm for a
      // collapsed ragdoll lying on a limb).
      EXPECT_GT(st.position.y(), -0.05) << "segment fell through the ground";
      EXPECT_LT(st.position.y(), 1.6);
      EXPECT_TRUE(st.position.allFinite());
    }
  }
}

TEST(Simulation, RenderBufferPublishesTheNewestFrame) {
  Simulation sim(1, 3);
  sim.spawnBox(0, 0, 0);
  const gaitlab::RenderHeader* h = sim.renderBuffer();
  const uint32_t seq0 = h->seq.load();
  sim.step(60);
  EXPECT_EQ(h->seq.load(), seq0 + 2);
  const uint32_t f = h->front.load();
  EXPECT_EQ(h->bodyCount[f], 1u);
  EXPECT_EQ(h->stepIndex[f], 60u);
  const auto* base = reinterpret_cast<const unsigned char*>(h);
  const float* m = reinterpret_cast<const float*>(base + h->matrices[f]);
  // The box fell from 1.5 m: its translation is below that, and its scale is its full size.
  EXPECT_LT(m[13], 1.5f);
  EXPECT_NEAR(std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]), 0.3f, 1e-5f);
}

TEST(Simulation, StateHashIsTheSameForTheSameInputsAndAnyThreadCount) {
  std::string hashes[3];
  for (int t = 1; t <= 3; ++t) {
    Simulation sim(t, 11);
    sim.demoScene(5);
    sim.step(120);
    hashes[t - 1] = sim.stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
  EXPECT_EQ(hashes[0], hashes[2]);
  Simulation other(1, 12);
  other.demoScene(5);
  other.step(120);
  EXPECT_NE(other.stateHash(), hashes[0]) << "a different seed should give a different scene";
}

TEST(CApi, CreatesStepsAndDestroys) {
  void* s = gl_sim_create(2, 5);
  EXPECT_EQ(gl_sim_threads(s), 2);
  EXPECT_EQ(gl_sim_spawn(s, 99, 0, 0, 0), -1) << "unknown kind is refused";
  EXPECT_GE(gl_sim_spawn(s, GL_KIND_BIPED, 0, 0, 0), 0);
  gl_sim_step(s, 12);
  EXPECT_EQ(gl_sim_step_index(s), 12u);
  EXPECT_EQ(std::string(gl_sim_state_hash(s)).size(), 16u);
  gl_sim_destroy(s);
}

TEST(CApi, ThreadCountIsClampedToWhatTheWasmPoolCanStart) {
  void* s = gl_sim_create(64, 1);
  EXPECT_EQ(gl_sim_threads(s), GL_MAX_THREADS);
  gl_sim_destroy(s);
  s = gl_sim_create(0, 1);
  EXPECT_EQ(gl_sim_threads(s), 1);
  gl_sim_destroy(s);
}

TEST(CApi, NativelyEveryThreadCountUpToTheLimitIsServedAndTheDefaultIsEveryCore) {
  // Natively threads are made on demand: no pool to run out of (sim/thread_budget.h).
  EXPECT_EQ(gl_pool_threads(), GL_MAX_THREADS);
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  EXPECT_EQ(gl_default_threads(), std::clamp(cores, 1, GL_MAX_THREADS));
  std::vector<void*> sims;
  for (int i = 0; i < 3; ++i) sims.push_back(gl_sim_create(GL_MAX_THREADS, 1));
  for (void* s : sims) {
    ASSERT_NE(s, nullptr) << gl_last_error();
    EXPECT_EQ(gl_sim_threads(s), GL_MAX_THREADS);
    gl_sim_destroy(s);
  }
}
