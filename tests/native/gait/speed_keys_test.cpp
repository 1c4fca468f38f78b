// Speed keys (gait/speed_keys.h): the parameters in effect are the keys blended linearly by the
// desired speed; gait files carry the keys (schema 4) and refuse bad ones naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>

#include "gait/defaults.h"
#include "gait/params_io.h"
#include "gait/speed_keys.h"

using namespace gaitlab::gait;
using nlohmann::json;

namespace {

bool sameBits(const GaitParams& a, const GaitParams& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

// The biped preset at 0.5 m/s and a copy with a shorter period, a lower duty factor and a
// different pitch graph at 1.5 m/s.
Gait twoKeys() {
  Gait g = Gait::single(defaultParams(Character::Biped), 0.5);
  SpeedKey fast{1.5, defaultParams(Character::Biped)};
  fast.params.period = 0.5;
  fast.params.legs[0].dutyFactor = 0.35;
  fast.params.legFrames[0].pitch = MotionGraph::of(0.0, 0.1, 0.2, 0.3);
  g.keys.push_back(fast);
  return g;
}

}  // namespace

TEST(SpeedKeys, OneKeyIsThatParameterSetAtEverySpeed) {
  const Gait g = Gait::single(defaultParams(Character::Quadruped), 0.8);
  for (double speed : {0.0, 0.8, 2.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    GaitParams p;
    paramsAtSpeed(Character::Quadruped, g, speed, &p);
    EXPECT_TRUE(sameBits(p, g.keys[0].params)) << speed;
  }
}

TEST(SpeedKeys, FieldsAreLinearInSpeedBetweenKeysAndHeldBeyondThem) {
  const Gait g = twoKeys();
  const GaitParams& slow = g.keys[0].params;
  const GaitParams& fast = g.keys[1].params;
  GaitParams p;
  paramsAtSpeed(Character::Biped, g, 1.0, &p);  // halfway
  EXPECT_DOUBLE_EQ(p.period, 0.5 * (slow.period + fast.period));
  EXPECT_DOUBLE_EQ(p.legs[0].dutyFactor, 0.5 * (slow.legs[0].dutyFactor + 0.35));
  for (int k = 0; k < MotionGraph::kKnots; ++k)
    EXPECT_DOUBLE_EQ(p.legFrames[0].pitch.knots[k],
                     0.5 * (slow.legFrames[0].pitch.knots[k] + fast.legFrames[0].pitch.knots[k]));
  EXPECT_EQ(p.gains.hipKp, slow.gains.hipKp);  // equal in both keys: unchanged
  paramsAtSpeed(Character::Biped, g, 1.25, &p);
  EXPECT_DOUBLE_EQ(p.period, slow.period + (fast.period - slow.period) * 0.75);
  // Walking backwards uses the speed's magnitude.
  GaitParams back;
  paramsAtSpeed(Character::Biped, g, -1.25, &back);
  EXPECT_TRUE(sameBits(p, back));
  paramsAtSpeed(Character::Biped, g, 0.2, &p);
  EXPECT_TRUE(sameBits(p, slow));
  paramsAtSpeed(Character::Biped, g, 3.0, &p);
  EXPECT_TRUE(sameBits(p, fast));
  paramsAtSpeed(Character::Biped, g, 1.5, &p);
  EXPECT_TRUE(sameBits(p, fast));
}

// The controller skips the blend while the desired speed moves where the parameters are held:
// heldAlike must say "alike" only where paramsAtSpeed gives the same bits, and must not where it
// does not.
TEST(SpeedKeys, HeldAlikeIsTrueExactlyWhereTheBlendIsTheSame) {
  const Gait g = twoKeys();  // keys at 0.5 and 1.5 m/s
  const double speeds[] = {-2.0, -0.3, 0.0, 0.2, 0.5, 0.7, 1.0, 1.5, 1.6, 3.0};
  int alike = 0, differ = 0;
  for (double a : speeds) {
    for (double b : speeds) {
      GaitParams pa, pb;
      paramsAtSpeed(Character::Biped, g, a, &pa);
      paramsAtSpeed(Character::Biped, g, b, &pb);
      if (g.heldAlike(a, b)) {
        EXPECT_TRUE(sameBits(pa, pb)) << a << " and " << b;
        ++alike;
      } else {
        EXPECT_FALSE(sameBits(pa, pb)) << a << " and " << b;
        ++differ;
      }
    }
  }
  EXPECT_GT(alike, 0);
  EXPECT_GT(differ, 0);
  EXPECT_TRUE(g.heldAlike(0.2, 0.4));
  EXPECT_TRUE(g.heldAlike(1.6, 2.5));
  EXPECT_FALSE(g.heldAlike(0.4, 0.6));
  EXPECT_FALSE(g.heldAlike(1.4, 1.6));
}

TEST(SpeedKeys, AGaitFileCarriesItsKeysAndReadsBackBitExactly) {
  const Gait g = twoKeys();
  for (int primary : {0, 1}) {
    Gait h = g;
    h.primary = primary;
    const std::string text = gaitFileJson(Character::Biped, h);
    GaitFile file;
    ASSERT_FALSE(parseGaitFile(text, Character::Biped, &file)) << text;
    const Gait& back = file.gait;
    EXPECT_EQ(back.keys[back.primary].speed, h.keys[primary].speed);
    EXPECT_TRUE(sameBits(back.primaryParams(), h.keys[primary].params));
    ASSERT_EQ(back.keys.size(), 2u);
    EXPECT_EQ(back.primary, primary);
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(back.keys[i].speed, g.keys[i].speed);
      EXPECT_TRUE(sameBits(back.keys[i].params, g.keys[i].params));
    }
    std::string normalized;
    ASSERT_FALSE(normalizeGaitFile(text, &normalized));
    EXPECT_EQ(normalized, gaitFileJson(Character::Biped, h, json::object(), -1));
  }
  // A gait of one key at 0 m/s is written as files were before speed keys (no "speed", no "keys").
  const json plain = json::parse(gaitFileJson(Character::Biped, defaultParams(Character::Biped)));
  EXPECT_FALSE(plain.contains("speed"));
  EXPECT_FALSE(plain.contains("keys"));
  EXPECT_EQ(plain["version"], kGaitFormatVersion);
}

TEST(SpeedKeys, BadKeysAreRefusedNamingTheFieldAndLeaveTheTargetUntouched) {
  const json good = json::parse(gaitFileJson(Character::Biped, twoKeys()));
  struct Case {
    const char* what;
    std::function<void(json&)> change;
    std::string field, message;
  };
  const std::vector<Case> cases = {
      {"keys in a version 3 file", [](json& j) { j["version"] = 3; }, "speed", "version 4"},
      {"keys not an array", [](json& j) { j["keys"] = json::object(); }, "keys", "expected an array"},
      {"a key not an object", [](json& j) { j["keys"][0] = 1.5; }, "keys[0]", "expected an object"},
      {"a key without a speed", [](json& j) { j["keys"][0].erase("speed"); }, "keys[0].speed", "missing"},
      {"a negative speed", [](json& j) { j["keys"][0]["speed"] = -1; }, "keys[0].speed", "outside"},
      {"a speed as text", [](json& j) { j["keys"][0]["speed"] = "fast"; }, "keys[0].speed", "expected a number"},
      {"two keys at one speed", [](json& j) { j["keys"][0]["speed"] = 0.5; }, "keys[0].speed", "already"},
      {"a key missing a parameter", [](json& j) { j["keys"][0]["params"].erase("period"); },
       "keys[0].params.period", "missing"},
      {"a key's parameter out of bounds", [](json& j) { j["keys"][0]["params"]["period"] = 1e6; },
       "keys[0].params.period", "outside"},
      {"a key's knot out of bounds", [](json& j) { j["keys"][0]["params"]["legFrame.pitch"][2] = 1e6; },
       "keys[0].params.legFrame.pitch[2]", "outside"},
      {"an unknown field in a key", [](json& j) { j["keys"][0]["gait"] = "run"; }, "keys[0].gait", "unknown field"},
      {"too many keys", [](json& j) {
         for (int i = 1; i < kMaxSpeedKeys; ++i) {
           json k = j["keys"][0];
           k["speed"] = 2.0 + i;
           j["keys"].push_back(k);
         }
       }, "keys", "at most"},
      {"the primary's speed not finite", [](json& j) { j["speed"] = nullptr; }, "speed", "expected a number"},
  };
  for (const Case& c : cases) {
    json j = good;
    c.change(j);
    GaitFile target;
    target.gait.primaryParams().period = 0.123;
    const auto error = parseGaitFile(j.dump(), Character::Biped, &target);
    ASSERT_TRUE(error) << c.what;
    EXPECT_EQ(error->field, c.field) << c.what;
    EXPECT_NE(error->message.find(c.message), std::string::npos) << c.what << ": " << error->message;
    EXPECT_EQ(target.gait.primaryParams().period, 0.123) << c.what;
    EXPECT_EQ(target.gait.keys.size(), 1u) << c.what;
  }
}

TEST(SpeedKeys, APatchEditsThePrimaryKeyAndMaySetTheKeysAllOrNothing) {
  const Gait g = twoKeys();  // primary: the key at 0.5 m/s
  Gait h = g;
  ASSERT_FALSE(applyGaitPatch(Character::Biped, R"({"period": 0.9})", &h));
  EXPECT_EQ(h.primaryParams().period, 0.9);
  EXPECT_TRUE(sameBits(h.keys[1].params, g.keys[1].params));

  // "keys" replaces the other keys; "speed" moves the primary.
  const json fastKey = json::parse(gaitFileJson(Character::Biped, g))["keys"];
  h = Gait::single(defaultParams(Character::Biped));
  json patch = {{"speed", 0.5}, {"keys", fastKey}};
  ASSERT_FALSE(applyGaitPatch(Character::Biped, patch.dump(), &h));
  ASSERT_EQ(h.keys.size(), 2u);
  EXPECT_EQ(h.keys[0].speed, 0.5);
  EXPECT_EQ(h.primary, 0);
  EXPECT_TRUE(sameBits(h.keys[1].params, g.keys[1].params));
  ASSERT_FALSE(applyGaitPatch(Character::Biped, R"({"keys": []})", &h));
  EXPECT_EQ(h.keys.size(), 1u);

  // Refused, and nothing changes: the primary moved onto another key's speed, a bad key.
  h = g;
  for (const char* bad : {R"({"speed": 1.5})", R"({"keys": [{"speed": 0.5, "params": {}}]})",
                          R"({"period": 0.9, "keys": [{"speed": 2}]})", R"({"period": -1})"}) {
    EXPECT_TRUE(applyGaitPatch(Character::Biped, bad, &h)) << bad;
    EXPECT_TRUE(sameBits(h.primaryParams(), g.primaryParams())) << bad;
    EXPECT_EQ(h.keys.size(), 2u) << bad;
  }
}
