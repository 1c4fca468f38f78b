// The walking criteria of the controller issue, shortened (the full 60 s version is the
// walking benchmark, bench/walking.mjs), and the physics of the stance leg they rest on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "gait/defaults.h"
#include "gait/gait_transition.h"
#include "gait/heading.h"
#include "gait/params_io.h"
#include "sim/simulation.h"
#include "sim/walk_trial.h"

using gaitlab::gait::Character;
using gaitlab::sim::PushDirection;
using gaitlab::sim::runWalk;
using gaitlab::sim::Simulation;
using gaitlab::sim::WalkOptions;

namespace {

struct Case {
  Character character;
  double speed;
};

class Walking : public testing::TestWithParam<Case> {};

std::string caseName(const testing::TestParamInfo<Case>& info) {
  return std::string(info.param.character == Character::Biped ? "biped" : "quadruped") + "_at_" +
         std::to_string(static_cast<int>(std::lround(info.param.speed * 100))) + "cm_s";
}

// One of the quadruped's shipped gait files (public/presets/NAME), read as the CLI reads it.
std::optional<gaitlab::gait::ParamsError> loadQuadrupedPreset(const char* name, gaitlab::gait::GaitFile* out) {
  return gaitlab::gait::loadGaitFile(std::string(GAITLAB_SOURCE_DIR) + "/public/presets/" + name,
                                     gaitlab::gait::Character::Quadruped, out);
}

}  // namespace

// With the shipped preset, on flat ground: no fall, mean speed within ±15 % of the goal, heading
// drift under 10°, every leg's measured duty factor within ±0.1 of its configured value.
TEST_P(Walking, ThePresetMeetsTheWalkingCriteria) {
  WalkOptions o;
  o.character = GetParam().character;
  o.speed = GetParam().speed;
  o.seconds = 20;
  const auto r = runWalk(o);
  ASSERT_FALSE(r.fell) << "fell after " << r.fallTime << " s";
  EXPECT_NEAR(r.meanSpeed, o.speed, 0.15 * o.speed);
  EXPECT_LT(r.headingDrift, 10.0);
  for (size_t l = 0; l < r.dutyMeasured.size(); ++l)
    EXPECT_NEAR(r.dutyMeasured[l], r.dutyConfig[l], 0.1) << "leg " << l;
}

INSTANTIATE_TEST_SUITE_P(Presets, Walking,
                         testing::Values(Case{Character::Biped, 0.5}, Case{Character::Biped, 1.0},
                                         Case{Character::Quadruped, 0.4}, Case{Character::Quadruped, 0.8}),
                         caseName);

// The stance legs' virtual force F_v = K_v (v_d − v) must move the leg frame towards the goal
// velocity (§3.1.4, eq. 3.6). Both feet planted (duty factor at its maximum), a goal of 0.5 m/s
// ahead: the leg frame has to go forwards. Taking the Jacobian transpose with the force at the
// sole, while the stance hip serves the leg frame's orientation, sent it backwards instead, and
// the faster the larger K_v.
TEST(StanceLeg, VelocityForceMovesTheLegFrameForwards) {
  // The same stand with and without F_v, so that what the gait's other terms do with the leg
  // frame (its pitch graph, its height) is the same in both and F_v's own effect is compared.
  const auto advance = [](double velocityGain, double* speed) {
    Simulation sim(1, 1);
    sim.spawn(Character::Biped, 0, 0, 0);
    gaitlab::gait::GaitParams p = sim.controller(0).params();
    for (auto& leg : p.legs) leg.dutyFactor = 1.0;  // clamped to the player's maximum
    p.legFrames[0].velocityGain = velocityGain;
    p.maxAcceleration = 1.6;  // v_d reaches the goal within the 0.5 s (the preset's ramp is gentler)
    sim.controller(0).setParams(p);
    sim.setGoal(0, {0.5, 0.0});
    const double z0 = sim.character(0).segmentState(0).position.z();
    sim.step(60);  // 0.5 s
    const auto s = sim.character(0).segmentState(0);
    *speed = s.linearVelocity.z();
    return s.position.z() - z0;
  };
  double withSpeed = 0, withoutSpeed = 0;
  const double with = advance(300, &withSpeed);
  const double without = advance(0, &withoutSpeed);
  // Measured with the shipped biped: 2.8 cm further in the 0.5 s.
  EXPECT_GT(with - without, 0.02) << "with F_v " << with << " m, without " << without << " m";
  EXPECT_GT(withSpeed - withoutSpeed, 0.1) << "with F_v " << withSpeed << " m/s, without " << withoutSpeed << " m/s";
}

// Whole-body stance (controller.cpp bodyStance, stance_forces.h): with all four feet planted and
// no goal speed the quadruped must stand, and stay nearly still (F_v damps any drift). Before it,
// four legs under hips that served only the leg frames' orientation (§3.1.3) formed a
// parallelogram with no horizontal stiffness, which drifted backwards and folded within 2–3 s.
TEST(BodyStance, TheQuadrupedStandsOnFourFeet) {
  Simulation sim(1, 1);
  sim.spawn(Character::Quadruped, 0, 0, 0);
  // The gains of the §10 trot (a schema-1 file, migrated on load). The shipped trot's leg frames
  // keep only a weak orientation PD (k_p 65 and 10 N·m/rad): its balance is in its foot
  // placement, and with its feet planted it creeps sideways and tips over after 8 s
  // (controller-notes §11).
  gaitlab::gait::GaitFile stand;
  const auto error = gaitlab::gait::loadGaitFile(
      std::string(GAITLAB_SOURCE_DIR) + "/tests/native/fixtures/quadruped-trot-s10.json",
      gaitlab::gait::Character::Quadruped, &stand);
  ASSERT_FALSE(error) << error->describe();
  gaitlab::gait::GaitParams p = stand.gait.primaryParams();
  for (auto& leg : p.legs) leg.dutyFactor = 1.0;  // clamped to the player's maximum
  sim.controller(0).setParams(p);
  sim.setGoal(0, {0.0, 0.0});
  const auto start = sim.character(0).segmentState(0);
  auto lastSecond = start;  // where it was a second before the end
  for (int second = 0; second < 10; ++second) {
    lastSecond = sim.character(0).segmentState(0);
    sim.step(120);
    ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0)) << "fell within " << second + 1 << " s";
  }
  const auto end = sim.character(0).segmentState(0);
  EXPECT_LT((end.position - start.position).norm(), 0.2) << "crept over 10 s";
  // Still: the mean velocity over the last second (m/s). The leg frame trembles on its planted
  // feet (instantaneous speeds 0.01-0.13 m/s, sampled once a second, with the standing hold's
  // integral term and without it), so one sample of it says little.
  EXPECT_LT((end.position - lastSecond.position).norm() / 1.0, 0.05);
  EXPECT_NEAR(end.position.y(), start.position.y(), 0.04);
}

