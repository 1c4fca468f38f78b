// Gait files (gait/params_io.h): the presets load, writing then reading gives back the same
// bits, and every kind of bad file is refused with the field named and the target untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "gait/defaults.h"
#include "gait/params_io.h"

using namespace gaitlab::gait;
using nlohmann::json;

namespace {

bool sameBits(const GaitParams& a, const GaitParams& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

std::string readSourceFile(const std::string& relative) {
  std::ifstream in(std::string(GAITLAB_SOURCE_DIR) + "/" + relative, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(GaitFile, ShippedPresetsLoadAndAreWhatTheBinaryEmbeds) {
  for (Character c : {Character::Biped, Character::Quadruped}) {
    const std::string path = std::string("public/presets/") + characterName(c) + ".json";
    const std::string text = readSourceFile(path);
    ASSERT_FALSE(text.empty()) << path;
    EXPECT_EQ(text, presetText(c)) << path << " changed since the build embedded it";
    GaitFile file;
    const auto error = parseGaitFile(text, c, &file);
    ASSERT_FALSE(error) << path << ": " << error->describe();
    EXPECT_EQ(file.character, c);
    EXPECT_TRUE(sameBits(file.gait.primaryParams(), defaultParams(c)));
  }
}

TEST(GaitFile, RoundTripsBitExactly) {
  // Random values within the bounds, plus awkward ones: non-terminating binary fractions,
  // the smallest subnormal, negative zero.
  std::mt19937_64 rng(42);
  for (Character c : {Character::Biped, Character::Quadruped}) {
    for (int trial = 0; trial < 20; ++trial) {
      GaitParams p = defaultParams(c);
      int i = 0;
      forEachParam(c, p, [&](const ParamField& f) {
        for (int k = 0; k < f.spec.knots; ++k, ++i) {
          const double u = static_cast<double>(rng() >> 11) * 0x1.0p-53;
          double v = f.spec.min + u * (f.spec.max - f.spec.min);
          if (i % 7 == 3 && f.spec.min <= 0 && f.spec.max >= 0) v = trial % 2 ? -0.0 : 4.9e-324;
          if (i % 11 == 5) v = f.spec.min + (f.spec.max - f.spec.min) / 3.0;
          f.values[k] = v;
        }
      });
      GaitFile back;
      const auto error = parseGaitFile(gaitFileJson(c, p, {{"seed", trial}}), c, &back);
      ASSERT_FALSE(error) << error->describe();
      EXPECT_TRUE(sameBits(back.gait.primaryParams(), p)) << characterName(c) << " trial " << trial;
      EXPECT_EQ(back.meta["seed"], trial);
      // Compact output reads back the same.
      GaitFile compact;
      ASSERT_FALSE(parseGaitFile(gaitFileJson(c, p, {}, -1), c, &compact));
      EXPECT_TRUE(sameBits(compact.gait.primaryParams(), p));
    }
  }
}

TEST(GaitFile, WithoutAnExpectedCharacterTheFileSaysWhichItIs) {
  GaitFile file;
  ASSERT_FALSE(parseGaitFile(presetText(Character::Quadruped), std::nullopt, &file));
  EXPECT_EQ(file.character, Character::Quadruped);
}

TEST(GaitFile, UnreadableFileIsAnError) {
  GaitFile file;
  const auto error = loadGaitFile("/nonexistent/gait.json", std::nullopt, &file);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->message, "cannot be read");
}

// Each bad file: how to break the biped preset, the field the error must name, and a piece of
// the message.
struct BadFile {
  const char* what;
  std::function<std::string(json)> make;
  std::string field;
  std::string message;
};

TEST(GaitFile, AVersion1FileIsMigrated) {
  // Schema 2 dropped the support gain and added gains.swingTargetRate, whose 0 is version 1's
  // behaviour: a version-1 file loads with everything else unchanged.
  json v2 = json::parse(presetText(Character::Quadruped));
  v2["version"] = 2;
  v2.erase("speed");  // schema 4's speed keys
  v2.erase("keys");
  json v1 = v2;
  v1["version"] = 1;
  v1["params"].erase("gains.swingTargetRate");
  v1["params"]["front.supportGain"] = 1500.0;
  v1["params"]["back.supportGain"] = 900.0;
  GaitFile migrated, current;
  ASSERT_FALSE(parseGaitFile(v1.dump(), Character::Quadruped, &migrated));
  v2["params"]["gains.swingTargetRate"] = 0.0;
  ASSERT_FALSE(parseGaitFile(v2.dump(), Character::Quadruped, &current));
  EXPECT_TRUE(sameBits(migrated.gait.primaryParams(), current.gait.primaryParams()));
  EXPECT_EQ(migrated.gait.primaryParams().gains.swingTargetRate, 0.0);
  // The migration is for version 1 only: the support gain is unknown in a version-2 file.
  v2["params"]["front.supportGain"] = 1500.0;
  const auto error = parseGaitFile(v2.dump(), Character::Quadruped, &current);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->field, "front.supportGain");
}

TEST(GaitFile, AVersion2FileIsMigrated) {
  // Schema 3 added the low-speed capture-point placement per leg frame and speed tracking; weight
  // and gain 0 walk as version 2 did, so a version-2 file loads as itself with both off.
  json v3 = json::parse(presetText(Character::Biped));
  v3["version"] = 3;
  v3.erase("speed");  // schema 4's speed keys
  v3.erase("keys");
  json v2 = v3;
  v2["version"] = 2;
  for (const char* key : {"legFrame.capturePlacement", "legFrame.captureBlendSpeed", "legFrame.captureSideways",
                          "speedIntegralGain"})
    v2["params"].erase(key);
  GaitFile migrated, current;
  ASSERT_FALSE(parseGaitFile(v2.dump(), Character::Biped, &migrated));
  v3["params"]["legFrame.capturePlacement"] = 0.0;
  v3["params"]["legFrame.captureBlendSpeed"] = 0.5;
  v3["params"]["legFrame.captureSideways"] = 0.05;
  v3["params"]["speedIntegralGain"] = 0.0;
  ASSERT_FALSE(parseGaitFile(v3.dump(), Character::Biped, &current));
  EXPECT_TRUE(sameBits(migrated.gait.primaryParams(), current.gait.primaryParams()));
  EXPECT_EQ(migrated.gait.primaryParams().legFrames[0].capturePlacement, 0.0);
  EXPECT_EQ(migrated.gait.primaryParams().speedIntegralGain, 0.0);
}

namespace {

// Every field a schema from 6 on added to each key, with the value its migration gives files
// older than it: the value that walks as those files did, and the characters whose schema has it.
// (turnRollMoment, added by 12, is in the quadruped's schema only from 13: biped files of 12 had
// it, with no effect.)
enum class Of { Both, Biped, Quadruped };
struct AddedField {
  int schema;
  const char* name;
  double value;
  Of of = Of::Both;
};
constexpr AddedField kAddedFields[] = {
    {6, "standSpeed", 0.0},
    {7, "maxSpeedTrim", 0.5},
    {8, "speedTrackedFrom", 0.15},
    {9, "transitionPhase", 0.0},
    {10, "maxTurnSlip", 5.0},
    {11, "turnPlacement", 0.0},
    {12, "turnRollMoment", 0.0, Of::Quadruped},
    {14, "hipForwardStop", 0.7, Of::Biped},
};

// The preset of `c` as a file of schema `version` would have it: the fields later schemas added
// (kAddedFields) taken out of the parameters and of every key. It must load as the preset with
// those fields at their migrated values, key by key and bit for bit: a migration adds what was
// added and moves nothing else.
void expectMigrated(Character c, int version) {
  json current = json::parse(presetText(c));
  ASSERT_TRUE(current.contains("keys"));
  json old = current;
  old["version"] = version;
  for (const auto& [schema, name, value, of] : kAddedFields) {
    const bool has = of == Of::Both || (of == Of::Biped) == (c == Character::Biped);
    if (schema <= version || !has) continue;
    old["params"].erase(name);
    current["params"][name] = value;
    for (json& key : old["keys"]) key["params"].erase(name);
    for (json& key : current["keys"]) key["params"][name] = value;
  }
  GaitFile migrated, expected;
  ASSERT_FALSE(parseGaitFile(old.dump(), c, &migrated));
  ASSERT_FALSE(parseGaitFile(current.dump(), c, &expected));
  ASSERT_EQ(migrated.gait.keys.size(), expected.gait.keys.size());
  for (size_t k = 0; k < migrated.gait.keys.size(); ++k)
    EXPECT_TRUE(sameBits(migrated.gait.keys[k].params, expected.gait.keys[k].params)) << "key " << k;
}

}  // namespace

TEST(GaitFile, AVersion5FileIsMigratedToSteppingInPlace) {
  // Schema 6 added standing on planted feet (standSpeed); 0 steps in place at goal 0 as every
  // gait of version 5 did, so a version-5 file loads as itself, keys and all, with it off (and
  // with the later schemas' fields at their old constants, as below).
  for (Character c : {Character::Biped, Character::Quadruped})
    expectMigrated(c, 5);
}

TEST(GaitFile, AVersion6FileIsMigratedToTheOldTrimBound) {
  // Schema 7 made speed tracking's trim bound a parameter of each key (maxSpeedTrim); every gait
  // before it had 0.5 m/s, so a version-6 file loads with 0.5 in every key and nothing else moved.
  for (Character c : {Character::Biped, Character::Quadruped})
    expectMigrated(c, 6);
}

TEST(GaitFile, AVersion7FileIsMigratedToTrackingFromTheOldSpeed) {
  // Schema 8 made the desired speed from which speed tracking acts a parameter of each key
  // (speedTrackedFrom); every gait before it had 0.15 m/s, so a version-7 file loads with 0.15 in
  // every key and nothing else moved.
  for (Character c : {Character::Biped, Character::Quadruped}) expectMigrated(c, 7);
}

TEST(GaitFile, AVersion8FileIsMigratedToChangingGaitAtTheCycleStart) {
  // Schema 9 made where in its cycle a key's gait is left for another footfall pattern a
  // parameter of each key (transitionPhase); every change before it was taken where the cycle
  // starts, so a version-8 file loads with 0 in every key and nothing else moved.
  for (Character c : {Character::Biped, Character::Quadruped}) expectMigrated(c, 8);
}

TEST(GaitFile, AVersion9FileIsMigratedToTurningUnbounded) {
  // Schema 10 bounded how far a turn's heading may lead the body's path, per key (maxTurnSlip);
  // before it nothing bounded it, which 5 m/s (kNoTurnSlipBound) reproduces, so a version-9 file
  // loads with 5 in every key and nothing else moved.
  for (Character c : {Character::Biped, Character::Quadruped}) expectMigrated(c, 9);
}

TEST(GaitFile, AVersion10FileIsMigratedToFeetPlacedAsIfGoingStraight) {
  // Schema 11 moved the strike points outwards from a turn, per key (turnPlacement); before it
  // they were placed as if going straight, which 0 reproduces, so a version-10 file loads with 0
  // in every key and nothing else moved.
  for (Character c : {Character::Biped, Character::Quadruped}) expectMigrated(c, 10);
}

TEST(GaitFile, AVersion11FileIsMigratedToATurnsRollMomentCancelled) {
  // Schema 12 left the roll moment of a turn's sideways force to the whole-body stance, per key
  // (turnRollMoment); before it the stance cancelled it, which 0 reproduces, so a version-11 file
  // loads with 0 in every key and nothing else moved.
  for (Character c : {Character::Biped, Character::Quadruped}) expectMigrated(c, 11);
}

TEST(GaitFile, AVersion12BipedFileIsReadWithoutTheRollMomentItNeverUsed) {
  // Schema 13 keeps turnRollMoment to the bodies of several leg frames, whose whole-body stance
  // it acts in. A biped file of 12 has it in every key, at whatever value an editor left it: it
  // loads as the preset, bit for bit, and a file of 13 that still names it is refused.
  json current = json::parse(presetText(Character::Biped));
  ASSERT_FALSE(current["params"].contains("turnRollMoment"));
  json old = current;
  old["version"] = 12;
  old["params"]["turnRollMoment"] = 1.5;
  for (json& key : old["keys"]) key["params"]["turnRollMoment"] = 0.0;
  GaitFile migrated, expected;
  ASSERT_FALSE(parseGaitFile(old.dump(), Character::Biped, &migrated));
  ASSERT_FALSE(parseGaitFile(current.dump(), Character::Biped, &expected));
  ASSERT_EQ(migrated.gait.keys.size(), expected.gait.keys.size());
  for (size_t k = 0; k < migrated.gait.keys.size(); ++k)
    EXPECT_TRUE(sameBits(migrated.gait.keys[k].params, expected.gait.keys[k].params)) << "key " << k;
  old["version"] = 13;
  const auto error = parseGaitFile(old.dump(), Character::Biped, &migrated);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->describe(), "turnRollMoment: unknown parameter for a biped");
}

TEST(GaitFile, AVersion13BipedFileKeepsTheHipStopItsGaitsWereSearchedOn) {
  // Schema 14 gave the biped's body a hip that flexes 2 rad and its gaits the 0.7 rad stop they
  // were all searched on, as the walking controller's (hipForwardStop): a biped file of 13 loads
  // with 0.7 in every key and nothing else moved; a quadruped's file of 13 loads as it was.
  for (Character c : {Character::Biped, Character::Quadruped}) expectMigrated(c, 13);
}

TEST(GaitFile, AVersion3FileIsMigrated) {
  // Schema 4 added speed keys beside the parameters: a version-3 file is one key, tuned at 0 m/s,
  // its parameters as they were; keys are refused in it.
  json v4 = json::parse(presetText(Character::Biped));
  ASSERT_TRUE(v4.contains("keys"));
  json v3 = v4;
  v3["version"] = 3;
  v3.erase("speed");
  v3.erase("keys");
  GaitFile migrated, current;
  ASSERT_FALSE(parseGaitFile(v3.dump(), Character::Biped, &migrated));
  ASSERT_FALSE(parseGaitFile(v4.dump(), Character::Biped, &current));
  EXPECT_TRUE(sameBits(migrated.gait.primaryParams(), current.gait.primaryParams()));
  ASSERT_EQ(migrated.gait.keys.size(), 1u);
  EXPECT_EQ(migrated.gait.keys[0].speed, 0.0);
  v3["keys"] = v4["keys"];
  const auto error = parseGaitFile(v3.dump(), Character::Biped, &migrated);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->field, "keys");
}

