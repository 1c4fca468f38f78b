// The C ABI's gait-parameter functions (c_api.h), as the web page calls them: schema, presets,
// setting a character's (or a kind's) parameters from a gait file and reading them back.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <cstring>
#include <string>

#include "api/c_api.h"
#include "api/handles.h"
#include "gait/defaults.h"
#include "gait/params_io.h"
#include "sim/simulation.h"

using nlohmann::json;
using namespace gaitlab;

namespace {

json parse(const char* text) { return json::parse(text ? text : "", nullptr, false); }

std::string bipedFileWithPeriod(double period) {
  json j = parse(gl_preset_json(GL_KIND_BIPED));
  j["params"]["period"] = period;
  return j.dump();
}

}  // namespace

TEST(ParamsCApi, SchemaAndPresetsAreJson) {
  const json schema = parse(gl_schema_json());
  ASSERT_FALSE(schema.is_discarded());
  EXPECT_EQ(schema["version"], gaitlab::gait::kSchemaVersion);
  EXPECT_GT(schema["characters"]["biped"].size(), 10u);
  EXPECT_GT(schema["characters"]["quadruped"].size(), schema["characters"]["biped"].size());
  EXPECT_EQ(parse(gl_preset_json(GL_KIND_BIPED))["character"], "biped");
  EXPECT_EQ(parse(gl_preset_json(GL_KIND_QUADRUPED))["character"], "quadruped");
  EXPECT_EQ(gl_preset_json(GL_KIND_BOX), nullptr);
}

TEST(ParamsCApi, SetsOneCharacterAndReadsItBack) {
  void* sim = gl_sim_create(1, 1);
  const int biped = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  const int box = gl_sim_spawn(sim, GL_KIND_BOX, 3, 0, 0);
  const int other = gl_sim_spawn(sim, GL_KIND_BIPED, 6, 0, 0);
  const int quadruped = gl_sim_spawn(sim, GL_KIND_QUADRUPED, -3, 0, 0);

  ASSERT_EQ(gl_sim_set_params(sim, biped, GL_KIND_BIPED, bipedFileWithPeriod(1.25).c_str()), GL_OK)
      << gl_last_error();
  EXPECT_EQ(parse(gl_sim_get_params(sim, biped))["params"]["period"], 1.25);
  EXPECT_EQ(parse(gl_sim_get_params(sim, other))["params"]["period"],
            parse(gl_preset_json(GL_KIND_BIPED))["params"]["period"]);
  EXPECT_EQ(parse(gl_sim_get_params(sim, quadruped))["character"], "quadruped");
  EXPECT_EQ(gl_sim_get_params(sim, box), nullptr);

  // What get_params returns is a gait file that loads back to the controller's exact gait: every
  // speed key, bit for bit (the parameters in effect are blended from them by the desired speed).
  sim::Simulation* s = &api::simulationOf(sim);
  gait::GaitFile file;
  ASSERT_FALSE(gait::parseGaitFile(gl_sim_get_params(sim, biped), gait::Character::Biped, &file));
  const gait::Gait& held = s->controller(0).gait();
  ASSERT_EQ(file.gait.keys.size(), held.keys.size());
  EXPECT_EQ(file.gait.primary, held.primary);
  for (size_t k = 0; k < held.keys.size(); ++k) {
    EXPECT_EQ(file.gait.keys[k].speed, held.keys[k].speed) << "key " << k;
    EXPECT_EQ(std::memcmp(&file.gait.keys[k].params, &held.keys[k].params, sizeof(gait::GaitParams)), 0) << "key " << k;
  }
  gl_sim_destroy(sim);
}

TEST(ParamsCApi, RefusesWithACodeAndAMessageAndChangesNothing) {
  void* sim = gl_sim_create(1, 1);
  const int biped = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  const int box = gl_sim_spawn(sim, GL_KIND_BOX, 3, 0, 0);
  const std::string before = gl_sim_get_params(sim, biped);

  EXPECT_EQ(gl_sim_set_params(sim, biped, GL_KIND_BIPED, bipedFileWithPeriod(99).c_str()),
            GL_ERR_INVALID_PARAMS);
  EXPECT_NE(std::string(gl_last_error()).find("period: 99.0 is outside"), std::string::npos)
      << gl_last_error();
  EXPECT_EQ(gl_sim_set_params(sim, biped, GL_KIND_BIPED, "{"), GL_ERR_INVALID_PARAMS);
  EXPECT_EQ(gl_sim_set_params(sim, biped, GL_KIND_BIPED, nullptr), GL_ERR_INVALID_PARAMS);
  EXPECT_EQ(gl_sim_set_params(sim, biped, GL_KIND_QUADRUPED, gl_preset_json(GL_KIND_QUADRUPED)),
            GL_ERR_KIND);
  EXPECT_EQ(gl_sim_set_params(sim, biped, GL_KIND_BIPED, gl_preset_json(GL_KIND_QUADRUPED)),
            GL_ERR_INVALID_PARAMS);
  EXPECT_NE(std::string(gl_last_error()).find("character"), std::string::npos);
  EXPECT_EQ(gl_sim_set_params(sim, box, GL_KIND_BIPED, gl_preset_json(GL_KIND_BIPED)), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_set_params(sim, 77, GL_KIND_BIPED, gl_preset_json(GL_KIND_BIPED)), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_set_params(sim, -1, GL_KIND_QUADRUPED, gl_preset_json(GL_KIND_QUADRUPED)),
            GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_set_params(sim, biped, GL_KIND_BOX, gl_preset_json(GL_KIND_BIPED)), GL_ERR_KIND);
  EXPECT_EQ(gl_sim_get_params(sim, biped), before);
  gl_sim_destroy(sim);
}

TEST(ParamsCApi, MinusOneSetsEveryCharacterOfTheKind) {
  void* sim = gl_sim_create(1, 1);
  gl_sim_demo_scene(sim, 6);  // three bipeds, three quadrupeds, boxes
  json q = parse(gl_preset_json(GL_KIND_QUADRUPED));
  q["params"]["period"] = 0.85;
  ASSERT_EQ(gl_sim_set_params(sim, -1, GL_KIND_QUADRUPED, q.dump().c_str()), GL_OK) << gl_last_error();
  sim::Simulation* s = &api::simulationOf(sim);
  int quadrupeds = 0;
  for (int i = 0; i < s->characterCount(); ++i) {
    const json p = parse(gl_sim_get_params(sim, s->characterId(i)));
    if (p["character"] == "quadruped") {
      ++quadrupeds;
      EXPECT_EQ(p["params"]["period"], 0.85);
    } else {
      EXPECT_NE(p["params"]["period"], 0.85);
    }
  }
  EXPECT_EQ(quadrupeds, 3);
  gl_sim_destroy(sim);
}