// The stance forces must carry the body towards the goal velocity: all four feet planted and a
// goal of 0.3 m/s ahead, the body has to go forwards (the ground forces are chosen to give the
// whole body F_v, eq. 3.6).
TEST(BodyStance, VelocityForceMovesTheQuadrupedForwards) {
  Simulation sim(1, 1);
  sim.spawn(Character::Quadruped, 0, 0, 0);
  gaitlab::gait::GaitParams p = sim.controller(0).params();
  for (auto& leg : p.legs) leg.dutyFactor = 1.0;
  sim.controller(0).setParams(p);
  sim.setGoal(0, {0.3, 0.0});
  const double z0 = sim.character(0).segmentState(0).position.z();
  sim.step(60);  // 0.5 s
  const auto s = sim.character(0).segmentState(0);
  EXPECT_GT(s.position.z() - z0, 0.02);
  EXPECT_GT(s.linearVelocity.z(), 0.05);
}

// Swing PDs that follow their targets' velocity (gains.swingTargetRate, controller-notes §11):
// with the position-only PD of the thesis the quadruped's swing feet lag their path and strike
// late, so its legs spend less of the cycle in stance than configured; following the path's
// velocity they arrive (nearly) on time.
TEST(SwingLeg, FollowingTheTargetsVelocityKeepsTheDutyFactor) {
  const auto largestShortfall = [](double rate) {
    Simulation sim(1, 1);
    sim.spawn(Character::Quadruped, 0, 0, 0);
    gaitlab::gait::GaitParams p = sim.controller(0).params();
    p.gains.swingTargetRate = rate;
    sim.controller(0).setParams(p);
    sim.setGoal(0, {0.4, 0.0});
    for (int step = 0; step < 10 * 120 && !gaitlab::sim::hasFallen(sim, 0); ++step) sim.step(1);
    const auto& player = sim.controller(0).player();
    EXPECT_GT(player.leg(0).touchDowns, 10) << "rate " << rate;
    double shortfall = 0;
    for (int l = 0; l < player.legCount(); ++l)
      shortfall = std::max(shortfall, player.schedule(l).dutyFactor - player.measuredDutyFactor(l));
    return shortfall;
  };
  EXPECT_LT(largestShortfall(1.0), 0.1);
  EXPECT_GT(largestShortfall(0.0), 0.15);
}

// The quadruped's second gait, a lateral-sequence walk (public/presets/quadruped-walk.json): it
// walks on its own, and a quadruped switches from it to the trot and back in mid-stride (new
// parameters at any phase; the gait phase moves to the new footfall pattern, gait_transition.h)
// without falling.
TEST(QuadrupedGaits, TheWalkWalksAndSwitchesWithTheTrot) {
  gaitlab::gait::GaitFile walk;
  const auto error = loadQuadrupedPreset("quadruped-walk.json", &walk);
  ASSERT_FALSE(error) << error->describe();
  WalkOptions o;
  o.character = Character::Quadruped;
  const gaitlab::gait::Gait gait = walk.gait;
  o.gait = &gait;
  o.speed = 0.3;
  o.seconds = 20;
  const auto r = runWalk(o);
  ASSERT_FALSE(r.fell) << "the walk fell after " << r.fallTime << " s";
  EXPECT_NEAR(r.meanSpeed, o.speed, 0.15 * o.speed);

  gaitlab::gait::GaitFile trotFile;
  const auto trotError = loadQuadrupedPreset("quadruped-trot.json", &trotFile);
  ASSERT_FALSE(trotError) << trotError->describe();
  const gaitlab::gait::GaitParams trot = trotFile.gait.primaryParams();
  Simulation sim(1, 1);
  sim.spawn(Character::Quadruped, 0, 0, 0);
  double z = sim.character(0).segmentState(0).position.z();
  for (int part = 0; part < 4; ++part) {
    const bool walking = part % 2 == 0;
    sim.controller(0).setParams(walking ? walk.gait.primaryParams() : trot);
    sim.setGoal(0, {walking ? 0.3 : 0.6, 0.0});
    for (int step = 0; step < 5 * 120; ++step) {
      sim.step(1);
      ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0)) << "fell " << step / 120.0 << " s into part " << part;
    }
    const double now = sim.character(0).segmentState(0).position.z();
    EXPECT_GT(now - z, walking ? 0.8 : 2.0) << "part " << part << " of the run";
    z = now;
  }
}

namespace {
// How long each goal is held (s, arbitrary) in the tests that change the goal back and forth
// between two speeds, as the walking benchmark's transition trial does at random.
constexpr double kGoalHolds[] = {2.3, 1.1, 3.7, 1.9, 2.9, 1.4, 3.2, 2.6, 1.7, 3.9};
}  // namespace

// The quadruped preset chooses its gait by speed (gait/gait_transition.h): the walk below 0.3 m/s,
// the trot above. The goal changes between 0.2 and 0.6 m/s every 1 to 4 s, so the gait changes at
// whatever phase the stride is in: it never falls, and walks with the walk's footfall pattern at
// 0.2 m/s and the trot's at 0.6. (The walking benchmark's transition trial does 20 such runs per
// pair of speeds; without the phase shift at the change, 5 of 20 runs between standing and the
// trot fell there.)
TEST(QuadrupedGaits, ThePresetChangesBetweenWalkAndTrotBySpeedInMidStride) {
  gaitlab::gait::GaitFile walk;
  const auto error = loadQuadrupedPreset("quadruped-walk.json", &walk);
  ASSERT_FALSE(error) << error->describe();
  const auto& walkLegs = walk.gait.primaryParams().legs;
  const auto& trotLegs = gaitlab::gait::defaultParams(Character::Quadruped).legs;  // the 0.8 m/s key
  ASSERT_TRUE(gaitlab::gait::footfallDiffers(walkLegs, trotLegs, 4));
  for (double startPhase : {0.0, 0.37, 0.71}) {
    Simulation sim(1, 1);
    sim.spawn(Character::Quadruped, 0, 0, 0);
    sim.controller(0).setPhase(startPhase);
    double walked = 0;
    for (int part = 0; part < 10; ++part) {
      const bool walking = part % 2 == 0;
      sim.setGoal(0, {walking ? 0.2 : 0.6, 0.0});
      const double z = sim.character(0).segmentState(0).position.z();
      const int steps = static_cast<int>(kGoalHolds[part] * 120);
      for (int step = 0; step < steps; ++step) {
        sim.step(1);
        ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0))
            << "start phase " << startPhase << ": fell " << step / 120.0 << " s into part " << part;
      }
      walked += sim.character(0).segmentState(0).position.z() - z;
      const auto& legs = sim.controller(0).params().legs;
      EXPECT_FALSE(gaitlab::gait::footfallDiffers(legs, walking ? walkLegs : trotLegs, 4))
          << "start phase " << startPhase << ", part " << part << ": not the " << (walking ? "walk" : "trot");
    }
    EXPECT_GT(walked, 8.0) << "start phase " << startPhase;  // 27 s at 0.2 and 0.6 m/s, ramps between
  }
}

