// The parameter schema (gait/schema.h): it covers every field of GaitParams exactly once, its
// names follow the morphology, the shipped defaults sit within its bounds, and the flat vector
// the optimiser works on maps back to the same struct.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "body/morphology.h"
#include "gait/defaults.h"
#include "gait/schema.h"

using namespace gaitlab::gait;

namespace {

// GaitParams is plain doubles (scalars, motion-graph knots, arrays): the tests view it as an
// array of doubles to find which slot a schema entry writes. Adding a field of another type to
// GaitParams breaks this on purpose: the schema must learn about it.
static_assert(sizeof(GaitParams) % sizeof(double) == 0, "GaitParams must hold only doubles");
constexpr int kSlots = sizeof(GaitParams) / sizeof(double);

int slotOf(const GaitParams& p, const double* field) {
  return static_cast<int>(field - reinterpret_cast<const double*>(&p));
}

// Slots a character does not use: the leg frames and legs beyond its own (GaitParams has room for
// the bodies of creature files, up to kMaxLegFrames leg frames), the biped's spine gains (it
// has no spine) and the quadruped's hip stop.
std::set<int> unusedSlots(Character c) {
  std::set<int> unused;
  GaitParams p;
  const auto range = [&](const void* begin, size_t bytes) {
    const int first = slotOf(p, static_cast<const double*>(begin));
    for (int i = 0; i < static_cast<int>(bytes / sizeof(double)); ++i) unused.insert(first + i);
  };
  const bool biped = c == Character::Biped;
  const int frames = biped ? 1 : 2, legs = 2 * frames;
  range(&p.legFrames[frames], (kMaxLegFrames - frames) * sizeof(LegFrameParams));
  range(&p.legs[legs], (kMaxLegs - legs) * sizeof(LegParams));
  if (biped) {  // no spine, and no whole-body stance for a turn's roll moment
    range(&p.gains.spineKp, sizeof(double));
    range(&p.gains.spineKd, sizeof(double));
    range(&p.turnRollMoment, sizeof(double));
  } else {  // a thigh's forward stop: the quadruped's legs fold both ways
    range(&p.hipForwardStop, sizeof(double));
  }
  return unused;
}

class PerCharacter : public ::testing::TestWithParam<Character> {};

}  // namespace

TEST_P(PerCharacter, EveryUsedFieldOfGaitParamsIsInTheSchemaExactlyOnce) {
  const Character c = GetParam();
  const GaitParams base{};
  std::map<int, std::string> owner;  // slot -> the schema entry that writes it
  GaitParams probe = base;
  forEachParam(c, probe, [&](const ParamField& f) {
    for (int k = 0; k < f.spec.knots; ++k) {
      // Perturb one knot through the visitor and look at which slot of the struct changed.
      GaitParams changed = base;
      double* value = nullptr;
      forEachParam(c, changed, [&](const ParamField& g) {
        if (g.spec.name == f.spec.name) value = &g.values[k];
      });
      ASSERT_NE(value, nullptr);
      *value += 12345.0;
      int differing = 0, slot = -1;
      for (int s = 0; s < kSlots; ++s) {
        if (std::memcmp(reinterpret_cast<const double*>(&changed) + s,
                        reinterpret_cast<const double*>(&base) + s, sizeof(double)) != 0) {
          ++differing;
          slot = s;
        }
      }
      ASSERT_EQ(differing, 1) << f.spec.name << "[" << k << "]";
      EXPECT_EQ(owner.count(slot), 0u) << f.spec.name << " writes the slot of " << owner[slot];
      owner[slot] = f.spec.name;
    }
  });
  const std::set<int> unused = unusedSlots(c);
  for (int s = 0; s < kSlots; ++s) {
    if (unused.count(s)) {
      EXPECT_EQ(owner.count(s), 0u) << "an unused slot is in the schema: " << owner[s];
    } else {
      EXPECT_EQ(owner.count(s), 1u) << "slot " << s << " of GaitParams is in no schema entry";
    }
  }
  EXPECT_EQ(static_cast<int>(owner.size()), paramDimension(c));
}