TEST(GaitFile, RefusesBadFilesNamingTheFieldAndLeavesTheTargetUntouched) {
  const json preset = json::parse(presetText(Character::Biped), nullptr, false);
  ASSERT_FALSE(preset.is_discarded());
  const auto with = [](std::function<void(json&)> change) {
    return [change](json j) {
      change(j);
      return j.dump();
    };
  };
  const std::vector<BadFile> cases = {
      {"truncated JSON", [](json j) { const std::string s = j.dump(); return s.substr(0, s.size() / 2); },
       "", "not valid JSON"},
      {"not an object", [](json) { return std::string("[1, 2]"); }, "", "expected a JSON object"},
      {"unknown top-level field", with([](json& j) { j["colour"] = "red"; }), "colour", "unknown field"},
      {"wrong format", with([](json& j) { j["format"] = "gaitlab-scene"; }), "format", "expected \"gaitlab-gait\""},
      {"missing format", with([](json& j) { j.erase("format"); }), "format", "missing"},
      {"newer version", with([](json& j) { j["version"] = kGaitFormatVersion + 1; }), "version", "expected 1 to"},
      {"version 0", with([](json& j) { j["version"] = 0; }), "version", "expected 1 to"},
      {"version as a string", with([](json& j) { j["version"] = "1"; }), "version", "expected 1"},
      {"unknown character", with([](json& j) { j["character"] = "horse"; }), "character", "\"horse\""},
      {"other character", with([](json& j) { j["character"] = "quadruped"; }), "character",
       "for a quadruped, not a biped"},
      {"params missing", with([](json& j) { j.erase("params"); }), "params", "missing"},
      {"params not an object", with([](json& j) { j["params"] = json::array(); }), "params", "expected an object"},
      {"meta not an object", with([](json& j) { j["meta"] = "hello"; }), "meta", "expected an object"},
      {"missing parameter", with([](json& j) { j["params"].erase("legFrame.pitch"); }), "legFrame.pitch", "missing"},
      {"unknown parameter", with([](json& j) { j["params"]["legFrame.wobble"] = 1; }), "legFrame.wobble",
       "unknown parameter"},
      {"quadruped parameter in a biped file", with([](json& j) { j["params"]["gains.spineKp"] = 1; }),
       "gains.spineKp", "unknown parameter"},
      {"number as a string", with([](json& j) { j["params"]["period"] = "1.0"; }), "period",
       "expected a number, got a string"},
      {"null", with([](json& j) { j["params"]["period"] = nullptr; }), "period", "expected a number, got null"},
      {"scalar given knots", with([](json& j) { j["params"]["period"] = {1, 1, 1, 1}; }), "period",
       "expected a number, got an array of 4"},
      {"graph given a scalar", with([](json& j) { j["params"]["legFrame.pitch"] = 0.1; }), "legFrame.pitch",
       "expected an array of 4 numbers"},
      {"three knots", with([](json& j) { j["params"]["legFrame.pitch"] = {0, 0, 0}; }), "legFrame.pitch",
       "got an array of 3"},
      {"knot not a number", with([](json& j) { j["params"]["legFrame.stepHeight"][1] = true; }),
       "legFrame.stepHeight[1]", "expected a number, got a boolean"},
      {"knot out of bounds", with([](json& j) { j["params"]["legFrame.stepHeight"][2] = 5.0; }),
       "legFrame.stepHeight[2]", "5.0 is outside [0.0, 0.25]"},
      {"scalar below its bound", with([](json& j) { j["params"]["period"] = 0.01; }), "period",
       "0.01 is outside [0.3, 3.0]"},
      {"the last field out of bounds", with([](json& j) { j["params"]["right.strikeTime"] = -1; }),
       "right.strikeTime", "outside"},
      // JSON has no NaN or infinity; a number too large for a double is refused by the parser
      // itself, whose message quotes it.
      {"overflowing number", [](json j) {
         j["params"]["period"] = 1.0;  // a known spelling to replace, whatever the preset's value
         std::string s = j.dump();
         const std::string key = "\"period\":1.0";
         s.replace(s.find(key), key.size(), "\"period\":1e999");
         return s;
       },
       "", "number overflow parsing '1e999'"},
  };
  for (const BadFile& bad : cases) {
    SCOPED_TRACE(bad.what);
    // The target holds values of its own that a half-load would overwrite.
    GaitFile target;
    target.gait = Gait::single(defaultParams(Character::Biped));
    GaitParams& params = target.gait.primaryParams();
    params.period = 2.5;
    params.legFrames[0].pitch = MotionGraph::of(0.1, 0.2, 0.3, 0.4);
    params.legs[1].strikeTime = 0.25;
    const GaitFile before = target;
    const auto error = parseGaitFile(bad.make(preset), Character::Biped, &target);
    ASSERT_TRUE(error) << "accepted";
    EXPECT_EQ(error->field, bad.field) << error->describe();
    EXPECT_NE(error->message.find(bad.message), std::string::npos) << error->describe();
    ASSERT_EQ(target.gait.keys.size(), 1u) << "half-loaded";
    EXPECT_TRUE(sameBits(target.gait.primaryParams(), before.gait.primaryParams())) << "half-loaded";
    EXPECT_EQ(target.character, before.character);
  }
}