// The pace (public/presets/quadruped-pace.json): the lateral pairs lift together (front left with
// back left, front right with back right, each pair within 0.15 of a cycle), and it walks 0.4 and
// 0.8 m/s within ±15 % (the walking benchmark: every goal from 0.4 to 1.3 m/s within ±10 %).
TEST(QuadrupedGaits, ThePaceWalks) {
  gaitlab::gait::GaitFile pace;
  const auto error = loadQuadrupedPreset("quadruped-pace.json", &pace);
  ASSERT_FALSE(error) << error->describe();
  const auto& legs = pace.gait.primaryParams().legs;  // front left, front right, back left, back right
  EXPECT_LT(std::abs(std::remainder(legs[0].stepTrigger - legs[2].stepTrigger, 1.0)), 0.15);
  EXPECT_LT(std::abs(std::remainder(legs[1].stepTrigger - legs[3].stepTrigger, 1.0)), 0.15);
  WalkOptions o;
  o.character = Character::Quadruped;
  o.gait = &pace.gait;
  o.seconds = 20;
  for (double speed : {0.4, 0.8}) {
    o.speed = speed;
    const auto r = runWalk(o);
    ASSERT_FALSE(r.fell) << speed << " m/s: the pace fell after " << r.fallTime << " s";
    EXPECT_NEAR(r.meanSpeed, speed, 0.15 * speed);
    EXPECT_LT(r.headingDrift, 10.0);
  }
}

// A gait pinned in the demo's gait menu (walk, trot, pace) is set while the character walks, at
// whatever phase its stride is in; one of another footfall pattern is taken up where the gait
// cycle starts again. Before that (the parameters still the old gait's, the gait player's phase
// not yet wrapped) nothing changes; at the wrap the new pattern is in effect, within one period.
TEST(QuadrupedGaits, AGaitOfAnotherPatternSetWhileWalkingWaitsForTheCycleStart) {
  gaitlab::gait::GaitFile walk;
  const auto error = loadQuadrupedPreset("quadruped-walk.json", &walk);
  ASSERT_FALSE(error) << error->describe();
  const auto& walkLegs = walk.gait.primaryParams().legs;
  Simulation sim(1, 1);
  sim.spawn(Character::Quadruped, 0, 0, 0);
  sim.setGoal(0, {0.4, 0.0});
  for (int step = 0; step < 240; ++step) sim.step(1);
  auto& controller = sim.controller(0);
  while (controller.player().phase() < 0.3 || controller.player().phase() > 0.4) sim.step(1);
  ASSERT_TRUE(gaitlab::gait::footfallDiffers(controller.params().legs, walkLegs, 4));
  const double period = controller.player().period();
  const int changes = controller.gaitChanges();  // the preset's own, starting from rest
  controller.setGait(walk.gait);
  EXPECT_EQ(controller.gaitChanges(), changes);
  int steps = 0;
  double phase = controller.player().phase();
  for (;;) {
    sim.step(1);
    ++steps;
    if (!gaitlab::gait::footfallDiffers(controller.params().legs, walkLegs, 4)) break;
    const double now = controller.player().phase();
    ASSERT_GE(now, phase) << "the phase wrapped " << steps << " steps after the gait was set, still the trot";
    phase = now;
    ASSERT_LT(steps * gaitlab::physics::kFixedStep, period) << "not the walk after a whole period";
  }
  EXPECT_EQ(controller.gaitChanges(), changes + 1);
  EXPECT_GT(steps * gaitlab::physics::kFixedStep, 0.5 * period);  // set at 0.3–0.4 of the cycle
}

// The same at every phase: from the walk and from the pace to the trot, and from the pace and the
// trot to the walk, at the demo's quadruped speed (0.4 m/s), 32 switches each at phases spread
// over the cycle: none falls in the 5 s after. (Taken up at once, at whatever phase, 3 of 50 such
// switches from the pace to the trot fell and 6 of 50 from the pace to the walk with the gaits of
// before, 1–2 s later, rolling over sideways: the demo page's gait-switch test failed now and
// then; with the shipped gaits 5 of 50 from the trot to the walk, and this test fails, at trot
// phase 0.28; controller-notes §22.)
TEST(QuadrupedGaits, APinnedGaitIsTakenUpFromAnyPhaseWithoutAFall) {
  gaitlab::gait::GaitFile walk, pace, trot;
  for (auto [name, file] : {std::pair{"quadruped-walk.json", &walk}, std::pair{"quadruped-pace.json", &pace},
                            std::pair{"quadruped-trot.json", &trot}}) {
    const auto error = loadQuadrupedPreset(name, file);
    ASSERT_FALSE(error) << name << ": " << error->describe();
  }
  constexpr int kSwitches = 32;
  const std::pair<const gaitlab::gait::GaitFile*, const gaitlab::gait::GaitFile*> pairs[] = {
      {&walk, &trot}, {&pace, &trot}, {&pace, &walk}, {&trot, &walk}};
  const auto name = [&](const gaitlab::gait::GaitFile* f) { return f == &walk ? "walk" : f == &pace ? "pace" : "trot"; };
  for (const auto& [from, to] : pairs) {
    for (int i = 0; i < kSwitches; ++i) {
      Simulation sim(1, 1);
      sim.spawn(Character::Quadruped, 0, 0, 0);
      sim.controller(0).setGait(from->gait);
      sim.setGoal(0, {0.4, 0.0});
      // 2 s and then 5 steps more each time: over 160 steps, 5 coprime to the cycles of the trot
      // (36 steps), the pace (38) and the walk (79), so 32 different phases of each.
      const int before = 240 + 5 * i;
      for (int step = 0; step < before; ++step) sim.step(1);
      ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0)) << "the " << name(from) << " fell before the switch";
      const double phase = sim.controller(0).player().phase();
      sim.controller(0).setGait(to->gait);
      for (int step = 0; step < 5 * 120; ++step) {
        sim.step(1);
        ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0))
            << name(from) << " to " << name(to) << " set at phase " << phase << ": fell " << step / 120.0
            << " s after";
      }
    }
  }
}

