// The C ABI's contract (the comment at the top of c_api.h): every refusal returns its type's
// failure value (a negative GL_ERR_* code, NULL, NaN) and leaves a message in gl_last_error that
// names what was refused; strings live as long as the header says (a simulation's string
// survives calls on another simulation); settings structs start from their defaults.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "api/c_api.h"
#include "optimize/optimizer.h"
#include "sim/experiment.h"

namespace {

// A refusal, and the text its message must start with: the argument it names.
struct Refusal {
  const char* call;
  std::function<bool()> refused;  // true if the call returned its failure value
  std::string names;
};

// Puts a message in gl_last_error that no refusal below produces, so that each test sees a
// message its own call set.
const char* const kMarker = "legs: -12345 is not 0 (mixed), 2 or 4";
void clearError() {
  ASSERT_EQ(gl_bench_max_characters(-12345), GL_ERR_ARGUMENT);
  ASSERT_EQ(std::string(gl_last_error()), kMarker);
}

}  // namespace

TEST(CApiContract, EveryRefusalReturnsItsFailureValueAndNamesTheArgument) {
  void* sim = gl_sim_create(1, 1);
  const int biped = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  const int box = gl_sim_spawn(sim, GL_KIND_BOX, 3, 0, 0);
  ASSERT_GE(biped, 0);
  ASSERT_GE(box, 0);
  const double nan = std::nan("");
  gl_throw_settings badHalf;
  gl_throw_defaults(&badHalf);
  badHalf.half = 2;
  gl_throw_settings badFrom;
  gl_throw_defaults(&badFrom);
  badFrom.from[1] = nan;
  const auto throwAt = [&](auto change) {
    gl_throw_at_settings t;
    gl_throw_at_defaults(&t);
    t.id = biped;
    t.from[2] = -8;
    change(t);
    return gl_sim_throw_at(sim, &t);
  };
  gl_drag_settings noId;
  gl_drag_defaults(&noId);
  gl_drag_settings badSegment;
  gl_drag_defaults(&badSegment);
  badSegment.id = biped;
  badSegment.segment = 999;
  gl_opt_settings badKind, badMethod, badCandidates;
  gl_opt_defaults(&badKind);
  badKind.kind = GL_KIND_BOX;
  gl_opt_defaults(&badMethod);
  badMethod.method = 7;
  gl_opt_defaults(&badCandidates);
  badCandidates.candidates = 1;
  const auto bench = [](auto change) {
    gl_bench_settings b;
    gl_bench_defaults(&b);
    b.steps = 1;
    b.runs = 1;
    change(b);
    return gl_bench_point(&b) == nullptr;
  };

  const std::vector<Refusal> refusals = {
      {"gl_sim_spawn kind", [&] { return gl_sim_spawn(sim, 9, 0, 0, 0) == GL_ERR_ARGUMENT; }, "kind: 9 "},
      {"gl_sim_spawn position", [&] { return gl_sim_spawn(sim, GL_KIND_BOX, nan, 0, 0) == GL_ERR_ARGUMENT; },
       "x: NaN is not finite"},
      {"gl_sim_spawn_creature file",
       [&] { return gl_sim_spawn_creature(sim, "{\"format\": \"gaitlab-creature\"}", 0, 0, 0) == GL_ERR_ARGUMENT; },
       "creature: version: missing"},
      {"gl_sim_spawn_creature null", [&] { return gl_sim_spawn_creature(sim, nullptr, 0, 0, 0) == GL_ERR_ARGUMENT; },
       "creature: not valid JSON"},
      {"gl_sim_spawn_creature position",
       [&] { return gl_sim_spawn_creature(sim, nullptr, 0, nan, 0) == GL_ERR_ARGUMENT; }, "z: NaN is not finite"},
      {"gl_cruise_speed", [&] { return std::isnan(gl_cruise_speed(GL_KIND_BOX)); }, "kind: 2 "},
      {"gl_sim_demo_scene", [&] { return gl_sim_demo_scene(sim, -1) == GL_ERR_ARGUMENT; }, "characters: -1 "},
      {"gl_sim_step", [&] { return gl_sim_step(sim, -3) == GL_ERR_ARGUMENT; }, "steps: -3 "},
      {"gl_preset_json", [&] { return gl_preset_json(GL_KIND_BOX) == nullptr; }, "kind: 2 "},
      {"gl_sim_set_params kind", [&] { return gl_sim_set_params(sim, biped, 7, "{}") == GL_ERR_KIND; }, "kind: 7 "},
      {"gl_sim_set_params id", [&] { return gl_sim_set_params(sim, 77, GL_KIND_BIPED, "{}") == GL_ERR_NO_CHARACTER; },
       "id: no character has id 77"},
      {"gl_sim_set_params file",
       [&] { return gl_sim_set_params(sim, biped, GL_KIND_BIPED, "{") == GL_ERR_INVALID_PARAMS; }, ""},
      {"gl_sim_get_params", [&] { return gl_sim_get_params(sim, box) == nullptr; },
       "id: no character has id " + std::to_string(box)},
      {"gl_sim_set_goal id", [&] { return gl_sim_set_goal(sim, 77, 1, 0) == GL_ERR_NO_CHARACTER; }, "id: no character has id 77"},
      {"gl_sim_set_goal speed", [&] { return gl_sim_set_goal(sim, biped, nan, 0) == GL_ERR_ARGUMENT; }, "goal speed: NaN is not finite"},
      {"gl_sim_throw_box half", [&] { return gl_sim_throw_box(sim, &badHalf) == GL_ERR_ARGUMENT; }, "half: 2"},
      {"gl_sim_throw_box from", [&] { return gl_sim_throw_box(sim, &badFrom) == GL_ERR_ARGUMENT; }, "from: (0.0, NaN, 0.0) is not finite"},
      {"gl_sim_throw_at id", [&] { return throwAt([](gl_throw_at_settings& t) { t.id = 77; }) == GL_ERR_NO_CHARACTER; },
       "id: no character has id 77"},
      {"gl_sim_throw_at prop", [&] { return throwAt([&](gl_throw_at_settings& t) { t.id = box; }) == GL_ERR_NO_CHARACTER; },
       "id: no character has id " + std::to_string(box)},
      {"gl_sim_throw_at segment", [&] { return throwAt([](gl_throw_at_settings& t) { t.segment = 99; }) == GL_ERR_ARGUMENT; },
       "segment: "},
      {"gl_sim_throw_at from", [&] { return throwAt([&](gl_throw_at_settings& t) { t.from[0] = nan; }) == GL_ERR_ARGUMENT; },
       "from: (NaN, 1.0, -8.0) is not finite"},
      {"gl_sim_throw_at local", [&] { return throwAt([](gl_throw_at_settings& t) { t.local[1] = 11; }) == GL_ERR_ARGUMENT; },
       "local: "},
      {"gl_sim_throw_at speed", [&] { return throwAt([&](gl_throw_at_settings& t) { t.speed = nan; }) == GL_ERR_ARGUMENT; },
       "speed: NaN is not finite"},
      {"gl_sim_throw_at slow", [&] { return throwAt([](gl_throw_at_settings& t) { t.speed = 0.5; }) == GL_ERR_ARGUMENT; },
       "speed: 0.5 is outside [1.0, 100.0]"},
      {"gl_sim_throw_at lob", [&] {
         return throwAt([](gl_throw_at_settings& t) { t.from[2] = -900; t.speed = 2; }) == GL_ERR_ARGUMENT;
       }, "speed: the throw at character "},
      {"gl_sim_throw_at half", [&] { return throwAt([](gl_throw_at_settings& t) { t.half = 0.01; }) == GL_ERR_ARGUMENT; },
       "half: 0.01 is outside [0.03, 0.5] m"},
      {"gl_sim_drag id", [&] { return gl_sim_drag(sim, &noId) == GL_ERR_NO_CHARACTER; }, "id: no character has id -1"},
      {"gl_sim_drag segment", [&] { return gl_sim_drag(sim, &badSegment) == GL_ERR_ARGUMENT; }, "segment: "},
      {"gl_sim_reset_character", [&] { return gl_sim_reset_character(sim, 77) == GL_ERR_NO_CHARACTER; }, "id: no character has id 77"},
      {"gl_sim_remove_character", [&] { return gl_sim_remove_character(sim, 77) == GL_ERR_NO_CHARACTER; }, "id: no character has id 77"},
      {"gl_sim_set_auto_reset", [&] { return gl_sim_set_auto_reset(sim, -1) == GL_ERR_ARGUMENT; }, "seconds: -1"},
      {"gl_sim_character_info", [&] { return gl_sim_character_info(sim, nullptr, -1) == GL_ERR_ARGUMENT; }, "capacity: -1 "},
      {"gl_sim_set_terrain", [&] { return gl_sim_set_terrain(sim, 3) == GL_ERR_ARGUMENT; }, "kind: 3 "},
      {"gl_sim_ground_height", [&] { return std::isnan(gl_sim_ground_height(sim, nan, 0)); }, "point: "},
      {"gl_opt_create kind", [&] { return gl_opt_create(&badKind, nullptr, nullptr) == nullptr; }, "kind: 2 "},
      {"gl_opt_create method", [&] { return gl_opt_create(&badMethod, nullptr, nullptr) == nullptr; }, "method: 7 "},
      {"gl_opt_create candidates", [&] { return gl_opt_create(&badCandidates, nullptr, nullptr) == nullptr; },
       "candidates: 1 is outside [2, 1000]"},
      {"gl_opt_create start", [&] {
         gl_opt_settings s;
         gl_opt_defaults(&s);
         return gl_opt_create(&s, "{}", nullptr) == nullptr;
       }, "start: "},
      {"gl_opt_create objective", [&] {
         gl_opt_settings s;
         gl_opt_defaults(&s);
         return gl_opt_create(&s, nullptr, R"({"wd": "heavy"})") == nullptr;
       }, "wd: expected a number"},
      {"gl_bench_max_characters", [&] { return gl_bench_max_characters(3) == GL_ERR_ARGUMENT; }, "legs: 3 "},
      {"gl_bench_warm_up", [&] { return gl_bench_warm_up(3, 1) == GL_ERR_ARGUMENT; }, "legs: 3 "},
      {"gl_bench_point legs", [&] { return bench([](gl_bench_settings& b) { b.legs = 3; }); }, "legs: 3 "},
      {"gl_bench_point characters",
       [&] { return bench([](gl_bench_settings& b) { b.characters = gl_bench_max_characters(b.legs) + 1; }); },
       "characters: "},
      {"gl_bench_point mode", [&] { return bench([](gl_bench_settings& b) { b.mode = 3; }); }, "mode: 3 "},
      {"gl_bench_point steps", [&] { return bench([](gl_bench_settings& b) { b.steps = 0; }); }, "steps: 0 "},
      {"gl_bench_point runs", [&] { return bench([](gl_bench_settings& b) { b.runs = 0; }); }, "runs: 0 "},
      {"gl_bench_point shards", [&] { return bench([](gl_bench_settings& b) { b.shards = 65; }); }, "shards: 65 "},
      {"gl_bench_point spacing", [&] { return bench([](gl_bench_settings& b) { b.spacing = 1; }); }, "spacing: 1"},
  };
  for (const Refusal& r : refusals) {
    SCOPED_TRACE(r.call);
    clearError();
    EXPECT_TRUE(r.refused()) << gl_last_error();
    const std::string message = gl_last_error();
    EXPECT_NE(message, kMarker) << "the refusal set no message";
    EXPECT_FALSE(message.empty());
    EXPECT_EQ(message.rfind(r.names, 0), 0u) << message;
  }
  // Nothing refused changed the scene.
  EXPECT_EQ(gl_sim_character_count(sim), 1);
  EXPECT_EQ(gl_sim_step_index(sim), 0u);
  gl_sim_destroy(sim);
}

