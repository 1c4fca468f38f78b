// Arena wandering (sim/wander.h): the turn rate points a character at the arena's centre near
// its edge and away from a neighbour ahead, never beyond the measured ±0.3 rad/s; a wandering
// crowd stays inside its arena and keeps walking; and a run replays bit for bit however it is
// stepped, through the C ABI as through the C++ API.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "api/c_api.h"
#include "sim/simulation.h"
#include "sim/wander.h"

using gaitlab::sim::Simulation;
using gaitlab::sim::WanderBody;
using gaitlab::sim::wanderTurnRate;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST(Wander, AtTheEdgeFacingOutItTurnsBackAtTheFullRate) {
  // At (9.5, 0) in an arena of 10 m, facing +x (heading pi/2: straight out): the centre is
  // behind; either way round is a full turn, and the rate is the limit.
  std::vector<WanderBody> bodies{{0, 9.5, 0, kPi / 2, 1.0, true, false}};
  EXPECT_NEAR(std::abs(wanderTurnRate(bodies, 0, 10, 0)), 0.3, 1e-12);
  // Facing +z at (9.5, 0): the centre is to the right (-x is right when facing +z): negative.
  bodies[0].heading = 0;
  EXPECT_NEAR(wanderTurnRate(bodies, 0, 10, 0), -0.3, 1e-12);
  // The same at (-9.5, 0): the centre is to the left.
  bodies[0].x = -9.5;
  EXPECT_NEAR(wanderTurnRate(bodies, 0, 10, 0), 0.3, 1e-12);
}

TEST(Wander, ItTurnsAwayFromANeighbourAheadAndIgnoresOneBehind) {
  // In the middle of a large arena, facing +z, a neighbour 1 m ahead and a little left (+x):
  // turn right (negative). The same neighbour behind: only the drift, which is smaller.
  std::vector<WanderBody> bodies{{0, 0, 0, 0, 1.0, true, false}, {1, 0.3, 1.0, 0, 1.0, true, false}};
  const double ahead = wanderTurnRate(bodies, 0, 100, 0);
  EXPECT_LT(ahead, -0.1);
  bodies[1].z = -1.0;
  EXPECT_LE(std::abs(wanderTurnRate(bodies, 0, 100, 0)), 0.5 * 0.3 + 1e-12);
}

TEST(Wander, AWanderingCrowdStaysInItsArenaAndKeepsWalking) {
  // The demo's mixed crowd (smaller, for time): 6 characters wander in an arena of 10 m for
  // 30 simulated seconds (the bipeds reach its edge within 10 s); none leaves it and every one
  // still walks. (The page's 5-minute check is tests/e2e/demo-crowd.test.mjs.)
  Simulation sim(1, 1);
  sim.demoScene(6);
  const double radius = 10;
  ASSERT_TRUE(sim.setWander(-1, radius));
  for (int second = 0; second < 30; ++second) {
    sim.step(120);
    for (int i = 0; i < sim.characterCount(); ++i) {
      const auto& c = sim.character(i);
      const auto root = c.segmentState(c.morphology().legFrames[0]);
      EXPECT_LT(std::hypot(root.position.x(), root.position.z()), radius) << "character " << i << " at " << second << " s";
    }
  }
  int walking = 0;
  for (int i = 0; i < sim.characterCount(); ++i) {
    const auto& c = sim.character(i);
    const auto root = c.segmentState(c.morphology().legFrames[0]);
    if (!sim.fallen(i) && std::hypot(root.linearVelocity.x(), root.linearVelocity.z()) > 0.15) ++walking;
  }
  EXPECT_EQ(walking, 6) << "of 6";
}

TEST(Wander, ARunReplaysTheSameHoweverItIsStepped) {
  // Wandering steers at fixed step indices, so one batch of 250 steps and 250 single steps give
  // the same state; the C ABI's call gives the same as the C++ API's.
  Simulation a(1, 3, gaitlab::sim::kCrowdShards);  // as gl_sim_create makes it
  a.demoScene(6);
  a.setWander(-1, 10);
  a.step(250);
  void* b = gl_sim_create(1, 3);
  ASSERT_EQ(gl_sim_demo_scene(b, 6), GL_OK);
  ASSERT_EQ(gl_sim_set_wander(b, -1, 10), GL_OK);
  for (int s = 0; s < 250; ++s) gl_sim_step(b, 1);
  EXPECT_EQ(a.stateHash(), std::string(gl_sim_state_hash(b)));
  // Without wandering the run differs (the wanderers turned).
  Simulation c(1, 3, gaitlab::sim::kCrowdShards);
  c.demoScene(6);
  c.step(250);
  EXPECT_NE(a.stateHash(), c.stateHash());
  gl_sim_destroy(b);
}

TEST(Wander, TheCallRefusesUnderTheABIsConvention) {
  void* s = gl_sim_create(1, 1);
  ASSERT_EQ(gl_sim_demo_scene(s, 2), GL_OK);
  const std::string before = gl_sim_state_hash(s);
  EXPECT_EQ(gl_sim_set_wander(s, -1, 1.0), GL_ERR_ARGUMENT);
  EXPECT_NE(std::string(gl_last_error()).find("arena_radius"), std::string::npos);
  EXPECT_EQ(gl_sim_set_wander(s, -1, std::nan("")), GL_ERR_ARGUMENT);
  EXPECT_EQ(gl_sim_set_wander(s, 9999, 10), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_set_wander(s, 0, 10), GL_OK);
  EXPECT_EQ(gl_sim_set_wander(s, 0, 0), GL_OK);
  gl_sim_step(s, 0);
  EXPECT_EQ(before, std::string(gl_sim_state_hash(s)));
  gl_sim_destroy(s);
}