// The walking benchmark's speed-range criteria, shortened (bench/walking.mjs: the sweep, the ramp
// and the push ladder). Goal 0: both characters stand on planted feet (gait/standing.cpp), the
// biped balancing on its ankles, the quadruped as a table; stepping in place, before, they
// crept 0.4 m (biped) and 0.7 m (quadruped) in 20 s without the controller's standing hold.
TEST(SpeedRange, BothCharactersHoldTheirSpotAtGoalZero) {
  for (Character c : {Character::Biped, Character::Quadruped}) {
    WalkOptions o;
    o.character = c;
    o.speed = 0.0;
    o.seconds = 20;
    const auto r = runWalk(o);
    ASSERT_FALSE(r.fell) << characterName(c) << " fell after " << r.fallTime << " s";
    EXPECT_LT(r.meanSpeed, 0.05) << characterName(c);
    EXPECT_LT(r.positionDrift, 0.1) << characterName(c);  // over the second half; measured 0.02-0.03 m
    // After walking: up to 1 m/s and back to 0, then 14 s at goal 0. Each comes to a stand on
    // planted feet (gait/standing.cpp) a little beyond where the goal reached 0 (measured: the
    // biped 0.16 m, its stopping distance from the ramp's last speeds; the quadruped 0.053 m,
    // within the walking benchmark's 0.1 m) and does not move once it stands (measured 0.000 m
    // over the last 8 s, both). How long the last steps take varies from stop to stop: of 40
    // such ramps ending at 13–22.75 s, one biped's moved more than 1 cm in its last 10 s, with the
    // speed trim's error bound and without (controller-notes §50); this one stands from 4.4 s
    // after the goal reached 0.
    o.speedSchedule = {{0.0, 0.0}, {8.0, 1.0}, {16.0, 0.0}};
    o.seconds = 30;
    o.driftWindow = 14;
    const auto stopped = runWalk(o);
    ASSERT_FALSE(stopped.fell) << characterName(c) << " fell after " << stopped.fallTime << " s";
    EXPECT_LT(stopped.positionDrift, c == Character::Quadruped ? 0.1 : 0.25) << characterName(c) << ": stopping distance";
    EXPECT_GT(stopped.standingFraction, 0.3) << characterName(c) << ": it stands from about 17 s of 30";
    o.driftWindow = 8;
    EXPECT_LT(runWalk(o).positionDrift, 0.01) << characterName(c) << ": standing, it does not move";
  }
}

namespace {

// Standing on planted feet (gait/standing.cpp), as the locomotion criteria ask of each character:
// at goal 0 it stops stepping and stands, not moving, every foot down; pushed at the criteria's
// standing impulse (held 0.2 s, three or four 4 s apart, over ten draws of their phases), it
// steps to recover and stands again; given a goal, it walks off. `atLeast`: runs of the ten that
// must not fall, lateral / forward / backward; `standsBetween`: the least share of a pushed run
// spent standing.
struct StandingCase {
  Character character;
  double impulse;  // N·s
  int atLeast[3];
  double standsBetween;
  double walkOff, walkOffTolerance;  // m/s
};

void expectStandsAndStepsOnlyToRecover(const StandingCase& k) {
  const char* who = characterName(k.character);
  WalkOptions o;
  o.character = k.character;
  o.speed = 0.0;
  o.seconds = 20;
  const auto quiet = runWalk(o);
  ASSERT_FALSE(quiet.fell) << who;
  EXPECT_GT(quiet.standingFraction, 0.9) << who;
  EXPECT_LT(quiet.positionDrift, 0.01) << who;
  for (size_t l = 0; l < quiet.dutyMeasured.size(); ++l)
    EXPECT_GT(quiet.dutyMeasured[l], 0.95) << who << ": leg " << l << " down";

  const std::tuple<PushDirection, const char*> directions[3] = {
      {PushDirection::Lateral, "lateral"}, {PushDirection::Forward, "forward"}, {PushDirection::Backward, "backward"}};
  for (int d = 0; d < 3; ++d) {
    const auto& [direction, name] = directions[d];
    int upright = 0;
    for (unsigned seed = 1; seed <= 10; ++seed) {
      WalkOptions pushed = o;
      pushed.seconds = 14;
      pushed.pushImpulse = k.impulse;
      pushed.pushDuration = 0.2;
      pushed.pushEvery = 4;
      pushed.seed = seed;
      pushed.pushDirection = direction;
      const auto r = runWalk(pushed);
      if (r.fell) continue;
      ++upright;
      EXPECT_GE(r.pushesSurvived, 3) << who << ", " << name << ", seed " << seed;  // a fourth may end the run
      EXPECT_GT(r.standingFraction, k.standsBetween) << who << ", " << name << ", seed " << seed
                                                     << ": it stands again between pushes";
    }
    EXPECT_GE(upright, k.atLeast[d]) << who << ", " << name << ": runs of 10 without a fall";
  }

  WalkOptions start = o;
  start.speedSchedule = {{0.0, 0.0}, {5.0, 0.0}, {5.01, k.walkOff}};
  start.seconds = 15;
  const auto walked = runWalk(start);
  ASSERT_FALSE(walked.fell) << who;
  EXPECT_GT(walked.standingFraction, 0.2) << who << ": it stood for the first 5 s";
  EXPECT_NEAR(walked.meanSpeed, k.walkOff, k.walkOffTolerance) << who << ": then walked off (mean over the second half)";
}

}  // namespace

// The biped balances on its ankles (the IK pose over its feet). Measured: standing 94 % of 20 s
// (from 0.5 s in), 0.0001 m moved; pushes of 60 N·s survived from every side in all ten draws;
// 1.01 m/s over the 10 s after a step of the goal to 1 m/s.
TEST(Standing, TheBipedStandsOnPlantedFeetAndStepsOnlyToRecover) {
  expectStandsAndStepsOnlyToRecover({Character::Biped, 60, {10, 10, 10}, 0.03, 1.0, 0.1});
}

// The quadruped stands as a table: every leg joint holds the pose it came to rest in, the weight
// fed forward through the legs, and it steps only once the capture point nears the edge of its
// feet. Measured: standing 97 % of 20 s, 0.001 m moved, every foot down 98 % of the time; pushes
// of 30 N·s (the criteria's standing push for the dog) survived from the front and the back in
// all ten draws, from the side in 9 (the walking benchmark's ladder has the rest); standing
// 50-81 % of each run; 0.40 m/s after a step of the goal to 0.4 m/s. Stepping in place, before,
// it fell in 8 of the 10 runs pushed from the side.
TEST(Standing, TheQuadrupedStandsAsATableAndStepsOnlyToRecover) {
  expectStandsAndStepsOnlyToRecover({Character::Quadruped, 30, {9, 10, 10}, 0.3, 0.4, 0.04});
}