TEST(CApiContract, ASuccessLeavesTheLastMessageAsItWas) {
  clearError();
  void* sim = gl_sim_create(1, 1);
  EXPECT_GE(gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0), 0);
  EXPECT_EQ(gl_sim_step(sim, 1), GL_OK);
  EXPECT_EQ(std::string(gl_last_error()), kMarker);
  gl_sim_destroy(sim);
}

TEST(CApiContract, ASimulationsStringSurvivesCallsOnAnotherSimulation) {
  void* a = gl_sim_create(1, 1);
  void* b = gl_sim_create(1, 2);
  const int ida = gl_sim_spawn(a, GL_KIND_BIPED, 0, 0, 0);
  const int idb = gl_sim_spawn(b, GL_KIND_QUADRUPED, 0, 0, 0);
  gl_sim_step(b, 30);
  const char* hashA = gl_sim_state_hash(a);
  const std::string copyA = hashA;
  const char* paramsA = nullptr;
  // b's strings, of both kinds, and a's gait file after a's hash: a's hash is then gone (the
  // same simulation), b's calls never touch a's string.
  const std::string hashB = gl_sim_state_hash(b);
  EXPECT_NE(hashB, copyA);
  EXPECT_NE(gl_sim_get_params(b, idb), nullptr);
  EXPECT_EQ(std::string(hashA), copyA) << "a call on simulation b overwrote simulation a's string";
  paramsA = gl_sim_get_params(a, ida);
  const std::string copyParamsA = paramsA;
  EXPECT_NE(copyParamsA.find("\"biped\""), std::string::npos);
  gl_sim_state_hash(b);
  gl_sim_get_params(b, idb);
  gl_sim_destroy(b);
  EXPECT_EQ(std::string(paramsA), copyParamsA);
  gl_sim_destroy(a);
}

