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

TEST_P(ReferenceScenePer, TheMotorsHoldTheStandingPose) {
  // Measured: the quadruped stands on its four legs with every joint within 0.06 rad of the rest
  // pose (the springs sag under gravity), and limp it folds (2.4 rad after 1 s). The biped, held
  // stiff with no balance control, is an inverted pendulum that topples after about 0.35 s (the
  // scene is for timing, not balance); until then its joints stay within 0.006 rad, and limp
  // they have given 0.032 rad by 0.3 s.
  const bool biped = GetParam() == Character::Biped;
  ReferenceScene scene(GetParam(), 4, 1);
  EXPECT_EQ(scene.largestPoseError(), 0.0);
  scene.step(biped ? 36 : 120);
  EXPECT_LT(scene.largestPoseError(), biped ? 0.015 : 0.1);
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