// The goal ramps up to 1.3 m/s and back to 0: no fall, and the speed follows the goal.
TEST(SpeedRange, TheBipedFollowsARampUpAndDown) {
  WalkOptions o;
  o.character = Character::Biped;
  o.speedSchedule = {{0.0, 0.0}, {8.0, 1.3}, {16.0, 0.0}};
  o.seconds = 20;
  o.driftWindow = 2;  // from 18 s, 2 s after the goal reached 0
  const auto r = runWalk(o);
  ASSERT_FALSE(r.fell) << "fell after " << r.fallTime << " s";
  ASSERT_GT(r.trackingSamples, 40);
  // Within ±10 % of the goal at a lag of up to 1 s: measured 123 of 123 (the push-robust preset,
  // and the one before it). At exactly 1 s (the stricter reading) the preset before it met 72 of
  // 123, and this one, which follows the goal more closely, 11.
  EXPECT_GE(r.trackingWithin, r.trackingSamples * 9 / 10);
  EXPECT_LT(r.positionDrift, 0.2);                         // stopped: measured 0.05 m in 2 s
}

// The top of each preset's range (bench/walking.mjs's sweep, shortened): the biped runs at
// 2.5 m/s with both feet off the ground between steps (2.51 m/s measured), the quadruped trots
// at 2.1 and 2.5 m/s within 10 % of the goal (its 2.1 m/s key searched with speed tracking on:
// controller-notes §31).
TEST(SpeedRange, TheBipedRunsAndTheQuadrupedTrotsAtTheTopOfTheirRange) {
  WalkOptions o;
  o.character = Character::Biped;
  o.speed = 2.5;
  o.seconds = 20;
  const auto run = runWalk(o);
  ASSERT_FALSE(run.fell) << "the run fell after " << run.fallTime << " s";
  EXPECT_NEAR(run.meanSpeed, 2.5, 0.1 * 2.5);
  // Both feet off the ground 8.6 % of the time (at 1.0 m/s the walk's quick steps leave the
  // ground for 4.2 %: controller-notes §18).
  EXPECT_GT(run.flightFraction, 0.06);
  o.character = Character::Quadruped;
  for (const double goal : {2.1, 2.5}) {
    o.speed = goal;
    const auto trot = runWalk(o);
    ASSERT_FALSE(trot.fell) << "the trot at " << goal << " m/s fell after " << trot.fallTime << " s";
    // Over 20 s from rest (the start counts): 2.05 and 2.42 m/s measured (2.36 at 2.5 before the
    // 2.7 m/s key's speed trim was bounded and integrated, controller-notes §57; 2.44 before the
    // 2.1 m/s key was moved towards its neighbours, §55).
    EXPECT_NEAR(trot.meanSpeed, goal, 0.1 * goal) << "goal " << goal;
  }
}

// Above the trot the quadruped canters (the walking benchmark's skills row, shortened): at 3.5 and
// 3.6 m/s its preset's canter keys, the feet striking one after another with all four off the
// ground for a while each stride, within 10 % of the goal (its fastest key sits near the speed it
// runs, with speed tracking making up the rest: controller-notes §49, §54); and from 3.2 m/s,
// where its 3.2 m/s key, searched for speed, runs near its goal (§67; 2.60 and 2.98 m/s at goals
// of 3.2 and 3.4 with the key before it). Over 30 s from rest (the second half's mean):
// 3.12, 3.28, 3.26 and 3.34 m/s, flight 4 %, 9 %, 14 % and 15 % (the skills row asks for 2 %).
TEST(SpeedRange, TheQuadrupedCantersAtTheTopOfItsRange) {
  WalkOptions o;
  o.character = Character::Quadruped;
  o.seconds = 30;
  for (const double goal : {3.2, 3.4, 3.5, 3.6}) {
    o.speed = goal;
    const auto canter = runWalk(o);
    ASSERT_FALSE(canter.fell) << "the canter at " << goal << " m/s fell after " << canter.fallTime << " s";
    EXPECT_EQ(canter.footfall, gaitlab::gait::Footfall::Canter) << "goal " << goal;
    EXPECT_GT(canter.flightFraction, 0.02) << "goal " << goal;
    EXPECT_NEAR(canter.meanSpeed, goal, 0.1 * goal) << "goal " << goal;
  }
}

// Turning at a canter (controller-notes §59–§60): told to turn, the body yaws at once, but its
// velocity turns only as fast as its stance feet push it round, and the canter, mostly on one
// foot, slid out of the turn until it rolled over. Three per-key parameters carry it round:
// - maxTurnSlip (0.25 m/s on the canter's keys) bounds how far the turn's heading may lead the
//   path, asin(0.25 / v); while turning the heading never leads it by more. With no bound, as
//   before schema 10, half of these walks fall (measured: both right turns).
// - turnPlacement (0.6) lands the feet outside the turn, where the ground force that carries the
//   body round passes through its centre of mass. At 3.5 m/s, told ±0.3 rad/s, it turns at
//   0.20–0.27 rad/s (measured); with the feet placed as if going straight, as before schema 11,
//   at 0.03–0.12.
// - turnRollMoment (2.0) leaves the roll moment of the turn's sideways force to the whole-body
//   stance rather than cancelling it with feet near the midline: the turns above run at 0.26–0.30
//   rad/s, within the walking criteria's ±20 % (measured); with the moment cancelled, as before
//   schema 12, at 0.22–0.27, 0.016–0.048 more slowly each.
TEST(Turning, TheCanterTurnsNearItsGoalWithItsHeadingNearItsPathAndItsFeetOutsideTheTurn) {
  const auto walk = [](const gaitlab::gait::Gait& gait, double turn, double phase, double* largestExcess,
                       double seconds = 30) {
    WalkOptions o;
    o.character = Character::Quadruped;
    o.gait = &gait;
    o.speed = 3.5;
    o.turnRate = turn;
    o.seconds = seconds;
    o.startPhase = phase;
    if (largestExcess) {
      o.observe = [&](const Simulation& sim) {
        const gaitlab::physics::Character& ch = sim.character(0);
        const gaitlab::body::Morphology& m = ch.morphology();
        Eigen::Vector3d v = Eigen::Vector3d::Zero();
        double mass = 0;
        for (size_t i = 0; i < m.segments.size(); ++i) {
          v += m.segments[i].mass * ch.segmentState(static_cast<int>(i)).linearVelocity;
          mass += m.segments[i].mass;
        }
        v /= mass;
        const double speed = std::hypot(v.x(), v.z());
        const double slip = sim.controller(0).params().maxTurnSlip;
        if (speed <= slip + 0.2) return;  // the bound is asin(slip / v): meaningless near v = slip
        const double lead = gaitlab::gait::wrapAngle(sim.controller(0).desiredHeading() - std::atan2(v.x(), v.z()));
        if (lead * turn > 0) *largestExcess = std::max(*largestExcess, std::abs(lead) - std::asin(slip / speed));
      };
    }
    return runWalk(o);
  };
  const gaitlab::gait::Gait shipped = gaitlab::gait::defaultGait(Character::Quadruped);
  gaitlab::gait::Gait unbounded = shipped;
  for (gaitlab::gait::SpeedKey& k : unbounded.keys) k.params.maxTurnSlip = gaitlab::gait::kNoTurnSlipBound;
  gaitlab::gait::Gait straightFeet = shipped;
  for (gaitlab::gait::SpeedKey& k : straightFeet.keys) k.params.turnPlacement = 0;
  gaitlab::gait::Gait rollCancelled = shipped;
  for (gaitlab::gait::SpeedKey& k : rollCancelled.keys) k.params.turnRollMoment = 0;
  for (const double turn : {0.3, -0.3}) {
    for (const double phase : {0.0, 0.5}) {
      double excess = 0;
      const auto r = walk(shipped, turn, phase, &excess);
      EXPECT_FALSE(r.fell) << "turn " << turn << ", phase " << phase << ": fell after " << r.fallTime << " s";
      // It turns the way it is told, within the walking criteria's 20 % and not faster.
      EXPECT_GT(r.yawRate / turn, 0.8) << "turn " << turn << ", phase " << phase << ": yaw " << r.yawRate;
      EXPECT_LT(r.yawRate / turn, 1.05) << "turn " << turn << ", phase " << phase << ": yaw " << r.yawRate;
      // One fixed step of the body's velocity changing after the bound was applied.
      EXPECT_LT(excess, 0.05) << "turn " << turn << ", phase " << phase;
      // The feet outside the turn are what turns it: placed as if going straight, it turns at
      // least 0.08 rad/s more slowly (or falls).
      const auto straight = walk(straightFeet, turn, phase, nullptr);
      if (!straight.fell)
        EXPECT_GT(std::abs(r.yawRate), std::abs(straight.yawRate) + 0.08)
            << "turn " << turn << ", phase " << phase << ": yaw " << r.yawRate << " against " << straight.yawRate;
      // And the roll moment left to the stance: cancelled, it turns more slowly.
      const auto cancelled = walk(rollCancelled, turn, phase, nullptr);
      if (!cancelled.fell)
        EXPECT_GT(std::abs(r.yawRate), std::abs(cancelled.yawRate) + 0.01)
            << "turn " << turn << ", phase " << phase << ": yaw " << r.yawRate << " against " << cancelled.yawRate;
    }
  }
  // Without the bound on the heading's lead it falls: over a minute from 8 start phases each way,
  // 10 of 16 (the shipped gait, none).
  int unboundedFalls = 0;
  for (const double turn : {0.3, -0.3})
    for (int i = 0; i < 8; ++i) unboundedFalls += walk(unbounded, turn, (i + 0.5) / 8, nullptr, 60).fell ? 1 : 0;
  EXPECT_GE(unboundedFalls, 6);
}

