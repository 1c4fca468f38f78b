// The peer benchmark's reference scene (native/src/peers/reference_scene.h): ragdolls whose motors
// hold the standing pose, stepped deterministically whatever the thread count.
#include "peers/reference_scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "peers/morphology_json.h"

using gaitlab::gait::Character;
using gaitlab::peers::ReferenceScene;

namespace {

class ReferenceScenePer : public testing::TestWithParam<Character> {};

TEST_P(ReferenceScenePer, TheMotorsHoldTheStandingPoseThroughTheTimedWindow) {
  // The peer benchmark times steps 31 to 150 (0.25–1.25 s), so every engine's ragdolls must still
  // stand at 1.25 s. Measured: the quadruped's joints stay within 0.06 rad of the rest pose (the
  // springs sag under gravity); the biped, held stiff with no balance control, is an inverted
  // pendulum on ankle springs weaker than its weight's moment and topples slowly (0.001 rad at
  // 1 s, 0.013 at 2 s, 0.09 at 3 s). With the knee damping of the preset the holding gains came
  // from (15.06 instead of 7.5) its knees oscillated apart from 0.2 s and it lay by 1 s.
  const bool biped = GetParam() == Character::Biped;
  ReferenceScene scene(GetParam(), 4, 1);
  EXPECT_EQ(scene.largestPoseError(), 0.0);
  const double standing = scene.meanRootHeight();
  scene.step(150);
  EXPECT_LT(scene.largestPoseError(), biped ? 0.01 : 0.1);
  EXPECT_NEAR(scene.meanRootHeight(), standing, 0.01);
}

TEST_P(ReferenceScenePer, TheSameSceneStepsToTheSameBitsOnAnyNumberOfThreads) {
  ReferenceScene one(GetParam(), 6, 1, 2), two(GetParam(), 6, 2, 2);
  one.step(60);
  two.step(60);
  EXPECT_EQ(one.hash(), two.hash());
  ReferenceScene again(GetParam(), 6, 1, 2);
  again.step(59);
  EXPECT_NE(again.hash(), one.hash());
}

TEST_P(ReferenceScenePer, TheMorphologyJsonDescribesEverySegmentAndJoint) {
  const auto m = GetParam() == Character::Biped ? gaitlab::body::makeBiped() : gaitlab::body::makeQuadruped();
  const auto j = nlohmann::json::parse(gaitlab::peers::morphologyJson(GetParam()));
  ASSERT_EQ(j["segments"].size(), m.segments.size());
  for (size_t i = 0; i < m.segments.size(); ++i) {
    const auto& s = j["segments"][i];
    EXPECT_EQ(s["parent"], m.segments[i].parent);
    EXPECT_EQ(s["joint"]["axes"].size(), static_cast<size_t>(gaitlab::body::dofCount(m.segments[i].joint.type)));
    if (m.segments[i].parent >= 0) EXPECT_GT(s["motor"]["kp"].get<double>(), 0.0) << m.segments[i].name;
  }
}

INSTANTIATE_TEST_SUITE_P(Characters, ReferenceScenePer, testing::Values(Character::Biped, Character::Quadruped),
                         [](const auto& info) { return info.param == Character::Biped ? "biped" : "quadruped"; });

}  // namespace
