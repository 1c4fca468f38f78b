// The C ABI's generation-by-generation optimiser (gl_opt_*), as the browser's optimize panel
// would drive it.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "api/c_api.h"
#include "gait/params_io.h"

using nlohmann::json;

namespace {

// gl_opt_create with the search's settings given positionally, the rest at their defaults.
void* create(int kind, int method, int candidates, uint32_t seed, int threads, const char* start,
             const char* objective) {
  gl_opt_settings s;
  gl_opt_defaults(&s);
  s.kind = kind;
  s.method = method;
  s.candidates = candidates;
  s.seed = seed;
  s.threads = threads;
  return gl_opt_create(&s, start, objective);
}

}  // namespace

TEST(OptimizeCApi, StepsAGenerationAtATimeAndReturnsTheBestAsAGaitFile) {
  void* opt = create(GL_KIND_QUADRUPED, 0, 3, 7, 2, nullptr,
                            R"({"seconds": 1.0, "warmup": 0.5, "speeds": [0.5, 1.0]})");
  ASSERT_NE(opt, nullptr) << gl_last_error();
  EXPECT_EQ(gl_opt_generation(opt), 0);
  const double first = gl_opt_step(opt);
  const double second = gl_opt_step(opt);
  EXPECT_TRUE(std::isfinite(first));
  EXPECT_LE(second, first);
  EXPECT_EQ(gl_opt_generation(opt), 2);
  EXPECT_EQ(gl_opt_evaluations(opt), 6);
  const std::string text = gl_opt_best_json(opt);
  gaitlab::gait::GaitFile file;
  const auto error = gaitlab::gait::parseGaitFile(text, gaitlab::gait::Character::Quadruped, &file);
  ASSERT_FALSE(error) << error->describe();
  EXPECT_EQ(file.meta["objective"], second);
  EXPECT_EQ(file.meta["generations"], 2);
  gl_opt_destroy(opt);
}

TEST(OptimizeCApi, RefusesBadInputWithAMessage) {
  EXPECT_EQ(create(GL_KIND_BOX, 0, 3, 1, 1, nullptr, nullptr), nullptr);
  EXPECT_EQ(std::string(gl_last_error()), "kind: 2 is not a character's (GL_KIND_BIPED, GL_KIND_QUADRUPED, GL_KIND_HEXAPOD or GL_KIND_OCTOPOD)");
  EXPECT_EQ(create(GL_KIND_BIPED, 0, 3, 1, 1, "{}", nullptr), nullptr);
  EXPECT_NE(std::string(gl_last_error()).find("format"), std::string::npos);
  EXPECT_EQ(create(GL_KIND_BIPED, 0, 3, 1, 1, nullptr, R"({"wr": -2})"), nullptr);
  EXPECT_NE(std::string(gl_last_error()).find("wr: "), std::string::npos);
  EXPECT_EQ(create(GL_KIND_BIPED, 0, 3, 1, 1, nullptr, R"({"speeds": []})"), nullptr);
  EXPECT_EQ(create(GL_KIND_BIPED, 0, 3, 1, 1, nullptr, "[1]"), nullptr);
}

TEST(OptimizeCApi, RefusesSpeedsOutOfRangeAndFractionalStarts) {
  EXPECT_EQ(create(GL_KIND_BIPED, 0, 3, 1, 1, nullptr, R"({"speeds": [1.0, 9.0]})"), nullptr);
  EXPECT_NE(std::string(gl_last_error()).find("speeds: 9.0 is outside"), std::string::npos) << gl_last_error();
  EXPECT_EQ(create(GL_KIND_BIPED, 0, 3, 1, 1, nullptr, R"({"starts": 2.5})"), nullptr);
  EXPECT_NE(std::string(gl_last_error()).find("starts: 2.5 is not a whole number"), std::string::npos) << gl_last_error();
}

TEST(OptimizeCApi, TakesGroundsAndRefusesBadOnesNamingTheField) {
  void* opt = create(GL_KIND_BIPED, 0, 2, 1, 1, nullptr, R"({"grounds": ["flat", "slope@3.14159"]})");
  EXPECT_NE(opt, nullptr) << gl_last_error();
  gl_opt_destroy(opt);
  for (const char* bad : {R"({"grounds": ["hill"]})", R"({"grounds": ["slope@down"]})", R"({"grounds": []})",
                          R"({"grounds": "slope"})", R"({"grounds": [3]})"}) {
    SCOPED_TRACE(bad);
    EXPECT_EQ(create(GL_KIND_BIPED, 0, 2, 1, 1, nullptr, bad), nullptr);
    EXPECT_EQ(std::string(gl_last_error()).find("grounds: "), 0u) << gl_last_error();
  }
  EXPECT_EQ(create(GL_KIND_BIPED, 0, 2, 1, 1, nullptr, R"({"grounds": ["hill"]})"), nullptr);
  EXPECT_NE(std::string(gl_last_error()).find("'hill' is not flat, slope or bumps"), std::string::npos);
}

// The optimize panel checks its form against this table before it starts a search.
TEST(OptimizeCApi, DescribesItsSettingsWithBoundsAndDefaults) {
  const json j = json::parse(gl_opt_settings_json());
  ASSERT_TRUE(j["settings"].is_array());
  std::string names;
  for (const json& s : j["settings"]) {
    names += s["name"].get<std::string>() + " ";
    EXPECT_LE(s["min"].get<double>(), s["default"].get<double>()) << s.dump();
    EXPECT_GE(s["max"].get<double>(), s["default"].get<double>()) << s.dump();
    EXPECT_FALSE(s["description"].get<std::string>().empty());
    EXPECT_EQ(s["integer"].get<bool>(), s["name"] == "starts" || s["name"] == "startPhases" || s["name"] == "turnBothWays" || s["name"] == "turnStraight" || s["name"] == "pushAnyWay" || s["name"] == "ramp" || s["name"] == "boxHits" || s["name"] == "speedChanges");
    // Every setting it lists is one gl_opt_create accepts at its default.
    void* opt = create(GL_KIND_BIPED, 0, 2, 1, 1, nullptr, json{{s["name"], s["default"]}}.dump().c_str());
    EXPECT_NE(opt, nullptr) << gl_last_error();
    gl_opt_destroy(opt);
  }
  EXPECT_EQ(names, "wd wv wa wr wt wf wk ws wp wo fallPenalty seconds warmup starts startImpulse startPhases turnRate turnBothWays turnStraight pushImpulse pushEvery pushDuration pushAnyWay ramp stopFrom boxHits speedChanges ");
  EXPECT_EQ(j["speeds"]["min"], -5.0);
  EXPECT_EQ(j["speeds"]["max"], 5.0);
  EXPECT_EQ(j["speeds"]["default"], json::array({1.0}));
  EXPECT_EQ(j["grounds"]["default"], json::array({"flat"}));
  EXPECT_EQ(j["grounds"]["terrains"], json::array({"flat", "slope", "bumps"}));
}
