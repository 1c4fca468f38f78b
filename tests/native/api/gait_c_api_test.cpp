// The C ABI's gait calls the web page's editors and share links rest on: gl_gait_normalize (the
// only validator and migrator of gait files the page uses) and gl_sim_patch_params (an edit as a
// patch, all or nothing, refused with the parameter named).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "api/c_api.h"
#include "gait/defaults.h"
#include "gait/params_io.h"
#include "gait/schema.h"
#include "sim/simulation.h"

using nlohmann::json;

namespace {

json parse(const char* text) { return json::parse(text ? text : "", nullptr, false); }

// A simulation with two bipeds and a quadruped; destroyed with the test.
struct Scene {
  void* sim = gl_sim_create(1, 1);
  int biped0 = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  int biped1 = gl_sim_spawn(sim, GL_KIND_BIPED, 3, 0, 0);
  int quadruped = gl_sim_spawn(sim, GL_KIND_QUADRUPED, -3, 0, 0);
  ~Scene() { gl_sim_destroy(sim); }
  json params(int id) const { return parse(gl_sim_get_params(sim, id))["params"]; }
};

}  // namespace

TEST(GaitCApi, NormalizeGivesTheCurrentVersionOrTheFieldItRefuses) {
  json old = parse(gl_preset_json(GL_KIND_BIPED));
  old["version"] = 1;
  old.erase("speed");  // schema 4's speed keys
  old.erase("keys");
  old["params"].erase("gains.swingTargetRate");
  old["params"]["legFrame.supportGain"] = 900;
  const char* out = gl_gait_normalize(old.dump().c_str());
  ASSERT_NE(out, nullptr) << gl_last_error();
  const json doc = parse(out);
  EXPECT_EQ(doc["version"], gaitlab::gait::kSchemaVersion);
  EXPECT_EQ(doc["params"]["gains.swingTargetRate"], 0.0);
  EXPECT_FALSE(doc["params"].contains("legFrame.supportGain"));

  const std::pair<std::string, std::string> refusals[] = {
      {"{\"format\": ", "not valid JSON"},
      {R"({"format":"gaitlab-gait","version":15,"character":"biped","params":{}})", "version: expected 1 to 14, got 15"},
      {R"({"format":"gaitlab-gait","version":2,"character":"octopus","params":{}})", "character: expected \"biped\" or \"quadruped\" or \"hexapod\" or \"octopod\", got \"octopus\""},
      {R"({"format":"other","version":2,"character":"biped","params":{}})", "format: expected \"gaitlab-gait\", got \"other\""},
      {R"({"format":"gaitlab-gait","version":2,"character":"biped","params":[1,2]})", "params: expected an object, got an array of 2"},
      {R"({"format":"gaitlab-gait","version":2,"character":"biped","params":{}})", "period: missing"},
  };
  for (const auto& [text, message] : refusals) {
    EXPECT_EQ(gl_gait_normalize(text.c_str()), nullptr) << text;
    EXPECT_NE(std::string(gl_last_error()).find(message), std::string::npos) << text << " -> " << gl_last_error();
  }
  EXPECT_EQ(gl_gait_normalize(nullptr), nullptr);
}

TEST(GaitCApi, PatchChangesOneCharacterOrAKindAllOrNothing) {
  Scene s;
  const json before0 = s.params(s.biped0), before1 = s.params(s.biped1), beforeQ = s.params(s.quadruped);
  ASSERT_EQ(gl_sim_patch_params(s.sim, s.biped0, GL_KIND_BIPED, R"({"period": 1.25})"), GL_OK) << gl_last_error();
  json expected = before0;
  expected["period"] = 1.25;
  EXPECT_EQ(s.params(s.biped0), expected);
  EXPECT_EQ(s.params(s.biped1), before1);

  // Every biped: each keeps its own other parameters.
  ASSERT_EQ(gl_sim_patch_params(s.sim, -1, GL_KIND_BIPED, R"({"legFrame.pitch": [0.1, 0, 0, 0.1]})"), GL_OK);
  expected["legFrame.pitch"] = {0.1, 0, 0, 0.1};
  EXPECT_EQ(s.params(s.biped0), expected);
  EXPECT_EQ(s.params(s.biped1)["period"], before1["period"]);
  EXPECT_EQ(s.params(s.biped1)["legFrame.pitch"], expected["legFrame.pitch"]);
  EXPECT_EQ(s.params(s.quadruped), beforeQ);

  // A bad value anywhere refuses the whole patch, naming the parameter.
  const json now0 = s.params(s.biped0);
  EXPECT_EQ(gl_sim_patch_params(s.sim, -1, GL_KIND_BIPED, R"({"period": 1.0, "right.dutyFactor": 0.95})"), GL_ERR_INVALID_PARAMS);
  EXPECT_STREQ(gl_last_error(), "right.dutyFactor: 0.95 is outside [0.2, 0.9]");
  EXPECT_EQ(s.params(s.biped0), now0);
  EXPECT_EQ(gl_sim_patch_params(s.sim, s.biped0, GL_KIND_BIPED, R"({"frontLeft.dutyFactor": 0.5})"), GL_ERR_INVALID_PARAMS);
  EXPECT_STREQ(gl_last_error(), "frontLeft.dutyFactor: unknown parameter for a biped");
  EXPECT_EQ(gl_sim_patch_params(s.sim, s.quadruped, GL_KIND_BIPED, R"({"period": 1.0})"), GL_ERR_KIND);
  EXPECT_EQ(gl_sim_patch_params(s.sim, 99, GL_KIND_BIPED, R"({"period": 1.0})"), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_patch_params(s.sim, -1, GL_KIND_BOX, R"({"period": 1.0})"), GL_ERR_KIND);
  EXPECT_EQ(s.params(s.biped0), now0);

  // A patch of every parameter to the preset's values is the preset.
  ASSERT_EQ(gl_sim_patch_params(s.sim, s.biped0, GL_KIND_BIPED, parse(gl_preset_json(GL_KIND_BIPED))["params"].dump().c_str()), GL_OK);
  EXPECT_EQ(s.params(s.biped0), parse(gl_preset_json(GL_KIND_BIPED))["params"]);
}

// An edit by patch and the same edit as a whole gait file drive the simulation identically.
TEST(GaitCApi, PatchWalksLikeTheSameGaitSetWhole) {
  std::string hashes[2];
  for (int way = 0; way < 2; ++way) {
    Scene s;
    gl_sim_step(s.sim, 30);
    if (way == 0) {
      ASSERT_EQ(gl_sim_patch_params(s.sim, s.biped0, GL_KIND_BIPED, R"({"period": 0.9, "left.dutyFactor": 0.65})"), GL_OK);
    } else {
      json file = parse(gl_sim_get_params(s.sim, s.biped0));
      file["params"]["period"] = 0.9;
      file["params"]["left.dutyFactor"] = 0.65;
      ASSERT_EQ(gl_sim_set_params(s.sim, s.biped0, GL_KIND_BIPED, file.dump().c_str()), GL_OK);
    }
    gl_sim_step(s.sim, 120);
    hashes[way] = gl_sim_state_hash(s.sim);
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}