// Speed tracking's trim belongs to the gait it was integrated under (controller-notes §50): the
// canter at 3.6 m/s needs about 1.4 m/s of it; when the goal drops to 2.2 m/s and the gait changes
// to the trot, the trim starts again from zero instead of asking the trot for that much more.
TEST(SpeedTracking, TheTrimStartsAgainFromZeroAtAChangeOfGait) {
  Simulation sim(1, 1);
  sim.spawn(Character::Quadruped, 0, 0, 0);
  sim.setGoal(0, {3.6, 0.0});
  sim.step(20 * 120);
  ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0));
  const auto& canter = sim.controller(0);
  EXPECT_GT(canter.speedTrim(), 0.5) << "the canter's trim";
  const int changes = canter.gaitChanges();
  sim.setGoal(0, {2.2, 0.0});
  int step = 0;
  for (; step < 3 * 120 && sim.controller(0).gaitChanges() == changes; ++step) sim.step(1);
  ASSERT_GT(sim.controller(0).gaitChanges(), changes) << "no change to the trot within 3 s";
  // The change is taken after the step's integration, so the trim reads zero (allowed: 0.01).
  EXPECT_LT(std::abs(sim.controller(0).speedTrim()), 0.01) << "the trot's trim, " << step / 120.0 << " s after the goal dropped";
}

// A change of gait made while the desired speed holds the goal (here the walking benchmark's slow
// climb, 0 → 3.5 m/s in 30 s, slower than any key's maxAcceleration) starts the new gait's trim at
// the body's lag behind the goal then, within its key's bound (controller-notes §72). Measured: the
// trim starts at 0.29–0.31 m/s entering the canter, and the whole ramp 0 → 3.5 → 0 m/s keeps 540 of
// its 549 samples within ±10 % of the goal (510 with the trim started from zero).
TEST(SpeedTracking, AChangeOfGaitAtAHeldGoalStartsTheTrimAtTheBodysLag) {
  Simulation sim(1, 1);
  sim.spawn(Character::Quadruped, 0, 0, 0);
  int changes = sim.controller(0).gaitChanges();
  int checked = 0;
  for (int step = 0; step < 30 * 120; ++step) {
    const double goal = 3.5 * step / (30.0 * 120);
    sim.setGoal(0, {goal, 0.0});
    const auto& c = sim.controller(0);
    sim.step(1);
    if (c.gaitChanges() == changes) continue;
    changes = c.gaitChanges();
    if (c.params().transitionPhase == 0.0) continue;  // into the walk or the trot: lags of a few cm/s
    ++checked;
    // Into the canter: the trot lags the goal by about 0.3 m/s there.
    EXPECT_GT(c.speedTrim(), 0.15) << "the canter's trim at " << step / 120.0 << " s (v_d " << c.desiredVelocity().z() << ")";
    EXPECT_LE(c.speedTrim(), c.params().maxSpeedTrim + 0.01);
  }
  ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0));
  EXPECT_EQ(checked, 1) << "changes into the canter on the climb";

  WalkOptions o;
  o.character = Character::Quadruped;
  o.speedSchedule = {{0.0, 0.0}, {30.0, 3.5}, {60.0, 0.0}};
  o.seconds = 80;
  const auto ramp = runWalk(o);
  ASSERT_FALSE(ramp.fell);
  // 549 as shipped; 540 with half the trot's 2.7 m/s key's speedIntegralGain, whose trim wound
  // up too slowly after the canter (controller-notes §73); 510 with the trim started from zero.
  EXPECT_GE(ramp.trackingWithin, 545) << "of " << ramp.trackingSamples;
}

