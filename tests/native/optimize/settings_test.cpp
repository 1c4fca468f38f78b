// optimize/settings.h: the one reader of a search's objective settings, whether they come as the
// optimize panel's JSON object (gl_opt_create) or as `gaitlab optimize`'s options.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "optimize/settings.h"

using namespace gaitlab::optimize;
using nlohmann::json;

TEST(ObjectiveSettingsReader, JsonAndCommandLineGiveTheSameSettings) {
  ObjectiveSettings fromJson, fromOptions;
  ASSERT_EQ(readObjectiveSettings(json::parse(R"({"speeds": [0.5, 1.25], "grounds": ["flat", "slope@3.14159"],
                                                   "wr": 2, "starts": 3})"),
                                  &fromJson),
            "");
  ASSERT_EQ(readObjectiveOptions("0.5,1.25", "flat,slope@3.14159", "wr=2,starts=3", &fromOptions), "");
  EXPECT_EQ(settingsJson(fromJson), settingsJson(fromOptions));
  EXPECT_EQ(fromJson.speeds, (std::vector<double>{0.5, 1.25}));
  EXPECT_EQ(fromJson.grounds.size(), 2u);
  EXPECT_EQ(fromJson.wr, 2.0);
  EXPECT_EQ(fromJson.starts, 3);
  // Options not given keep what was there.
  ObjectiveSettings none;
  ASSERT_EQ(readObjectiveOptions(std::nullopt, std::nullopt, std::nullopt, &none), "");
  EXPECT_EQ(settingsJson(none), settingsJson(ObjectiveSettings{}));
}

TEST(ObjectiveSettingsReader, RefusesNamingTheFieldAndChangesNothing) {
  const std::string defaults = settingsJson(ObjectiveSettings{});
  const std::vector<std::pair<const char*, const char*>> refused = {
      {R"({"speeds": [1, 9]})", "speeds: 9 is outside [-5, 5] m/s"},
      {R"({"speeds": []})", "speeds: expected a non-empty array of numbers"},
      {R"({"speeds": ["fast"]})", "speeds: expected numbers"},
      {R"({"grounds": ["hill"]})", "grounds: 'hill' is not flat, slope or bumps"},
      {R"({"grounds": [3]})", "grounds: expected strings such as \"slope@3.14159\""},
      {R"({"wr": -1})", "wr: -1.0 is outside [0.0, 1000.0]"},
      {R"({"starts": 2.5})", "starts: 2.5 is not a whole number"},
      {R"({"colour": 1})", "unknown objective setting 'colour'"},
      {R"({"wd": "heavy"})", "wd: expected a number"},
      {R"([1])", "objective settings: expected a JSON object"},
  };
  for (const auto& [text, message] : refused) {
    SCOPED_TRACE(text);
    ObjectiveSettings s;
    // A valid field before the refused one is not applied either.
    json j = json::parse(text);
    if (j.is_object()) j["seconds"] = 2.0;
    EXPECT_EQ(readObjectiveSettings(j, &s), message);
    EXPECT_EQ(settingsJson(s), defaults);
  }
}

TEST(ObjectiveSettingsReader, CommandLineProblemsAreNamedByTheirOption) {
  ObjectiveSettings s;
  EXPECT_EQ(readObjectiveOptions("1,fast", std::nullopt, std::nullopt, &s), "--speeds: 'fast' is not a speed in [-5, 5] m/s");
  EXPECT_EQ(readObjectiveOptions("9", std::nullopt, std::nullopt, &s), "--speeds: 9.0 is outside [-5, 5] m/s");
  EXPECT_EQ(readObjectiveOptions(std::nullopt, "flat,hill", std::nullopt, &s), "--grounds: 'hill' is not flat, slope or bumps");
  EXPECT_EQ(readObjectiveOptions(std::nullopt, std::nullopt, "wr=-1", &s), "--objective: wr: -1.0 is outside [0.0, 1000.0]");
  EXPECT_EQ(readObjectiveOptions(std::nullopt, std::nullopt, "wd", &s), "--objective: 'wd' is not NAME=NUMBER");
  EXPECT_EQ(readObjectiveOptions("0.5", std::nullopt, "colour=1", &s), "--objective: unknown objective setting 'colour'");
  EXPECT_EQ(settingsJson(s), settingsJson(ObjectiveSettings{})) << "a refused command line changes nothing";
}

TEST(ObjectiveSettingsReader, TheTableListsEverySettingTheReaderTakes) {
  const json table = json::parse(objectiveSettingsTableJson());
  for (const json& spec : table["settings"]) {
    ObjectiveSettings s;
    EXPECT_EQ(readObjectiveSettings({{spec["name"].get<std::string>(), spec["default"]}}, &s), "") << spec.dump();
  }
}
