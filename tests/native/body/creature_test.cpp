// Creature files (body/creature.h): the shipped biped and quadruped as data, bodies of other leg
// counts built by the same rules, and files refused whole with the field named.
#include "body/creature.h"

#include <gtest/gtest.h>

#include "api/c_api.h"

#include "gait/derived_gait.h"
#include "gait/defaults.h"
#include "gait/params_io.h"
#include "sim/simulation.h"
#include "sim/walk_trial.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>

namespace gaitlab::body {
namespace {

using nlohmann::json;

std::string readText(const std::string& relative) {
  std::ifstream in(std::string(GAITLAB_SOURCE_DIR) + "/" + relative);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

json shippedQuadruped() { return json::parse(readText("public/creatures/quadruped.json")); }

// The refusal of a copy of the shipped quadruped with one edit, as "field: message".
std::string refusal(const std::function<void(json&)>& edit) {
  json doc = shippedQuadruped();
  edit(doc);
  Morphology m;
  m.name = "untouched";
  const auto error = parseCreatureFile(doc.dump(), &m);
  EXPECT_EQ(m.name, "untouched") << "a refused file must build nothing";
  return error ? error->describe() : "accepted";
}

// The files on disk are the bodies the simulation uses (the binary embeds them at build time),
// with the proportions the README and the controller's notes give them.
TEST(Creature, TheShippedFilesAreTheShippedCharacters) {
  Morphology biped, quadruped;
  ASSERT_FALSE(parseCreatureFile(readText("public/creatures/biped.json"), &biped));
  ASSERT_FALSE(parseCreatureFile(readText("public/creatures/quadruped.json"), &quadruped));
  EXPECT_EQ(biped.segments.size(), makeBiped().segments.size());
  EXPECT_EQ(quadruped.segments.size(), makeQuadruped().segments.size());
  for (size_t i = 0; i < quadruped.segments.size(); ++i) {
    EXPECT_EQ(quadruped.segments[i].name, makeQuadruped().segments[i].name);
    EXPECT_EQ(quadruped.segments[i].center, makeQuadruped().segments[i].center);
  }
  EXPECT_NEAR(biped.totalMass(), 59.0, 1e-9);
  EXPECT_NEAR(biped.segments[biped.legs[0].upper].joint.pivot.y(), 0.91, 1e-9);  // hip height
  EXPECT_NEAR(quadruped.totalMass(), 33.0, 1e-9);
  EXPECT_NEAR(quadruped.segments[quadruped.legs[0].upper].joint.pivot.y(), 0.485, 1e-9);
  EXPECT_EQ(quadruped.spine.size(), 4u);
  EXPECT_EQ(quadruped.legFrames, (std::vector<int>{0, 5}));
  EXPECT_EQ(quadruped.legs[2].name, "back.left");
  EXPECT_EQ(quadruped.legs[2].legFrame, 5);
  EXPECT_EQ(quadruped.legs[0].kneeBend, -1.0);  // the front knees point backwards
  EXPECT_EQ(biped.legs[1].name, "right");
  EXPECT_EQ(biped.segments[0].rgba, 0xd9734effu);
}

// A six-legged body: a third leg frame and a second spine section, by the same rules. Every
// segment hangs from one before it, the feet rest on the ground, and each pair of legs hangs from
// its own leg frame.
TEST(Creature, ThreeLegFramesMakeASixLeggedBody) {
  json doc = shippedQuadruped();
  json middle = doc["legFrames"][0];
  middle["name"] = "legframe.middle";
  middle["z"] = 0.0;
  middle["legs"]["name"] = "middle";
  doc["legFrames"] = {doc["legFrames"][0], middle, doc["legFrames"][1]};
  json front = doc["spine"][0], back = doc["spine"][0];
  front["from"] = 0.28, front["to"] = 0.12, front["links"] = 2;
  back["from"] = -0.12, back["to"] = -0.28, back["links"] = 2;
  doc["spine"] = {front, back};
  Morphology m;
  const auto error = parseCreatureFile(doc.dump(), &m);
  ASSERT_FALSE(error) << error->describe();
  EXPECT_EQ(m.legs.size(), 6u);
  EXPECT_EQ(m.legFrames, (std::vector<int>{0, 3, 6}));
  EXPECT_EQ(m.spine, (std::vector<int>{1, 2, 4, 5}));
  EXPECT_EQ(m.segments[3].parent, 2);  // the middle leg frame hangs from the front section's last link
  EXPECT_NEAR(m.segments[3].joint.pivot.z(), 0.12, 1e-12);
  EXPECT_EQ(m.legs[2].name, "middle.left");
  EXPECT_EQ(m.legs[2].legFrame, 3);
  for (size_t i = 1; i < m.segments.size(); ++i) EXPECT_LT(m.segments[i].parent, static_cast<int>(i));
  for (const Leg& leg : m.legs) {
    const Segment& foot = m.segments[leg.foot];
    EXPECT_DOUBLE_EQ(foot.center.y() - foot.halfExtents.y(), 0.0) << leg.name;
  }
}

// A walk with the body read from the shipped file on disk is the walk with the built-in body, state
// for state; a body that differs in one segment's mass is another walk.
TEST(Creature, TheShippedFilesWalkAsTheBuiltInBodies) {
  for (const char* name : {"biped", "quadruped"}) {
    Morphology fromFile;
    ASSERT_FALSE(parseCreatureFile(readText(std::string("public/creatures/") + name + ".json"), &fromFile));
    sim::WalkOptions w;
    w.character = gait::characterOf(fromFile);
    w.speed = 0.8;
    w.seconds = 3;
    const std::string builtIn = sim::runWalk(w).stateHash;
    w.body = &fromFile;
    EXPECT_EQ(sim::runWalk(w).stateHash, builtIn) << name;
    Morphology heavier = fromFile;
    heavier.segments[heavier.legs[0].upper].mass *= 1.1;
    w.body = &heavier;
    EXPECT_NE(sim::runWalk(w).stateHash, builtIn) << name;
  }
}

// A first gait for a body of any leg count: two alternating groups of legs (alternating tripods on
// six legs, tetrapods on eight), each leg down for more than half the cycle, the period scaled to
// the legs' length by dynamic similarity.
TEST(Creature, TheDerivedGaitAlternatesTwoGroupsOfLegs) {
  for (const char* name : {"insect", "spider"}) {
    Morphology m;
    ASSERT_FALSE(parseCreatureFile(readText(std::string("public/creatures/") + name + ".json"), &m));
    const gait::GaitParams p = gait::derivedGait(m);
    for (size_t l = 0; l < m.legs.size(); ++l) {
      const int pair = static_cast<int>(l / 2), side = static_cast<int>(l % 2);
      EXPECT_EQ(p.legs[l].stepTrigger, (pair + side) % 2 == 0 ? 0.0 : 0.5) << name << " leg " << m.legs[l].name;
      EXPECT_GT(p.legs[l].dutyFactor, 0.5);
    }
  }
  // The insect's left front, right middle and left back legs lift together.
  Morphology insect;
  ASSERT_FALSE(parseCreatureFile(readText("public/creatures/insect.json"), &insect));
  EXPECT_EQ(insect.legs[0].name, "front.left");
  EXPECT_EQ(insect.legs[3].name, "middle.right");
  // Legs twice as long: a period √2 as long, steps twice as high.
  json doc = json::parse(readText("public/creatures/insect.json"));
  for (json& f : doc["legFrames"]) f["legs"]["upper"]["length"] = 0.44, f["legs"]["lower"]["length"] = 0.44;
  Morphology tall;
  ASSERT_FALSE(parseCreatureFile(doc.dump(), &tall));
  const gait::GaitParams a = gait::derivedGait(insect), b = gait::derivedGait(tall);
  EXPECT_NEAR(b.period / a.period, std::sqrt(2.0), 1e-9);
  const auto highest = [](const gait::MotionGraph& g) { return *std::max_element(g.knots, g.knots + gait::MotionGraph::kKnots); };
  ASSERT_GT(highest(a.legFrames[2].stepHeight), 0.0);
  EXPECT_NEAR(highest(b.legFrames[2].stepHeight) / highest(a.legFrames[2].stepHeight), 2.0, 1e-9);
}

// The shipped creatures of three and four leg frames walk their derived gait with the controller
// every body shares (the walking benchmark's criteria, bench/results/walking-creatures.md, run
// them for 60 s; here 20 s at its two speeds).
TEST(Creature, TheShippedCreaturesWalkTheGaitDerivedFromThem) {
  for (const char* name : {"insect", "spider", "dragon"}) {
    Morphology m;
    ASSERT_FALSE(parseCreatureFile(readText(std::string("public/creatures/") + name + ".json"), &m));
    const gait::Gait gait = gait::Gait::single(gait::derivedGait(m));
    for (double speed : {0.4, 0.8}) {
      sim::WalkOptions w;
      w.character = gait::characterOf(m);
      w.body = &m;
      w.gait = &gait;
      w.speed = speed;
      w.seconds = 20;
      const sim::WalkResult r = sim::runWalk(w);
      EXPECT_FALSE(r.fell) << name << " at " << speed << " m/s fell at " << r.fallTime << " s";
      EXPECT_NEAR(r.meanSpeed, speed, 0.15 * speed) << name;
      EXPECT_LT(r.headingDrift, 10.0) << name;
    }
  }
}

// Legs of three segments (version 2, "tarsus"): a hock between the lower leg and the tarsus, bent
// the other way to the knee, and the foot hanging from the tarsus. The bird's legs are the
// biped's length, so it stands as high.
TEST(Creature, LegsOfThreeSegmentsHaveAHockThatBendsTheOtherWay) {
  Morphology bird;
  ASSERT_FALSE(parseCreatureFile(readText("public/creatures/bird.json"), &bird));
  ASSERT_EQ(bird.legs.size(), 2u);
  EXPECT_EQ(bird.segments.size(), 1u + 2u * 4u);
  for (const Leg& leg : bird.legs) {
    ASSERT_GE(leg.tarsus, 0);
    EXPECT_EQ(leg.aboveAnkle(), leg.tarsus);
    EXPECT_EQ(bird.segments[leg.tarsus].parent, leg.lower);
    EXPECT_EQ(bird.segments[leg.foot].parent, leg.tarsus);
    const Joint& knee = bird.segments[leg.lower].joint;
    const Joint& hock = bird.segments[leg.tarsus].joint;
    EXPECT_EQ(hock.type, JointType::Hinge);
    // The knee points forward (flexes by positive angles); the hock flexes by negative ones.
    EXPECT_DOUBLE_EQ(knee.upper[0], 2.4);
    EXPECT_DOUBLE_EQ(hock.lower[0], -2.4);
    EXPECT_DOUBLE_EQ(hock.upper[0], 0.05);
    EXPECT_NEAR(hock.pivot.y(), 2 * 0.03 + 0.01 + 0.18, 1e-12);
    int segs[4];
    EXPECT_EQ(leg.segments(segs), 4);
  }
  EXPECT_NEAR(bird.segments[bird.legs[0].upper].joint.pivot.y(), 0.91, 1e-12);
  EXPECT_NEAR(bird.totalMass(), 59.0, 1e-9);
  // Legs of two segments have none.
  EXPECT_EQ(makeQuadruped().legs[0].tarsus, -1);
}

// A body walks on legs of three segments with the controller every body shares (the tarsus held
// parallel to the thigh, gait/ik.h): the bird with the biped's gait at the biped's two speeds, and
// an insect whose legs are split into three with its derived gait at the creatures' speeds. At
// 0.8 m/s that insect walks 16 % slow (0.67 m/s; the two-segment insect 6 %), so there only its
// walking without a fall and straight is asserted.
TEST(Creature, BodiesWalkOnLegsOfThreeSegments) {
  Morphology bird, insect;
  ASSERT_FALSE(parseCreatureFile(readText("public/creatures/bird.json"), &bird));
  json doc = json::parse(readText("public/creatures/insect.json"));
  doc["version"] = 2;
  for (json& frame : doc["legFrames"]) {
    json& legs = frame["legs"];
    legs["upper"]["length"] = 0.16;
    legs["lower"]["length"] = 0.17;
    legs["tarsus"] = {{"length", 0.11}, {"halfThickness", 0.025}, {"mass", 0.3}, {"hock", {{"flexion", 2.4}, {"hyperextension", 0.05}}}};
  }
  ASSERT_FALSE(parseCreatureFile(doc.dump(), &insect));
  ASSERT_GE(insect.legs[5].tarsus, 0);
  const gait::Gait birdGait = gait::defaultGait(gait::Character::Biped);
  const gait::Gait insectGait = gait::Gait::single(gait::derivedGait(insect));
  struct Case {
    const Morphology* body;
    const gait::Gait* gait;
    double speed;
    bool tracked;
  };
  for (const Case& c : {Case{&bird, &birdGait, 0.5, true}, Case{&bird, &birdGait, 1.0, true},
                        Case{&insect, &insectGait, 0.4, true}, Case{&insect, &insectGait, 0.8, false}}) {
    sim::WalkOptions w;
    w.character = gait::characterOf(*c.body);
    w.body = c.body;
    w.gait = c.gait;
    w.speed = c.speed;
    w.seconds = 20;
    const sim::WalkResult r = sim::runWalk(w);
    EXPECT_FALSE(r.fell) << c.body->name << " at " << c.speed << " m/s fell at " << r.fallTime << " s";
    if (c.tracked) EXPECT_NEAR(r.meanSpeed, c.speed, 0.15 * c.speed) << c.body->name << " at " << c.speed;
    EXPECT_GT(r.meanSpeed, 0.5 * c.speed) << c.body->name << " at " << c.speed;
    EXPECT_LT(r.headingDrift, 10.0) << c.body->name << " at " << c.speed;
  }
}

// Creatures in a simulation, as the page spawns them (gl_sim_spawn_creature): an insect and a
// spider beside a quadruped walk, and the run is the same on one thread as on two.
TEST(Creature, CreaturesWalkInASimulationAlikeOnAnyNumberOfThreads) {
  Morphology insect, spider;
  ASSERT_FALSE(parseCreatureFile(readText("public/creatures/insect.json"), &insect));
  ASSERT_FALSE(parseCreatureFile(readText("public/creatures/spider.json"), &spider));
  std::string hashes[2];
  for (int threads : {1, 2}) {
    sim::Simulation sim(threads, 7);
    ASSERT_GE(sim.spawnCreature(insect, -2, 0, 0), 0);
    ASSERT_GE(sim.spawnCreature(spider, 0, 0, 0), 0);
    ASSERT_GE(sim.spawn(gait::Character::Quadruped, 2, 0, 0), 0);
    for (int i = 0; i < sim.characterCount(); ++i) sim.setGoal(i, {0.5, 0.0});
    sim.step(1200);  // 10 s
    for (int i = 0; i < sim.characterCount(); ++i) {
      EXPECT_FALSE(sim.fallen(i)) << "character " << i << " on " << threads << " threads";
      EXPECT_GT(sim.character(i).segmentState(sim.character(i).morphology().legFrames[0]).position.z(), 3.0) << i;
    }
    EXPECT_EQ(sim.character(0).morphology().legs.size(), 6u);
    hashes[threads - 1] = sim.stateHash();
  }
  EXPECT_EQ(hashes[0], hashes[1]);
}

// Through the C ABI, as the page does it: a six-legged creature is spawned from its file's text.
// It is a hexapod: gait files of that kind reach it, by kind and by id, and a quadruped's does not.
TEST(Creature, ACreatureOfThreeLegFramesTakesHexapodGaitFiles) {
  void* s = gl_sim_create(1, 1);
  const std::string insect = readText("public/creatures/insect.json");
  const int id = gl_sim_spawn_creature(s, insect.c_str(), 0, 0, 0);
  ASSERT_GE(id, 0) << gl_last_error();
  const int dog = gl_sim_spawn(s, GL_KIND_QUADRUPED, 3, 0, 0);
  EXPECT_EQ(gl_sim_set_params(s, id, GL_KIND_QUADRUPED, gl_preset_json(GL_KIND_QUADRUPED)), GL_ERR_KIND);
  EXPECT_EQ(std::string(gl_last_error()), "kind: character " + std::to_string(id) + " is not a quadruped");
  // What it walks is the gait derived from its own body, as a hexapod's gait file.
  const std::string own = gl_sim_get_params(s, id);
  EXPECT_NE(own.find("\"character\": \"hexapod\""), std::string::npos) << own.substr(0, 200);
  const std::string dogBefore = gl_sim_get_params(s, dog);
  EXPECT_EQ(gl_sim_patch_params(s, -1, GL_KIND_HEXAPOD, "{\"period\": 0.5, \"middleLeft.dutyFactor\": 0.6}"), GL_OK)
      << gl_last_error();
  EXPECT_EQ(std::string(gl_sim_get_params(s, dog)), dogBefore);  // the dog is not a hexapod
  const json patched = json::parse(gl_sim_get_params(s, id));
  EXPECT_EQ(patched["params"]["period"], 0.5);
  EXPECT_EQ(patched["params"]["middleLeft.dutyFactor"], 0.6);
  EXPECT_EQ(gl_sim_set_params(s, id, GL_KIND_HEXAPOD, own.c_str()), GL_OK) << gl_last_error();
  EXPECT_EQ(std::string(gl_sim_get_params(s, id)), own);
  EXPECT_EQ(gl_sim_step(s, 240), GL_OK);
  double info[2 * GL_INFO_FIELDS];
  ASSERT_EQ(gl_sim_character_info(s, info, 2), 2);
  EXPECT_EQ(info[GL_INFO_KIND], GL_KIND_HEXAPOD);
  EXPECT_EQ(info[GL_INFO_LEGS], 6.0);
  EXPECT_EQ(info[GL_INFO_FIELDS + GL_INFO_LEGS], 4.0);
  gl_sim_destroy(s);
}

// The optimize panel's learning for a designed body, through the C ABI: a search over the body of a
// creature file starts from the gait derived from it, every episode walks that body, and the
// learner walks it apart from the crowd. A body of another kind and a bad file are refused.
TEST(Creature, ASearchLearnsForACreaturesOwnBody) {
  const std::string insect = readText("public/creatures/insect.json");
  gl_opt_settings settings;
  gl_opt_defaults(&settings);
  settings.candidates = 2;
  const char* objective = R"({"seconds": 1.5, "speeds": [0.4]})";
  EXPECT_EQ(gl_opt_create_creature(&settings, nullptr, objective, insect.c_str()), nullptr);
  EXPECT_EQ(std::string(gl_last_error()), "kind: 0 is the biped's, and the creature's 3 leg frames make a hexapod");
  settings.kind = GL_KIND_HEXAPOD;
  json bad = json::parse(insect);
  bad["legFrames"][2]["mass"] = -1;
  EXPECT_EQ(gl_opt_create_creature(&settings, nullptr, objective, bad.dump().c_str()), nullptr);
  EXPECT_EQ(std::string(gl_last_error()), "creature: legFrames[2].mass: -1.0 is outside [0.01, 500.0]");

  // A longer-legged insect: its derived gait differs from the shipped insect's (the hexapod's default).
  json tall = json::parse(insect);
  for (json& frame : tall["legFrames"]) frame["legs"]["lower"]["length"] = frame["legs"]["lower"]["length"].get<double>() * 1.3;
  void* search = gl_opt_create_creature(&settings, nullptr, objective, tall.dump().c_str());
  ASSERT_NE(search, nullptr) << gl_last_error();
  void* shipped = gl_opt_create(&settings, nullptr, objective);
  ASSERT_NE(shipped, nullptr) << gl_last_error();
  // Before the first generation the best is the start: the body's own derived gait (the period
  // scales with √ of the leg's length), not the shipped insect's.
  const double period = json::parse(gl_opt_best_json(search))["params"]["period"].get<double>();
  const double shippedPeriod = json::parse(gl_opt_best_json(shipped))["params"]["period"].get<double>();
  EXPECT_NEAR(period / shippedPeriod, std::sqrt((0.22 + 1.3 * 0.22) / 0.44), 1e-9);
  gl_opt_step(search);
  EXPECT_EQ(gl_opt_evaluations(search), 2);
  EXPECT_EQ(json::parse(gl_opt_best_json(search))["character"], "hexapod");
  gl_opt_destroy(search);
  gl_opt_destroy(shipped);

  void* s = gl_sim_create(1, 1);
  EXPECT_EQ(gl_sim_add_apart_creature(s, bad.dump().c_str()), GL_ERR_ARGUMENT);
  const int id = gl_sim_add_apart_creature(s, tall.dump().c_str());
  ASSERT_GE(id, 0) << gl_last_error();
  double info[GL_INFO_FIELDS];
  ASSERT_EQ(gl_sim_character_info(s, info, 1), 1);
  EXPECT_EQ(info[GL_INFO_LEGS], 6.0);
  EXPECT_LT(info[GL_INFO_X], -4.0);  // apart: left of the grid
  gl_sim_destroy(s);
}

// Whatever the legs' length, the derived gait is a valid gait file of the body's kind (the period
// of short legs is held at the schema's shortest), and each kind's default reads back as itself.
TEST(Creature, TheDerivedGaitIsAGaitFileOfItsKind) {
  for (double scale : {0.5, 1.0, 1.6}) {
    json insect = json::parse(readText("public/creatures/insect.json"));
    for (json& frame : insect["legFrames"]) {
      for (const char* part : {"upper", "lower"})
        frame["legs"][part]["length"] = frame["legs"][part]["length"].get<double>() * scale;
    }
    gaitlab::body::Morphology m;
    ASSERT_FALSE(gaitlab::body::parseCreatureFile(insect.dump(), &m)) << scale;
    const std::string text = gaitlab::gait::gaitFileJson(gaitlab::gait::Character::Hexapod, gaitlab::gait::derivedGait(m));
    gaitlab::gait::GaitFile file;
    const auto error = gaitlab::gait::parseGaitFile(text, gaitlab::gait::Character::Hexapod, &file);
    EXPECT_FALSE(error) << scale << ": " << (error ? error->describe() : "");
  }
  for (gaitlab::gait::Character c : gaitlab::gait::kCharacters) {
    gaitlab::gait::GaitFile file;
    const auto error = gaitlab::gait::parseGaitFile(gaitlab::gait::presetText(c), c, &file);
    EXPECT_FALSE(error) << gaitlab::gait::characterName(c) << ": " << (error ? error->describe() : "");
  }
}

// Files of versions 1 and 2 were simulated with every ball joint's range mirrored (physics/
// character.cpp, docs/controller-notes.md §76): they are read mirrored, and walk as they did.
// The shipped biped, written as version 3, is the same body as its version-2 image, its range
// written mirrored as the physics then read it.
TEST(Creature, AFileOfVersionTwoIsReadWithItsHipRangeMirrored) {
  json now = json::parse(readText("public/creatures/biped.json"));
  ASSERT_EQ(now["version"], 3);
  json before = now;
  before["version"] = 2;
  json& hip = before["legFrames"][0]["legs"]["hip"];
  for (int i = 0; i < 3; ++i) {
    const double lower = now["legFrames"][0]["legs"]["hip"]["lower"][i];
    hip["lower"][i] = -now["legFrames"][0]["legs"]["hip"]["upper"][i].get<double>();
    hip["upper"][i] = -lower;
  }
  ASSERT_EQ(hip["lower"][0], -0.7) << "a hip that flexes 2.0 rad, in a file of version 2";
  Morphology fromNow, fromBefore;
  ASSERT_FALSE(parseCreatureFile(now.dump(), &fromNow));
  ASSERT_FALSE(parseCreatureFile(before.dump(), &fromBefore));
  for (size_t i = 0; i < fromNow.segments.size(); ++i) {
    EXPECT_EQ(fromNow.segments[i].joint.lower, fromBefore.segments[i].joint.lower) << fromNow.segments[i].name;
    EXPECT_EQ(fromNow.segments[i].joint.upper, fromBefore.segments[i].joint.upper) << fromNow.segments[i].name;
  }
  // A symmetric range (the quadruped's) reads the same in every version.
  Morphology v1, v3;
  json quadruped = shippedQuadruped();
  ASSERT_FALSE(parseCreatureFile(quadruped.dump(), &v1));
  quadruped["version"] = 3;
  ASSERT_FALSE(parseCreatureFile(quadruped.dump(), &v3));
  for (size_t i = 0; i < v1.segments.size(); ++i) EXPECT_EQ(v1.segments[i].joint.lower, v3.segments[i].joint.lower);
}

TEST(Creature, ABadFileIsRefusedWithTheFieldNamed) {
  EXPECT_EQ(refusal([](json& d) { d["legs"] = 4; }), "legs: unknown field");
  EXPECT_EQ(refusal([](json& d) { d.erase("armature"); }), "armature: missing");
  EXPECT_EQ(refusal([](json& d) { d["format"] = "gaitlab-gait"; }),
            "format: expected \"gaitlab-creature\", got \"gaitlab-gait\"");
  EXPECT_EQ(refusal([](json& d) { d["version"] = 4; }), "version: expected a whole number from 1 to 3, got 4");
  // A third leg segment is a version 2 field, with its hock's range.
  const json tarsus = {{"length", 0.1}, {"halfThickness", 0.02}, {"mass", 0.2}, {"hock", {{"flexion", 2.4}, {"hyperextension", 0.05}}}};
  EXPECT_EQ(refusal([&](json& d) { d["legFrames"][1]["legs"]["tarsus"] = tarsus; }),
            "legFrames[1].legs.tarsus: a third leg segment needs version 2 of the format");
  EXPECT_EQ(refusal([&](json& d) {
              d["version"] = 2;
              d["legFrames"][1]["legs"]["tarsus"] = tarsus;
              d["legFrames"][1]["legs"]["tarsus"].erase("hock");
            }),
            "legFrames[1].legs.tarsus.hock: missing");
  EXPECT_EQ(refusal([&](json& d) {
              d["version"] = 2;
              d["legFrames"][1]["legs"]["tarsus"] = tarsus;
              d["legFrames"][1]["legs"]["tarsus"]["hock"]["hyperextension"] = 2;
            }),
            "legFrames[1].legs.tarsus.hock.hyperextension: 2.0 is outside [0.0, 1.5707963267948966]");
  EXPECT_EQ(refusal([&](json& d) {
              d["version"] = 2;
              d["legFrames"][0]["legs"]["tarsus"] = tarsus;
              d["legFrames"][0]["legs"]["tarsus"]["length"] = 0;
            }),
            "legFrames[0].legs.tarsus.length: 0.0 is outside [0.01, 2.0]");
  EXPECT_EQ(refusal([](json& d) { d["legFrames"][1]["legs"]["upper"]["mass"] = -1; }),
            "legFrames[1].legs.upper.mass: -1.0 is outside [0.01, 500.0]");
  EXPECT_EQ(refusal([](json& d) { d["legFrames"][0]["halfExtents"][2] = "wide"; }),
            "legFrames[0].halfExtents[2]: expected a number, got a string");
  EXPECT_EQ(refusal([](json& d) { d["legFrames"][0]["legs"]["knee"]["points"] = "up"; }),
            "legFrames[0].legs.knee.points: expected \"forward\" or \"backward\", got \"up\"");
  EXPECT_EQ(refusal([](json& d) { d["legFrames"][0]["legs"]["hip"]["lower"][1] = 0.5; }),
            "legFrames[0].legs.hip.lower[1]: above hip.upper[1]");
  EXPECT_EQ(refusal([](json& d) { d["legFrames"][0]["colour"] = "orange"; }),
            "legFrames[0].colour: expected a colour \"#rrggbb\", got \"orange\"");
  EXPECT_EQ(refusal([](json& d) { d["legFrames"][1]["z"] = 0.5; }),
            "legFrames[1].z: leg frames go front to back: expected less than 0.4");
  EXPECT_EQ(refusal([](json& d) { d["spine"] = json::array(); }),
            "spine: expected an array of 1 sections (one between each two leg frames), got an array of 0");
  EXPECT_EQ(refusal([](json& d) { d["spine"][0]["links"] = 0; }),
            "spine[0].links: expected a whole number from 1 to 8, got 0");
  EXPECT_EQ(refusal([](json& d) { d["spine"][0]["from"] = 0.45; }), "spine[0].from: ahead of legFrames[0].z");
  EXPECT_EQ(refusal([](json& d) {
              json frames = json::array();
              for (int i = 0; i < 5; ++i) frames.push_back(d["legFrames"][0]);
              d["legFrames"] = frames;
            }),
            "legFrames: expected an array of 1 to 4 leg frames, got an array of 5");
}

TEST(Creature, TextThatIsNotACreatureFileIsRefused) {
  Morphology m;
  auto error = parseCreatureFile("{\"format\": ", &m);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->field, "");
  EXPECT_NE(error->message.find("not valid JSON"), std::string::npos) << error->message;
  error = parseCreatureFile(std::string(100, '[') + std::string(100, ']'), &m);
  ASSERT_TRUE(error);
  EXPECT_NE(error->message.find("nested deeper"), std::string::npos) << error->message;
  error = loadCreatureFile("/nonexistent/creature.json", &m);
  ASSERT_TRUE(error);
  EXPECT_EQ(error->message, "cannot read /nonexistent/creature.json");
}

}  // namespace
}  // namespace gaitlab::body
