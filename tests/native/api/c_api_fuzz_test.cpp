// The C ABI under hostile calls (c_api.h, api/limits.h): random sequences of the demo page's
// commands with arguments drawn from NaN, the infinities, huge, negative, zero and ordinary
// values each return a result or a refusal with a message, never a crash, a hang, an abort or a
// character whose state is not finite. Plus the properties behind it: a numeric command is
// refused naming the argument; a character whose state stops being finite anyway counts as fallen,
// is isolated, and every reset path rebuilds it standing; room is refused before allocation.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "api/c_api.h"
#include "api/handles.h"
#include "api/limits.h"
#include "sim/experiment.h"

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::vector<double> infos(void* sim) {
  std::vector<double> out(static_cast<size_t>(gl_sim_character_count(sim)) * GL_INFO_FIELDS);
  gl_sim_character_info(sim, out.data(), gl_sim_character_count(sim));
  return out;
}

// The property after every call: each character's reported state is finite.
void expectFinite(void* sim) {
  const std::vector<double> info = infos(sim);
  for (size_t i = 0; i < info.size(); ++i) ASSERT_TRUE(std::isfinite(info[i])) << "field " << i % GL_INFO_FIELDS;
}

// An argument as a hostile caller would choose it.
struct Hostile {
  std::mt19937 rng;
  double number() {
    static const double special[] = {kNaN, kInf, -kInf, 1e300, -1e300, 1e9, -1e9, 0.0, -0.0, 1e-320, 6.0, -6.0};
    if (rng() % 3 == 0) return special[rng() % (sizeof special / sizeof *special)];
    return std::uniform_real_distribution<double>(-4, 4)(rng);
  }
  int integer() {
    static const int special[] = {-1, 0, 1, 2, 3, 7, -2147483647 - 1, 2147483647, 65536, 1 << 20};
    return special[rng() % (sizeof special / sizeof *special)];
  }
};

}  // namespace

TEST(CApiFuzz, RandomCommandsReturnAResultOrARefusalAndLeaveTheStateFinite) {
  void* sim = gl_sim_create(2, 7);
  ASSERT_NE(sim, nullptr);
  ASSERT_EQ(gl_sim_add_characters(sim, GL_LAYOUT_ALTERNATING, 3), 3);
  Hostile h{std::mt19937(99)};
  int refusals = 0, successes = 0;
  for (int call = 0; call < 600; ++call) {
    const std::vector<double> info = infos(sim);
    // Mostly ids that exist, so that calls get past the id check to their numbers.
    const int id = info.empty() || h.rng() % 4 == 0 ? h.integer()
                                                    : static_cast<int>(info[(h.rng() % (info.size() / GL_INFO_FIELDS)) * GL_INFO_FIELDS]);
    int result = 0;
    switch (h.rng() % 13) {
      case 0: result = gl_sim_set_goal(sim, h.rng() % 3 ? id : -1, h.number(), h.number()); break;
      case 1: result = gl_sim_spawn(sim, h.integer() & 3, h.number(), h.number(), h.number()); break;
      case 2: {
        const gl_throw_settings t{{h.number(), h.number(), h.number()}, {h.number(), h.number(), h.number()}, h.number()};
        result = gl_sim_throw_box(sim, &t);
        break;
      }
      case 3: {
        const gl_drag_settings d{id, h.integer() & 15, {h.number(), h.number(), h.number()}, {h.number(), h.number(), h.number()}};
        result = gl_sim_drag(sim, &d);
        break;
      }
      case 4: result = gl_sim_set_auto_reset(sim, h.number()); break;
      case 5: result = gl_sim_reset_character(sim, id); break;
      case 6: result = h.rng() % 4 ? 0 : gl_sim_remove_character(sim, id); break;
      case 7: result = gl_sim_set_terrain(sim, h.integer()); break;
      case 8: result = gl_sim_room(sim, h.integer()); break;
      case 9: result = gl_sim_add_characters(sim, h.integer(), static_cast<int>(h.rng() % 4) - 1); break;
      case 10: result = gl_sim_step(sim, h.rng() % 2 ? h.integer() : 2); break;
      case 11: {
        const gl_throw_at_settings t{id, h.integer() & 15, {h.number(), h.number(), h.number()},
                                     {h.number(), h.number(), h.number()}, h.number(), h.number()};
        result = gl_sim_throw_at(sim, &t);
        break;
      }
      default: {
        const double y = gl_sim_ground_height(sim, h.number(), h.number());
        result = std::isnan(y) ? GL_ERR_ARGUMENT : 0;
        break;
      }
    }
    if (result < 0) {
      ++refusals;
      EXPECT_GT(std::string(gl_last_error()).size(), 0u);
    } else {
      ++successes;
    }
    ASSERT_NO_FATAL_FAILURE(expectFinite(sim));
    if (gl_sim_character_count(sim) > 12) gl_sim_remove_character(sim, static_cast<int>(infos(sim)[0]));
  }
  gl_sim_step(sim, 60);
  expectFinite(sim);
  EXPECT_GT(refusals, 100);
  EXPECT_GT(successes, 100);
  gl_sim_destroy(sim);
}

