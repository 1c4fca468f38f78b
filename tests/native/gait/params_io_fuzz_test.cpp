// Hostile gait files (gait/params_io.h, api/limits.h): generated structured inputs (nested deep,
// huge, long strings and arrays, non-finite and wrongly typed values, random bytes, damaged
// presets) each give a result or an error, never a crash, a hang or a value that is not finite.
// Every case is small enough that the whole file runs in about a second.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>
#include <string>

#include "api/limits.h"
#include "gait/defaults.h"
#include "gait/params_io.h"

using namespace gaitlab::gait;
namespace limits = gaitlab::limits;

namespace {

std::string nested(int depth, const std::string& inner = "0") {
  return std::string(depth, '[') + inner + std::string(depth, ']');
}

// A gait file whose top-level `field` is `value` and everything else as the biped preset.
std::string withField(const std::string& field, const std::string& value) {
  nlohmann::json doc = nlohmann::json::parse(presetText(Character::Biped));
  doc[field] = "@@";
  std::string text = doc.dump();
  text.replace(text.find("\"@@\""), 4, value);
  return text;
}

// Every parameter of a parsed file is finite (the property behind "never NaN in the state").
bool allFinite(Character c, GaitParams params) {
  bool finite = true;
  forEachParam(c, params, [&](const ParamField& f) {
    for (int k = 0; k < f.spec.knots; ++k) finite = finite && std::isfinite(f.values[k]);
  });
  return finite;
}

// Parses `text` and checks the property: an error leaves the target as it was; a success gives
// finite parameters. Returns the error's text ("" on success).
std::string judge(const std::string& text) {
  GaitFile file;
  file.gait = Gait::single(defaultParams(Character::Biped));
  const GaitParams before = file.gait.primaryParams();
  const auto error = parseGaitFile(text, std::nullopt, &file);
  if (error) {
    EXPECT_EQ(file.gait.keys.size(), 1u) << "a refused file changed the target";
    EXPECT_EQ(std::memcmp(&before, &file.gait.primaryParams(), sizeof before), 0) << "a refused file changed the target";
    return error->describe().empty() ? "(empty message)" : error->describe();
  }
  for (const SpeedKey& key : file.gait.keys) EXPECT_TRUE(allFinite(file.character, key.params));
  std::string normalized;
  EXPECT_FALSE(normalizeGaitFile(text, &normalized));
  return "";
}

}  // namespace

TEST(GaitFileFuzz, DeepNestingInEveryFieldIsRefusedWithoutRecursion) {
  // 100,000 levels crashed the CLI (a recursive copy and dump() of the error path) before the
  // limit; now the pre-scan stops at kMaxJsonDepth without building anything.
  for (const char* field : {"format", "version", "character", "params", "meta"}) {
    for (const std::string& inner : {std::string("0"), std::string("{\"a\":0}")}) {
      SCOPED_TRACE(field);
      const std::string message = judge(withField(field, nested(100000, inner)));
      EXPECT_NE(message.find("nested deeper than 16"), std::string::npos) << message;
    }
  }
  // Objects as deep as arrays, and an unclosed nesting (not JSON, and deep).
  std::string objects;
  for (int i = 0; i < 40000; ++i) objects += "{\"a\":";
  const std::string deepObjects = judge(objects + "0" + std::string(40000, '}'));
  EXPECT_NE(deepObjects.find("nested deeper"), std::string::npos) << deepObjects;
  EXPECT_NE(judge(std::string(1000000 / 4, '[')), "");
  // Within the limit, "meta" may nest (the optimiser writes objects two levels deep).
  EXPECT_EQ(judge(withField("meta", "{\"a\":" + nested(limits::kMaxJsonDepth - 3) + "}")), "");
  EXPECT_NE(judge(withField("meta", "{\"a\":" + nested(limits::kMaxJsonDepth - 1) + "}")), "");
}

TEST(GaitFileFuzz, HugeTextsStringsAndArraysAreRefusedNamingTheLimit) {
  const std::string big(limits::kMaxJsonBytes + 1, ' ');
  EXPECT_NE(judge(presetText(Character::Biped) + big).find("bytes long"), std::string::npos);
  const std::string longString = "\"" + std::string(limits::kMaxJsonString + 1, 'x') + "\"";
  EXPECT_NE(judge(withField("meta", "{\"note\":" + longString + "}")).find("string is longer"), std::string::npos);
  EXPECT_NE(judge(withField("meta", "{" + longString + ":1}")).find("string is longer"), std::string::npos);
  std::string array = "[0";
  for (long i = 0; i < limits::kMaxJsonArray; ++i) array += ",0";
  EXPECT_NE(judge(withField("meta", "{\"a\":" + array + "]}")).find("elements"), std::string::npos);
}