// Where the canter is left for the trot: where the gait phase reaches its keys' transitionPhase
// (0.45 of the cycle, its leading front foot just lifted off and only the leading hind foot down),
// not where the cycle starts (controller-notes §52).
TEST(QuadrupedGaits, TheCanterIsLeftWhereItsKeysSay) {
  const gaitlab::gait::Gait& preset = gaitlab::gait::defaultGait(Character::Quadruped);
  const double leaveAt = preset.keys.back().params.transitionPhase;
  ASSERT_GT(leaveAt, 0.0) << "the canter's keys leave it where the cycle starts";
  Simulation sim(1, 1);
  sim.spawn(Character::Quadruped, 0, 0, 0);
  sim.setGoal(0, {3.6, 0.0});
  sim.step(10 * 120);
  ASSERT_FALSE(gaitlab::sim::hasFallen(sim, 0));
  ASSERT_EQ(sim.controller(0).params().transitionPhase, leaveAt) << "not in the canter's keys";
  const int changes = sim.controller(0).gaitChanges();
  sim.setGoal(0, {2.2, 0.0});
  double before = 0;
  for (int step = 0; step < 3 * 120 && sim.controller(0).gaitChanges() == changes; ++step) {
    before = sim.controller(0).player().phase();
    sim.step(1);
  }
  ASSERT_GT(sim.controller(0).gaitChanges(), changes) << "no change to the trot within 3 s";
  // Taken in the step whose phase passed leaveAt: one step (1/120 s of a 0.3 s cycle) before it.
  EXPECT_LT(before, leaveAt);
  EXPECT_GE(before, leaveAt - (1.0 / 120) / preset.keys.back().params.period - 1e-9);
  EXPECT_EQ(sim.controller(0).params().transitionPhase, 0.0) << "the trot's keys leave it where the cycle starts";
}

// Changes back and forth between the trot and the canter, as the walking benchmark's 2.2 ↔ 3.5 m/s
// trial makes them: the goal changes 9 times, held 1.1 to 3.9 s, from 12 start phases. Measured:
// none of 12 runs falls (1 before the canter's keys were rearranged for these changes and the
// trot's bridge key slowed, §54; still none with the trot's 2.1 and 2.8 m/s keys moved, §55,
// §56); 5 with the canter left where its cycle starts, 9 before speed tracking's trim was reset at
// a change of gait and its error bounded (controller-notes §50, §52).
TEST(QuadrupedGaits, ChangesBetweenTrotAndCanterFallInAtMostOneRunInSix) {
  WalkOptions o;
  o.character = Character::Quadruped;
  double t = 0;
  for (int part = 0; part < 10; ++part) {
    const double goal = part % 2 == 0 ? 2.2 : 3.5;
    o.speedSchedule.push_back({t, goal});
    o.speedSchedule.push_back({t + kGoalHolds[part] - 0.001, goal});
    t += kGoalHolds[part];
  }
  o.seconds = t;
  int falls = 0, changes = 0;
  for (int k = 0; k < 12; ++k) {
    o.startPhase = k / 12.0;
    const auto r = runWalk(o);
    falls += r.fell ? 1 : 0;
    changes += r.gaitChanges;
  }
  EXPECT_LE(falls, 2) << "of 12 runs";
  EXPECT_GT(changes, 60) << "changes of gait made";  // measured 122: it does change, back and forth
}

namespace {
// The biped for 14 s at goal `speed`, pushed every 2.5 s (seed 7), as the push ladder pushes.
gaitlab::sim::WalkResult pushedBiped(gaitlab::sim::PushDirection direction, double speed, double impulse,
                                     double duration) {
  WalkOptions o;
  o.character = Character::Biped;
  o.speed = speed;
  o.pushImpulse = impulse;
  o.pushDuration = duration;
  o.pushEvery = 2.5;
  o.pushDirection = direction;
  o.seed = 7;
  o.seconds = 14;
  return runWalk(o);
}
}  // namespace

// Standing (goal 0), pushed forwards and backwards at 20 N·s: it steps to recover every time.
TEST(SpeedRange, TheBipedRecoversFromPushesAtGoalZero) {
  for (const auto direction : {gaitlab::sim::PushDirection::Forward, gaitlab::sim::PushDirection::Backward}) {
    const auto r = pushedBiped(direction, 0.0, 20, 0.0);
    EXPECT_FALSE(r.fell) << "fell after " << r.fallTime << " s";
    EXPECT_EQ(r.pushesSurvived, r.pushesApplied);
    EXPECT_GE(r.pushesApplied, 4);
  }
}

// The locomotion criteria's pushes, shortened (the walking benchmark's ladder has 20 per rung):
// the biped walking at 0.5 m/s and standing takes pushes of 60 N·s held 0.2 s, as SIMBICON's
// are (Yin et al. 2007: 350 N for 0.2 s), from the side, the front and the back.
TEST(SpeedRange, TheBipedTakesSixtyNewtonSecondPushesFromEverySide) {
  using gaitlab::sim::PushDirection;
  for (const auto direction : {PushDirection::Lateral, PushDirection::Forward, PushDirection::Backward}) {
    for (const double speed : {0.5, 0.0}) {
      const auto r = pushedBiped(direction, speed, 60, 0.2);
      EXPECT_FALSE(r.fell) << "direction " << static_cast<int>(direction) << " at " << speed << " m/s: fell after " << r.fallTime << " s";
      EXPECT_GE(r.pushesSurvived, 4);  // pushes 2 s behind them and still up
    }
  }
}

// A push held for 0.2 s (as Yin et al. 2007 push) gives the character the impulse it names: the
// whole body's sideways velocity when it ends is impulse / mass. (The same impulse given to the
// leg frame in one step, a blow, gives less: measured 0.33 m/s where this gives 0.53 m/s, the
// feet's contacts taking the rest in that step.)
TEST(WalkTrial, APushHeldOverTimeGivesTheImpulseItNames) {
  // Stepping in place (standSpeed 0): a biped standing on planted feet holds part of the push
  // with its ankles and the ground (gait/standing.cpp).
  gaitlab::gait::Gait stepping = gaitlab::gait::defaultGait(Character::Biped);
  for (gaitlab::gait::SpeedKey& k : stepping.keys) k.params.standSpeed = 0;
  WalkOptions o;
  o.character = Character::Biped;
  o.gait = &stepping;
  o.speed = 0.0;
  o.pushImpulse = 30;
  o.pushEvery = 60;  // one push, at 2 s
  o.pushDuration = 0.2;
  o.seed = 7;
  o.seconds = 2.3;
  double bodyVelocity = 0, mass = 0;
  o.observe = [&](const Simulation& sim) {
    if (std::abs(sim.time() - 2.2) > 0.5 * gaitlab::physics::kFixedStep) return;
    const gaitlab::physics::Character& c = sim.character(0);
    const gaitlab::body::Morphology& m = c.morphology();
    // Sideways is ±x: the biped faces +z (heading 0).
    double momentum = 0;
    for (int k = 0; k < c.segmentCount(); ++k) momentum += m.segments[k].mass * c.segmentState(k).linearVelocity.x();
    mass = m.totalMass();
    bodyVelocity = std::abs(momentum) / mass;
  };
  const auto r = runWalk(o);
  EXPECT_EQ(r.pushesApplied, 1);
  ASSERT_GT(mass, 0);
  EXPECT_NEAR(bodyVelocity, 30 / mass, 0.15 * 30 / mass);
}