TEST(CApiFuzz, NumericCommandsAreRefusedNamingTheArgument) {
  void* sim = gl_sim_create(1, 1);
  const int biped = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  ASSERT_GE(biped, 0);
  const auto refusedNaming = [](int result, const std::string& name) {
    EXPECT_EQ(result, GL_ERR_ARGUMENT) << name;
    EXPECT_EQ(std::string(gl_last_error()).rfind(name, 0), 0u) << gl_last_error();
  };
  refusedNaming(gl_sim_set_goal(sim, -1, kNaN, 0), "goal speed: NaN is not finite");
  refusedNaming(gl_sim_set_goal(sim, biped, 1, kInf), "goal turn rate: Infinity is not finite");
  refusedNaming(gl_sim_set_goal(sim, biped, 1e6, 0), "goal speed: 1000000.0 is outside [-5.0, 5.0]");
  refusedNaming(gl_sim_spawn(sim, GL_KIND_BOX, 0, -kInf, 0), "z: -Infinity is not finite");
  refusedNaming(gl_sim_spawn(sim, GL_KIND_BIPED, 1e9, 0, 0), "x: 1000000000.0 is outside");
  refusedNaming(gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 1e9), "heading: ");
  const gl_throw_settings fast{{0, 1, 0}, {0, 0, 1e4}, 0.1};
  refusedNaming(gl_sim_throw_box(sim, &fast), "velocity: ");
  const gl_throw_settings diagonal{{0, 1, 0}, {80, 80, 0}, 0.1};  // each within, the speed not
  refusedNaming(gl_sim_throw_box(sim, &diagonal), "velocity: ");
  const gl_drag_settings far{biped, 0, {0, 0, 0}, {0, 1e7, 0}};
  refusedNaming(gl_sim_drag(sim, &far), "target: ");
  const gl_drag_settings nanLocal{biped, 0, {kNaN, 0, 0}, {0, 0, 0}};
  refusedNaming(gl_sim_drag(sim, &nanLocal), "local: ");
  refusedNaming(gl_sim_set_auto_reset(sim, kInf), "seconds: Infinity is outside");
  refusedNaming(gl_sim_step(sim, gaitlab::limits::kMaxStepsPerCall + 1), "steps: ");
  // Nothing was changed by the refusals: the goal is the one it had.
  EXPECT_EQ(infos(sim)[GL_INFO_GOAL_SPEED], 0.0);
  gl_sim_destroy(sim);
}

TEST(CApiFuzz, ACharacterWhoseStateIsNotFiniteIsFallenIsolatedAndResetByEveryPath) {
  void* sim = gl_sim_create(1, 3);
  ASSERT_EQ(gl_sim_add_characters(sim, GL_LAYOUT_ALTERNATING, 2), 2);
  gl_sim_step(sim, 30);
  gaitlab::sim::Simulation& S = gaitlab::api::simulationOf(sim);
  // What a physics blow-up leaves: one body of character 0 with a velocity that is not finite.
  const auto breakCharacter = [&] {
    S.character(0).body(1)->setLinearVelocity(btVector3(kNaN, 0, 0));
    S.character(0).body(1)->activate(true);
  };
  // Each reset path: a reset, the automatic reset, a terrain switch.
  const std::vector<std::pair<const char*, std::function<void()>>> resets = {
      {"reset", [&] { ASSERT_EQ(gl_sim_reset_character(sim, static_cast<int>(infos(sim)[GL_INFO_ID])), GL_OK); }},
      {"auto-reset", [&] {
         ASSERT_EQ(gl_sim_set_auto_reset(sim, 0.25), GL_OK);
         gl_sim_step(sim, 40);
         ASSERT_EQ(gl_sim_set_auto_reset(sim, 0), GL_OK);
       }},
      {"terrain", [&] { ASSERT_EQ(gl_sim_set_terrain(sim, GL_TERRAIN_BUMPS), GL_OK); }},
  };
  for (const auto& [name, reset] : resets) {
    SCOPED_TRACE(name);
    breakCharacter();
    gl_sim_step(sim, 2);
    ASSERT_TRUE(S.broken(0));
    std::vector<double> info = infos(sim);
    EXPECT_EQ(info[GL_INFO_FALLEN], 1.0);  // counted fallen
    ASSERT_NO_FATAL_FAILURE(expectFinite(sim));
    EXPECT_NE(std::string(gl_sim_state_hash(sim)).size(), 0u);
    // Isolated: the other character walks on, finite.
    gl_sim_step(sim, 20);
    info = infos(sim);
    EXPECT_EQ(info[GL_INFO_FIELDS + GL_INFO_FALLEN], 0.0);
    ASSERT_NO_FATAL_FAILURE(expectFinite(sim));
    reset();
    EXPECT_FALSE(S.broken(0));
    gl_sim_step(sim, 30);
    info = infos(sim);
    EXPECT_EQ(info[GL_INFO_FALLEN], 0.0) << "rebuilt standing";
    ASSERT_NO_FATAL_FAILURE(expectFinite(sim));
  }
  gl_sim_destroy(sim);
}