TEST(GaitFileFuzz, EndlessAndHugeFilesReturnAfterReadingAtMostTheLimit) {
  GaitFile file;
  const auto start = std::chrono::steady_clock::now();
  const auto error = loadGaitFile("/dev/zero", std::nullopt, &file);
  ASSERT_TRUE(error);
  EXPECT_NE(error->describe().find("longer than"), std::string::npos) << error->describe();
  // Reading stops at the limit: this is a hang guard, not a timing (it took forever before).
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

TEST(GaitFileFuzz, NonFiniteAndWronglyTypedValuesAreRefused) {
  const nlohmann::json preset = nlohmann::json::parse(presetText(Character::Biped));
  const std::string name = preset["params"].begin().key();
  for (const char* bad : {"NaN", "Infinity", "-Infinity", "1e999", "-1e999", "1e308", "null", "true", "\"1\"", "[]",
                          "{}", "[1,2,3,4]", "\"\\u0000\"", "-0", "1e-400"}) {
    std::string text = preset.dump();
    const std::string key = "\"" + name + "\":";
    const size_t at = text.find(key) + key.size();
    const size_t end = text.find_first_of(",}", at);
    text.replace(at, end - at, bad);
    SCOPED_TRACE(bad);
    judge(text);  // the property; a value within bounds ("-0", "1e-400") may well be accepted
  }
  EXPECT_NE(judge(withField("version", "1e999")), "");
  EXPECT_NE(judge(withField("version", "2.5")), "");
  EXPECT_NE(judge(withField("version", "-9223372036854775809")), "");
}

TEST(GaitFileFuzz, RandomBytesAndDamagedPresetsGiveAResultOrAnError) {
  std::mt19937 rng(2024);
  const std::string preset = presetText(Character::Quadruped);
  const std::string alphabet = "{}[]\":,0123456789.eE+-ntruefalsNaIiy \\u\x80\xff\xc3";
  for (int i = 0; i < 400; ++i) {
    std::string text(rng() % 300, ' ');
    for (char& ch : text) ch = static_cast<char>(i % 2 ? rng() : alphabet[rng() % alphabet.size()]);
    judge(text);
  }
  for (int i = 0; i < 300; ++i) {
    std::string text = preset;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const size_t at = rng() % text.size();
      switch (rng() % 4) {
        case 0: text[at] = alphabet[rng() % alphabet.size()]; break;
        case 1: text.erase(at, 1 + rng() % 8); break;
        case 2: text.insert(at, nested(1 + rng() % 40)); break;
        default: text.insert(at, std::string(1 + rng() % 4, alphabet[rng() % alphabet.size()])); break;
      }
    }
    judge(text);
  }
}

TEST(GaitFileFuzz, PatchesHaveTheSameLimits) {
  GaitParams params = defaultParams(Character::Biped);
  const GaitParams before = params;
  for (const std::string& patch : {nested(100000), std::string(limits::kMaxJsonBytes + 1, ' '),
                                   std::string("{\"x\":") + nested(20) + "}", std::string("\xff\xfe"),
                                   std::string("{\"gains.swingTargetRate\": NaN}")}) {
    EXPECT_TRUE(applyParamsPatch(Character::Biped, patch, &params));
    EXPECT_EQ(std::memcmp(&before, &params, sizeof before), 0);
  }
}

TEST(GaitFileFuzz, MetaThatIsNotUtf8IsWrittenNotAborted) {
  // A command line in another encoding ends up in "meta" (gaitlab optimize): dump() aborts on
  // such bytes unless told to replace them.
  const nlohmann::json meta = {{"command", std::string("gaitlab optimize --out \xff\xfe.json")}};
  const std::string text = gaitFileJson(Character::Biped, defaultParams(Character::Biped), meta);
  GaitFile file;
  EXPECT_FALSE(parseGaitFile(text, Character::Biped, &file));
  EXPECT_NE(text.find("\xEF\xBF\xBD"), std::string::npos);
  EXPECT_FALSE(parseGaitFile(gaitFileJson(Character::Biped, defaultParams(Character::Biped), meta, -1), Character::Biped, &file));
}