// normalizeGaitFile: any version in, the current version out, canonical and complete; a refusal
// is parseGaitFile's, field named.
TEST(GaitFile, NormalizeMigratesAndWritesTheCanonicalForm) {
  json old = json::parse(presetText(Character::Quadruped));
  old["version"] = 1;
  old.erase("speed");  // schema 4's speed keys
  old.erase("keys");
  old["params"].erase("gains.swingTargetRate");
  old["params"]["front.supportGain"] = 800;
  old["meta"] = {{"author", "x"}};
  std::string out;
  const auto error = normalizeGaitFile(old.dump(), &out);
  ASSERT_FALSE(error) << error->describe();
  const json doc = json::parse(out);
  EXPECT_EQ(doc["version"], kGaitFormatVersion);
  EXPECT_EQ(doc["params"]["gains.swingTargetRate"], 0.0);
  EXPECT_FALSE(doc["params"].contains("front.supportGain"));
  EXPECT_EQ(doc["meta"]["author"], "x");
  EXPECT_EQ(doc["params"].size(), paramSpecs(Character::Quadruped).size());
  EXPECT_EQ(out.find('\n'), std::string::npos);  // one line
  // Normalising the normal form changes nothing.
  std::string again;
  ASSERT_FALSE(normalizeGaitFile(out, &again));
  EXPECT_EQ(again, out);

  json bad = json::parse(presetText(Character::Biped));
  bad["params"]["period"] = 7.5;
  std::string untouched = "kept";
  const auto refused = normalizeGaitFile(bad.dump(), &untouched);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->describe(), "period: 7.5 is outside [0.3, 3.0]");
  EXPECT_EQ(untouched, "kept");
}