TEST(CApiFuzz, RoomIsCountedAndASpawnBeyondItIsRefusedWithTheReason) {
  void* sim = gl_sim_create(1, 1);
  // A new simulation holds what the benchmark says it holds.
  EXPECT_EQ(gl_sim_room(sim, GL_KIND_BIPED), gl_bench_max_characters(GL_LEGS_BIPED));
  EXPECT_EQ(gl_sim_room(sim, GL_KIND_QUADRUPED), gl_bench_max_characters(GL_LEGS_QUADRUPED));
  EXPECT_EQ(gl_sim_room(sim, GL_KIND_BOX), gaitlab::limits::kMaxBoxes);
  EXPECT_EQ(gl_sim_room(sim, 3), GL_ERR_ARGUMENT);
  const int bipeds = gl_sim_room(sim, GL_KIND_BIPED);
  const int biped = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  EXPECT_EQ(gl_sim_room(sim, GL_KIND_BIPED), bipeds - 1);
  // Boxes dropped on one spot: every one touches every other. The 65th is refused.
  for (int i = 0; i < gaitlab::limits::kMaxBoxes; ++i) ASSERT_GE(gl_sim_spawn(sim, GL_KIND_BOX, 3, 3, 0), 0) << i;
  EXPECT_EQ(gl_sim_room(sim, GL_KIND_BOX), 0);
  EXPECT_EQ(gl_sim_spawn(sim, GL_KIND_BOX, 3, 3, 0), GL_ERR_FULL);
  EXPECT_NE(std::string(gl_last_error()).find("64 boxes"), std::string::npos) << gl_last_error();
  const gl_throw_settings t{{0, 1, 0}, {0, 0, 1}, 0.1};
  EXPECT_EQ(gl_sim_throw_box(sim, &t), GL_ERR_FULL);
  gl_throw_at_settings at;
  gl_throw_at_defaults(&at);
  at.id = biped;
  at.from[2] = -8;
  EXPECT_EQ(gl_sim_throw_at(sim, &at), GL_ERR_FULL);
  gl_sim_destroy(sim);
  // Thrown boxes make way for one another at the limit.
  sim = gl_sim_create(1, 1);
  for (int i = 0; i < gaitlab::limits::kMaxBoxes - 2; ++i) ASSERT_GE(gl_sim_spawn(sim, GL_KIND_BOX, i, 3, 0), 0);
  for (int i = 0; i < 5; ++i) EXPECT_GE(gl_sim_throw_box(sim, &t), 0) << i;
  EXPECT_EQ(gl_sim_room(sim, GL_KIND_BOX), 0);
  EXPECT_EQ(gaitlab::api::simulationOf(sim).boxCount(), gaitlab::limits::kMaxBoxes);
  gl_sim_destroy(sim);
}

TEST(CApiFuzz, BenchPointsWithHugeCountsAreRefusedBeforeAllocating) {
  gl_bench_settings b;
  gl_bench_defaults(&b);
  b.steps = 2147483647;
  EXPECT_EQ(gl_bench_point(&b), nullptr);
  b.steps = 100000;
  b.runs = 1000;
  EXPECT_EQ(gl_bench_point(&b), nullptr);
  EXPECT_EQ(std::string(gl_last_error()).rfind("steps × runs", 0), 0u) << gl_last_error();
}