// paramRuns is the schema's fields as runs of doubles, for the blend of speed keys: the same
// slots forEachParam visits, each once, in order, and no two runs that could be one.
TEST_P(PerCharacter, ParamRunsHoldExactlyTheVisitedSlotsMerged) {
  const Character c = GetParam();
  GaitParams p{};
  std::set<int> visited;
  forEachParam(c, p, [&](const ParamField& f) {
    for (int k = 0; k < f.spec.knots; ++k) visited.insert(slotOf(p, f.values + k));
  });
  std::set<int> inRuns;
  int end = -1;
  for (const ParamRun& r : paramRuns(c)) {
    EXPECT_GT(r.count, 0);
    EXPECT_GT(r.first, end) << "runs out of order, overlapping or left unmerged at slot " << r.first;
    for (int k = r.first; k < r.first + r.count; ++k) EXPECT_TRUE(inRuns.insert(k).second) << k;
    end = r.first + r.count;
  }
  EXPECT_EQ(inRuns, visited);
}

TEST_P(PerCharacter, NamesAreUniqueAndEntriesWellFormed) {
  std::set<std::string> names;
  for (const ParamSpec& s : paramSpecs(GetParam())) {
    EXPECT_TRUE(names.insert(s.name).second) << "duplicate " << s.name;
    EXPECT_LT(s.min, s.max) << s.name;
    EXPECT_TRUE(s.knots == 1 || s.knots == MotionGraph::kKnots) << s.name;
    EXPECT_GT(std::strlen(s.description), 10u) << s.name;
    EXPECT_GT(std::strlen(s.group), 0u) << s.name;
  }
}

TEST_P(PerCharacter, DefaultsLieWithinTheBounds) {
  GaitParams p = defaultParams(GetParam());
  forEachParam(GetParam(), p, [&](const ParamField& f) {
    for (int k = 0; k < f.spec.knots; ++k) {
      EXPECT_GE(f.values[k], f.spec.min) << f.spec.name << "[" << k << "]";
      EXPECT_LE(f.values[k], f.spec.max) << f.spec.name << "[" << k << "]";
    }
  });
}

TEST_P(PerCharacter, FlatVectorRoundTripsAndMatchesTheBounds) {
  const Character c = GetParam();
  const GaitParams p = defaultParams(c);
  const std::vector<double> v = toVector(c, p);
  ASSERT_EQ(static_cast<int>(v.size()), paramDimension(c));
  std::vector<double> lo, hi;
  bounds(c, &lo, &hi);
  ASSERT_EQ(lo.size(), v.size());
  ASSERT_EQ(hi.size(), v.size());
  GaitParams q{};
  fromVector(c, v, &q);
  EXPECT_EQ(toVector(c, q), v);
  // Changing one coordinate changes exactly that coordinate back in the vector.
  std::vector<double> w = v;
  w[v.size() / 2] = 0.5 * (lo[v.size() / 2] + hi[v.size() / 2]) + 1e-3;
  fromVector(c, w, &q);
  EXPECT_EQ(toVector(c, q), w);
}

INSTANTIATE_TEST_SUITE_P(Characters, PerCharacter,
                         ::testing::Values(Character::Biped, Character::Quadruped),
                         [](const auto& info) { return std::string(characterName(info.param)); });

TEST(Schema, LegAndLegFrameNamesFollowTheMorphology) {
  // Leg fields are named after the morphology's legs, in its order: "front.left" -> frontLeft.
  const auto camel = [](const std::string& dotted) {
    std::string out;
    bool upper = false;
    for (char ch : dotted) {
      if (ch == '.') {
        upper = true;
        continue;
      }
      out += upper ? static_cast<char>(std::toupper(ch)) : ch;
      upper = false;
    }
    return out;
  };
  for (const auto& [c, m] : {std::pair{Character::Biped, gaitlab::body::makeBiped()},
                             std::pair{Character::Quadruped, gaitlab::body::makeQuadruped()}}) {
    EXPECT_EQ(characterOf(m), c);
    std::vector<std::string> legs, frames;
    for (const ParamSpec& s : paramSpecs(c)) {
      const auto dot = s.name.rfind('.');
      if (s.name.substr(dot + 1) == "dutyFactor") legs.push_back(s.name.substr(0, dot));
      if (s.name.substr(dot + 1) == "pitch") frames.push_back(s.name.substr(0, dot));
    }
    ASSERT_EQ(legs.size(), m.legs.size());
    for (size_t i = 0; i < legs.size(); ++i) EXPECT_EQ(legs[i], camel(m.legs[i].name));
    EXPECT_EQ(frames.size(), m.legFrames.size());
  }
  EXPECT_EQ(paramSpecs(Character::Quadruped)[0].name, "period");
}