TEST(CApiContract, AnOptimisersStringSurvivesCallsOnSimulationsAndOtherOptimisers) {
  gl_opt_settings s;
  gl_opt_defaults(&s);
  s.candidates = 2;
  void* first = gl_opt_create(&s, nullptr, nullptr);
  s.kind = GL_KIND_QUADRUPED;
  void* second = gl_opt_create(&s, nullptr, nullptr);
  ASSERT_NE(first, nullptr);
  ASSERT_NE(second, nullptr);
  const char* best = gl_opt_best_json(first);
  const std::string copy = best;
  gl_opt_best_json(second);
  void* sim = gl_sim_create(1, 1);
  gl_sim_state_hash(sim);
  gl_sim_destroy(sim);
  EXPECT_EQ(std::string(best), copy);
  gl_opt_destroy(second);
  gl_opt_destroy(first);
}

TEST(CApiContract, StringsThatNeverChangeAreStatic) {
  EXPECT_EQ(gl_version(), gl_version());
  EXPECT_EQ(gl_schema_json(), gl_schema_json());
  EXPECT_EQ(gl_preset_json(GL_KIND_BIPED), gl_preset_json(GL_KIND_BIPED));
  EXPECT_EQ(gl_opt_settings_json(), gl_opt_settings_json());
  EXPECT_EQ(gl_bench_machine(), gl_bench_machine());
}