// applyParamsPatch: the named values change and nothing else; any bad value refuses the whole
// patch, naming the parameter, and leaves the parameters as they were.
TEST(GaitFile, PatchChangesOnlyWhatItNamesAllOrNothing) {
  const GaitParams preset = defaultParams(Character::Biped);
  GaitParams p = preset;
  ASSERT_FALSE(applyParamsPatch(Character::Biped, R"({"period": 1.25, "legFrame.pitch": [0.1, 0.2, -0.1, 0]})", &p));
  EXPECT_EQ(p.period, 1.25);
  EXPECT_EQ(p.legFrames[0].pitch.knots[1], 0.2);
  GaitParams expected = preset;
  expected.period = 1.25;
  const double pitch[4] = {0.1, 0.2, -0.1, 0};
  std::memcpy(expected.legFrames[0].pitch.knots, pitch, sizeof(pitch));
  EXPECT_TRUE(sameBits(p, expected));

  const std::pair<const char*, const char*> refusals[] = {
      {R"({"period": 1.0, "left.dutyFactor": 2})", "left.dutyFactor: 2.0 is outside [0.2, 0.9]"},
      {R"({"period": 1.0, "front.pitch": [0,0,0,0]})", "front.pitch: unknown parameter for a biped"},
      {R"({"legFrame.pitch": [0, 0]})", "legFrame.pitch: expected an array of 4 numbers (motion graph knots), got an array of 2"},
      {R"({"legFrame.stepHeight": [0, 0.1, -0.01, 0]})", "legFrame.stepHeight[2]: -0.01 is outside [0.0, 0.25]"},
      {R"({"period": "1"})", "period: expected a number, got a string"},
      // JSON has no infinity; nlohmann refuses a number beyond a double's range while parsing.
      {R"({"period": 1e999})", "not valid JSON: [json.exception.out_of_range.406] number overflow parsing '1e999'"},
      {R"([1, 2])", "expected a JSON object of parameter values, got an array of 2"},
  };
  for (const auto& [patch, message] : refusals) {
    GaitParams q = p;
    const auto error = applyParamsPatch(Character::Biped, patch, &q);
    ASSERT_TRUE(error) << patch;
    EXPECT_EQ(error->describe(), message) << patch;
    EXPECT_TRUE(sameBits(q, p)) << patch << " changed the parameters";
  }
  GaitParams q = p;
  const auto error = applyParamsPatch(Character::Biped, "{\"period\": ", &q);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->field, "");
  EXPECT_NE(error->message.find("not valid JSON"), std::string::npos);
}