TEST(Schema, JsonExportDescribesEveryParameterWithItsDefault) {
  const nlohmann::json doc = nlohmann::json::parse(schemaJson(), nullptr, false);
  ASSERT_FALSE(doc.is_discarded());
  EXPECT_EQ(doc["version"], kSchemaVersion);
  for (Character c : {Character::Biped, Character::Quadruped}) {
    const nlohmann::json& entries = doc["characters"][characterName(c)];
    ASSERT_EQ(entries.size(), paramSpecs(c).size());
    GaitParams defaults = defaultParams(c);
    size_t i = 0;
    forEachParam(c, defaults, [&](const ParamField& f) {
      const nlohmann::json& e = entries[i++];
      EXPECT_EQ(e["name"], f.spec.name);
      EXPECT_EQ(e["group"], f.spec.group);
      EXPECT_EQ(e["min"], f.spec.min);
      EXPECT_EQ(e["max"], f.spec.max);
      EXPECT_EQ(e["unit"], f.spec.unit);
      EXPECT_EQ(e["description"], f.spec.description);
      EXPECT_EQ(e["knots"], f.spec.knots);
      if (f.spec.knots == 1) {
        EXPECT_EQ(e["default"], f.values[0]) << f.spec.name;
      } else {
        ASSERT_TRUE(e["default"].is_array()) << f.spec.name;
        ASSERT_EQ(e["default"].size(), static_cast<size_t>(f.spec.knots));
        for (int k = 0; k < f.spec.knots; ++k) EXPECT_EQ(e["default"][k], f.values[k]);
      }
    });
  }
  const nlohmann::json one = nlohmann::json::parse(schemaJson(Character::Quadruped), nullptr, false);
  EXPECT_FALSE(one["characters"].contains("biped"));
  EXPECT_TRUE(one["characters"].contains("quadruped"));
}

// The page finds a parameter's leg or leg frame, and the legs' leg frames and sides, in the
// schema itself (it takes no names apart): every per-leg and per-leg-frame entry says which.
TEST(Schema, EntriesNameTheirLegOrLegFrameAndTheMorphologyIsExported) {
  const nlohmann::json doc = nlohmann::json::parse(schemaJson(), nullptr, false);
  ASSERT_FALSE(doc.is_discarded());
  for (Character c : kCharacters) {
    const nlohmann::json& morphology = doc["morphologies"][characterName(c)];
    EXPECT_EQ(morphology["kind"], kindNumber(c));
    EXPECT_EQ(characterFromKind(kindNumber(c)), c);
    EXPECT_EQ(characterOf(shippedBody(c)), c);
    ASSERT_EQ(morphology["legFrames"].size(), legFrameNames(c).size());
    ASSERT_EQ(morphology["legs"].size(), legNames(c).size());
    for (const nlohmann::json& e : doc["characters"][characterName(c)]) {
      const std::string name = e["name"];
      const ParamSpec* spec = findParam(c, name);
      ASSERT_NE(spec, nullptr) << name;
      if (e.contains("leg")) {
        const int i = e["leg"]["index"];
        EXPECT_EQ(spec->leg, i);
        EXPECT_EQ(e["leg"]["name"], legNames(c)[i]);
        EXPECT_EQ(name, legNames(c)[i] + "." + e["field"].get<std::string>());
      } else if (e.contains("legFrame")) {
        const int i = e["legFrame"]["index"];
        EXPECT_EQ(spec->legFrame, i);
        EXPECT_EQ(name, legFrameNames(c)[i] + "." + e["field"].get<std::string>());
      } else {
        EXPECT_EQ(spec->leg, -1);
        EXPECT_EQ(spec->legFrame, -1);
        EXPECT_EQ(e["field"], name);
      }
    }
  }
  EXPECT_FALSE(characterFromKind(2));  // a box is not a character
  EXPECT_EQ(findParam(Character::Biped, "front.pitch"), nullptr);
  // Every leg has its duty factor and step trigger; the quadruped's legs hang from both leg
  // frames, front legs from the first, and each pair has a left and a right leg.
  const nlohmann::json& legs = doc["morphologies"]["quadruped"]["legs"];
  const std::vector<std::pair<int, std::string>> expected = {{0, "left"}, {0, "right"}, {1, "left"}, {1, "right"}};
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(legs[i]["legFrame"], expected[i].first) << i;
    EXPECT_EQ(legs[i]["side"], expected[i].second) << i;
  }
  EXPECT_EQ(doc["morphologies"]["biped"]["legs"][0]["side"], "left");
  EXPECT_EQ(doc["morphologies"]["biped"]["legs"][1]["side"], "right");
}
