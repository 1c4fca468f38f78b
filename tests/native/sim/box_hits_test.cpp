// The box-hit trial (sim/box_hits.h): boxes thrown as the demo throws them hit the walking
// character (the simulation aims them), every hit is judged, the trial is reproducible from its
// seed, and what it counts as knocked over follows the box: a pebble knocks over nobody, a crate
// of half a tonne everybody. A quadruped it knocks over gets up by itself and walks on; a biped
// kips up by itself from some of its falls.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/box_hits.h"
#include "sim/simulation.h"

using gaitlab::gait::Character;
using gaitlab::sim::BoxHitOptions;
using gaitlab::sim::BoxHitResult;
using gaitlab::sim::runBoxHits;

namespace {

BoxHitOptions trial(Character c, int hits, double half) {
  BoxHitOptions o;
  o.walk.character = c;
  o.walk.speed = c == Character::Biped ? 0.5 : 0.4;
  o.walk.seed = 3;
  o.hits = hits;
  o.half = half;
  return o;
}

}  // namespace

TEST(BoxHits, AimedThrowsHitAndEveryHitIsJudged) {
  for (Character c : {Character::Biped, Character::Quadruped}) {
    const BoxHitResult r = runBoxHits(trial(c, 6, 0.12));
    ASSERT_EQ(r.hits.size(), 6u) << characterName(c);
    // The aim leads the walker: at most one throw in three may miss.
    EXPECT_LE(r.throws, 8) << characterName(c);
    for (const auto& h : r.hits) {
      EXPECT_GE(h.segment, 0);
      EXPECT_GE(h.speed, 14.0);   // the page's throw speed, faster beyond 14 m
      EXPECT_LE(h.speed, 18.5);   // thrown from at most 18 m (and a little above)
      EXPECT_GE(h.throwTime, 2.0);
      EXPECT_LE(h.throwTime, 4.01);
    }
  }
}

TEST(BoxHits, TheSameSeedGivesTheSameTrial) {
  const BoxHitResult a = runBoxHits(trial(Character::Biped, 4, 0.12));
  const BoxHitResult b = runBoxHits(trial(Character::Biped, 4, 0.12));
  ASSERT_EQ(a.hits.size(), b.hits.size());
  EXPECT_EQ(a.throws, b.throws);
  for (size_t i = 0; i < a.hits.size(); ++i) {
    EXPECT_EQ(a.hits[i].segment, b.hits[i].segment);
    EXPECT_EQ(a.hits[i].throwTime, b.hits[i].throwTime);
    EXPECT_EQ(a.hits[i].fell, b.hits[i].fell);
  }
}

TEST(BoxHits, WhatKnocksOverFollowsTheBox) {
  // A 6 cm box of 0.13 kg at 14 m/s (under 2 N·s): nobody falls.
  EXPECT_EQ(runBoxHits(trial(Character::Biped, 5, 0.03)).falls(), 0);
  EXPECT_EQ(runBoxHits(trial(Character::Quadruped, 5, 0.03)).falls(), 0);
  // A 1 m box of 600 kg: every hit knocks the character over.
  const BoxHitResult crate = runBoxHits(trial(Character::Biped, 5, 0.5));
  EXPECT_EQ(crate.falls(), static_cast<int>(crate.hits.size()));
}

TEST(BoxHits, AQuadrupedKnockedOverGetsUpByItself) {
  // The demo's box knocks the dog over more often than not; watched 10 s after each fall, it rolls
  // onto its belly and rises (gait/get_up.cpp): at most one in eight stays down.
  BoxHitOptions o = trial(Character::Quadruped, 8, 0.12);
  o.getUpSeconds = 10;
  const BoxHitResult r = runBoxHits(o);
  ASSERT_GE(r.falls(), 4);
  EXPECT_GE(r.getUps(), r.falls() - 1);
  for (const auto& h : r.hits) {
    if (!h.fell) EXPECT_EQ(h.gotUpAfter, -1.0);
    if (h.gotUpAfter >= 0) EXPECT_LE(h.gotUpAfter, 10.0);
  }
  // The watch changes nothing about the falls themselves.
  o.getUpSeconds = 0;
  const BoxHitResult unwatched = runBoxHits(o);
  EXPECT_EQ(unwatched.falls(), r.falls());
  EXPECT_EQ(unwatched.getUps(), 0);
}

TEST(BoxHits, ABipedKnockedOverKipsUpByItself) {
  // Watched 10 s after each fall, the biped rolls onto its back and kips up onto its feet
  // (gait/get_up_two_legs.cpp), tries again when a kip-up falls back, and walks on. On these
  // throws 5 hits knock it over: one it catches itself in a stumble (up at once, as before the
  // get-up), two it kips up from, 6–8 s after the fall, and two leave it down.
  BoxHitOptions o = trial(Character::Biped, 16, 0.12);
  o.getUpSeconds = 10;
  const BoxHitResult r = runBoxHits(o);
  ASSERT_GE(r.falls(), 3);
  int kipUps = 0;
  for (const auto& h : r.hits) kipUps += h.gotUpAfter > 0.5 ? 1 : 0;
  EXPECT_GE(kipUps, 2);
}

TEST(BoxHits, AQuadrupedThatGotUpWalksOnAtItsGoal) {
  // A box thrown at the dog's side as the page throws one, at the middle of its spine.
  gaitlab::sim::Simulation sim(1, 3);
  gaitlab::sim::WalkOptions walk;
  walk.character = Character::Quadruped;
  walk.speed = 0.4;
  gaitlab::sim::setUpWalk(sim, walk);
  const auto stepFor = [&](double seconds) { sim.step(static_cast<int>(std::lround(seconds / gaitlab::physics::kFixedStep))); };
  stepFor(3.0);
  const int spine = sim.character(0).morphology().spine[1];
  const Eigen::Vector3d at = sim.character(0).segmentState(spine).position;
  const Eigen::Vector3d from = at + Eigen::Vector3d(10, 1.5, 0);
  const double speed = gaitlab::sim::pageThrowSpeed((at - from).norm());
  sim.throwBox(from, sim.aimAt(0, spine, Eigen::Vector3d::Zero(), from, speed).velocity, 0.12);
  stepFor(1.5);
  ASSERT_TRUE(sim.controller(0).down()) << "the box knocked it over and it is getting up";
  for (int s = 0; s < 1200 && sim.controller(0).down(); ++s) sim.step(1);
  ASSERT_FALSE(sim.controller(0).down()) << "up within 10 s";
  stepFor(2.0);  // it stands up straight, then walks
  const Eigen::Vector3d before = sim.character(0).segmentState(0).position;
  stepFor(3.0);
  const Eigen::Vector3d moved = sim.character(0).segmentState(0).position - before;
  EXPECT_FALSE(gaitlab::sim::hasFallen(sim, 0));
  EXPECT_GT(std::hypot(moved.x(), moved.z()), 0.8) << "0.4 m/s for 3 s is 1.2 m";
}