TEST(CApiContract, SettingsDefaultsAreTheLibrarysOwn) {
  gl_opt_settings o;
  gl_opt_defaults(&o);
  const gaitlab::optimize::SearchOptions search;
  EXPECT_EQ(o.kind, GL_KIND_BIPED);
  EXPECT_EQ(o.method, GL_METHOD_GREEDY);
  EXPECT_EQ(o.candidates, search.candidates);
  EXPECT_EQ(o.threads, search.threads);
  EXPECT_EQ(o.seed, search.seed);
  gl_bench_settings b;
  gl_bench_defaults(&b);
  const gaitlab::sim::PointSpec point;
  EXPECT_EQ(b.legs, point.legs);
  EXPECT_EQ(b.characters, point.characters);
  EXPECT_EQ(b.mode, GL_MODE_SERIAL);
  EXPECT_EQ(b.steps, point.steps);
  EXPECT_EQ(b.runs, point.runs);
  EXPECT_EQ(b.shards, point.shards);
  EXPECT_EQ(b.spacing, point.spacing);
  EXPECT_EQ(b.seed, point.seed);
  EXPECT_EQ(b.frames, 0);
  gl_drag_settings d;
  gl_drag_defaults(&d);
  EXPECT_EQ(d.id, -1);
  gl_throw_settings t;
  gl_throw_defaults(&t);
  EXPECT_GE(t.half, 0.03);
  EXPECT_LE(t.half, 0.5);
  EXPECT_EQ(gl_max_threads(), GL_MAX_THREADS);
}

TEST(CApiContract, ABenchPointFromTheDefaultsRunsAndClampsItsThreads) {
  gl_bench_settings b;
  gl_bench_defaults(&b);
  b.steps = 4;
  b.runs = 1;
  b.threads = 64;
  b.mode = GL_MODE_FULL;
  const char* point = gl_bench_point(&b);
  ASSERT_NE(point, nullptr) << gl_last_error();
  EXPECT_NE(std::string(point).find("\"threads\":" + std::to_string(GL_MAX_THREADS)), std::string::npos) << point;
}