// Mean speed is measured along the path. One chord over the run's second half, corrected for the
// angle turned, said nothing once the half turned through about a whole circle (its chord then
// shrinks to the centre's wander): the biped turning 0.5 rad/s at 1 m/s for 25 s read 2.22 m/s.
TEST(WalkTrial, ATurningWalksMeanSpeedIsAlongItsPathThroughAWholeCircle) {
  WalkOptions o;
  o.character = Character::Biped;
  o.speed = 1.0;
  o.turnRate = 0.5;
  o.seconds = 25;  // the second half turns 6.3 rad
  const auto turning = runWalk(o);
  ASSERT_FALSE(turning.fell);
  ASSERT_NEAR(std::abs(turning.yawRate) * o.seconds / 2, 2 * 3.14159265358979, 0.5);
  o.turnRate = 0;
  const auto straight = runWalk(o);
  ASSERT_FALSE(straight.fell);
  EXPECT_NEAR(turning.meanSpeed, straight.meanSpeed, 0.05 * straight.meanSpeed);
}

namespace {

// The mean speed of `character`'s preset at goal `speed` for `seconds`, with `edit` made to every
// speed key; `what` names the edit if the walk falls.
double meanSpeedWithEveryKey(Character character, double speed, double seconds,
                             const std::function<void(gaitlab::gait::GaitParams&)>& edit, const std::string& what) {
  gaitlab::gait::Gait gait = gaitlab::gait::defaultGait(character);
  for (gaitlab::gait::SpeedKey& k : gait.keys) edit(k.params);
  WalkOptions o;
  o.character = character;
  o.gait = &gait;
  o.speed = speed;
  o.seconds = seconds;
  const auto r = runWalk(o);
  EXPECT_FALSE(r.fell) << what << ": fell after " << r.fallTime << " s";
  return r.meanSpeed;
}

}  // namespace

// Speed tracking's trim is bounded by each key's maxSpeedTrim: at 2.1 m/s, where the trot's key
// lags its goal without the trim (1.53 m/s measured), a bound of 0 walks slowest, 0.25 m/s faster
// (1.83) and the shipped 0.5 m/s (1.98) faster again.
TEST(SpeedRange, TheSpeedTrimIsBoundedByTheKeysMaxSpeedTrim) {
  const auto meanSpeed = [](double bound) {
    return meanSpeedWithEveryKey(Character::Quadruped, 2.1, 16, [bound](auto& p) { p.maxSpeedTrim = bound; },
                                 "bound " + std::to_string(bound));
  };
  const double none = meanSpeed(0), some = meanSpeed(0.25), shipped = meanSpeed(0.5);
  EXPECT_GT(some, none + 0.1);
  EXPECT_GT(shipped, some + 0.1);
}

// Speed tracking acts from each key's speedTrackedFrom: the biped's walk with double support steps
// at about 0.45 m/s unless the trim slows it, so at a goal of 0.1 m/s it walks the goal when
// tracked from 0.05 (the preset) and far too fast when tracked from 0.15, as every gait was
// before schema 8 (docs/controller-notes.md §48).
TEST(SpeedRange, SlowGoalsAreTrackedFromTheKeysSpeedTrackedFrom) {
  const auto meanSpeed = [](double from) {
    return meanSpeedWithEveryKey(Character::Biped, 0.1, 30, [from](auto& p) { p.speedTrackedFrom = from; },
                                 "tracked from " + std::to_string(from));
  };
  EXPECT_EQ(gaitlab::gait::defaultGait(Character::Biped).keys.front().params.speedTrackedFrom, 0.05);
  EXPECT_NEAR(meanSpeed(0.05), 0.1, 0.015);
  EXPECT_GT(meanSpeed(0.15), 0.2);
}

// A gait set before the first step starts the gait player from its own footfall pattern, as a
// character spawned with it would (`gaitlab walk --params`, the optimiser's episodes): the
// quadruped spawned with the trot and given the walk has the walk's legs in stance, and keeps a
// start phase given before it. (It had kept the trot's, so a gait benchmarked from a file walked
// differently from the same gait shipped as the preset.)
TEST(WalkTrial, AGaitSetBeforeTheFirstStepStartsThePlayerFromItsPattern) {
  gaitlab::gait::GaitFile walk;
  const auto error = loadQuadrupedPreset("quadruped-walk.json", &walk);
  ASSERT_FALSE(error) << error->describe();
  const gaitlab::gait::GaitParams& p = walk.gait.primaryParams();
  for (const double phase : {0.0, 0.3}) {
    Simulation sim(1, 1);
    sim.spawn(Character::Quadruped, 0, 0, 0);
    sim.controller(0).setPhase(phase);
    sim.controller(0).setGait(walk.gait);
    gaitlab::gait::LegSchedule schedule[4];
    for (int i = 0; i < 4; ++i) schedule[i] = {p.legs[i].stepTrigger, p.legs[i].dutyFactor};
    gaitlab::gait::GaitPlayer own;
    own.configure(4, schedule, p.period, phase);
    const auto& player = sim.controller(0).player();
    EXPECT_DOUBLE_EQ(player.phase(), phase);
    EXPECT_DOUBLE_EQ(player.period(), p.period);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(player.leg(i).stance, own.leg(i).stance) << "leg " << i << " at phase " << phase;
  }
}

// A start phase is where the gait player starts (the walking benchmark's starts from 100 phases):
// phase 0 is the gait's own start, bit for bit; another phase is another walk, which still walks.
TEST(WalkTrial, AStartPhaseStartsTheGaitThere) {
  WalkOptions o;
  o.character = Character::Biped;
  o.speed = 0.5;
  o.seconds = 5;
  const auto own = runWalk(o);
  o.startPhase = 0.0;
  EXPECT_EQ(runWalk(o).stateHash, own.stateHash);
  o.startPhase = 0.5;
  const auto half = runWalk(o);
  EXPECT_NE(half.stateHash, own.stateHash);
  EXPECT_FALSE(half.fell) << "fell after " << half.fallTime << " s";
  EXPECT_GT(half.distance, 1.0);
}

// The goal schedule of the ramp trial: linear between its points, held before and after.
TEST(WalkTrial, GoalScheduleInterpolates) {
  WalkOptions o;
  o.speed = 0.7;
  EXPECT_EQ(gaitlab::sim::goalSpeedAt(o, 3.0), 0.7);
  o.speedSchedule = {{1.0, 0.0}, {3.0, 1.0}, {4.0, 0.0}};
  EXPECT_EQ(gaitlab::sim::goalSpeedAt(o, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(gaitlab::sim::goalSpeedAt(o, 2.0), 0.5);
  EXPECT_DOUBLE_EQ(gaitlab::sim::goalSpeedAt(o, 3.5), 0.5);
  EXPECT_EQ(gaitlab::sim::goalSpeedAt(o, 9.0), 0.0);
}
