// The optimiser (optimize/): its random numbers, §3.3's perturbation, each term of the objective
// (eq. 3.10) on synthetic trajectories with known answers, the determinism of a search, and a
// short search that improves a detuned gait.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gait/defaults.h"
#include "gait/heading.h"
#include "gait/schema.h"
#include "optimize/objective.h"
#include "optimize/optimizer.h"
#include "optimize/random.h"
#include "sim/walk_trial.h"

using namespace gaitlab;
using namespace gaitlab::optimize;

// ---- random numbers -------------------------------------------------------------------------

TEST(OptimizeRandom, EngineIsTheStandardMersenneTwisterAndTheMappingIsOurs) {
  // C++ [rand.predef]: the 10000th output of a default-constructed mt19937_64.
  Random r(5489u);
  uint64_t v = 0;
  for (int i = 0; i < 10000; ++i) v = r.next();
  EXPECT_EQ(v, 9981545732273789042ull);
  Random a(7), b(7);
  for (int i = 0; i < 1000; ++i) {
    const uint64_t raw = a.next();
    const double u = b.uniform();
    EXPECT_EQ(u, static_cast<double>(raw >> 11) * 0x1.0p-53);
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

TEST(OptimizeRandom, NormalHasZeroMeanAndUnitVariance) {
  Random r(3);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(sum2 / n, 1.0, 0.01);
}

// ---- perturbation (§3.3) ---------------------------------------------------------------------

TEST(OptimizePerturb, ChangesAFifthOfTheCoordinatesByUpToATenthOfTheirRange) {
  const int dims = 100, trials = 1000;
  std::vector<double> lo(dims), hi(dims), x(dims);
  for (int i = 0; i < dims; ++i) {
    lo[i] = -1.0 - i;        // ranges differ per coordinate
    hi[i] = 3.0 + 2.0 * i;
    x[i] = 0.5 * (lo[i] + hi[i]);
  }
  Random rng(11);
  long changed = 0, small = 0;
  double meanStep = 0;
  for (int t = 0; t < trials; ++t) {
    const std::vector<double> y = perturb(x, lo, hi, 0.2, 0.1, rng);
    for (int i = 0; i < dims; ++i) {
      if (y[i] == x[i]) continue;
      ++changed;
      const double step = (y[i] - x[i]) / (hi[i] - lo[i]);  // in units of the range
      ASSERT_LE(std::abs(step), 0.1);
      meanStep += step;
      if (std::abs(step) < 0.05) ++small;
    }
  }
  const double n = static_cast<double>(dims) * trials;
  // Binomial(100000, 0.2): standard deviation 0.0013 of the fraction.
  EXPECT_NEAR(changed / n, 0.2, 0.006);
  // Uniform on (−0.1, 0.1): half the steps are under 0.05, and they average to zero.
  EXPECT_NEAR(static_cast<double>(small) / changed, 0.5, 0.015);
  EXPECT_NEAR(meanStep / changed, 0.0, 0.002);
}

TEST(OptimizePerturb, ClampsToTheBounds) {
  const int dims = 50;
  std::vector<double> lo(dims, 0.0), hi(dims, 1.0), top(dims, 1.0), bottom(dims, 0.0);
  Random rng(5);
  long atBound = 0, changed = 0;
  for (int t = 0; t < 2000; ++t) {
    for (const auto* x : {&top, &bottom}) {
      const std::vector<double> y = perturb(*x, lo, hi, 0.2, 0.1, rng);
      for (int i = 0; i < dims; ++i) {
        ASSERT_GE(y[i], 0.0);
        ASSERT_LE(y[i], 1.0);
        if (y[i] != (*x)[i]) ++changed;
      }
      for (int i = 0; i < dims; ++i) atBound += y[i] == (*x)[i];
    }
  }
  // From a bound, the steps that point outwards (half of those drawn) are clamped back onto it:
  // about 10 % of coordinates move, 90 % stay.
  const double n = 2.0 * 2000 * dims;
  EXPECT_NEAR(changed / n, 0.1, 0.006);
  EXPECT_NEAR(atBound / n, 0.9, 0.006);
}

// ---- objective terms (eq. 3.10) on synthetic trajectories -----------------------------------

namespace {

constexpr double kDt = 1.0 / 120.0;
constexpr double kStanding = 1.0;

// Records `seconds` of a leg frame whose state at time t is given by `at`.
ObjectiveTerms record(const ObjectiveSettings& s, double goalSpeed,
                      const std::function<LegFrameSample(double)>& at, double seconds,
                      bool fell = false) {
  ObjectiveRecorder r(s, goalSpeed, 0.0, kDt);
  const int steps = static_cast<int>(std::lround(seconds / kDt));
  for (int k = 1; k <= steps; ++k) {
    const LegFrameSample f = at(k * kDt);
    r.add(k * kDt, &f, 1);
  }
  return r.finish(fell, steps * kDt);
}

LegFrameSample upright(const Eigen::Vector3d& p, const Eigen::Vector3d& v, double height = kStanding) {
  return {p, v, Eigen::Quaterniond::Identity(), height, kStanding};
}

ObjectiveSettings settings() {
  ObjectiveSettings s;
  s.seconds = 3.0;
  s.warmup = 1.0;
  return s;
}

}  // namespace

TEST(OptimizeObjective, APerfectWalkScoresZero) {
  const auto t = record(settings(), 1.2, [](double t) {
    return upright({0, kStanding, 1.2 * t}, {0, 0, 1.2});
  }, 3.0);
  EXPECT_NEAR(t.fd, 0.0, 1e-12);
  EXPECT_NEAR(t.fv, 0.0, 1e-12);
  EXPECT_NEAR(t.fa, 0.0, 1e-12);
  EXPECT_NEAR(t.fr, 0.0, 1e-12);
  EXPECT_EQ(t.fall, 0.0);
  EXPECT_NEAR(t.total, 0.0, 1e-12);
}

TEST(OptimizeObjective, StandingStillMissesTheGoalByTheWholeDistance) {
  // Goal 1 m/s, measured for 2 s after the warm-up: f_v = 1 (m/s)², and the travel deviation is
  // (0 − 2 m)/2 m = −1, so f_d = 1.
  const auto t = record(settings(), 1.0, [](double) { return upright({0, kStanding, 0}, {0, 0, 0}); }, 3.0);
  EXPECT_NEAR(t.fv, 1.0, 1e-12);
  EXPECT_NEAR(t.fd, 1.0, 1e-9);
  EXPECT_NEAR(t.total, 2.0, 1e-9);
}

TEST(OptimizeObjective, SidewaysDriftCountsAsVelocityDeviation) {
  const auto t = record(settings(), 1.0, [](double t) {
    return upright({0.5 * t, kStanding, t}, {0.5, 0, 1.0});
  }, 3.0);
  EXPECT_NEAR(t.fv, 0.25, 1e-12);
  EXPECT_NEAR(t.fd, 0.0, 1e-9);  // forward travel is exact
}

TEST(OptimizeObjective, VelocityIsMeasuredInTheTurningGoalHeadingFrame) {
  // Goal: 1 m/s while turning at 0.5 rad/s. A walker whose velocity follows the goal heading
  // exactly has no velocity or travel deviation, and no rotation deviation if it faces it.
  ObjectiveSettings s = settings();
  s.turnRate = 0.5;
  ObjectiveRecorder r(s, 1.0, 0.0, kDt);
  for (int k = 1; k <= 360; ++k) {
    const double t = k * kDt, heading = 0.5 * t;
    const LegFrameSample f{{0, kStanding, 0}, gait::headingForward(heading), gait::headingQuat(heading),
                           kStanding, kStanding};
    r.add(t, &f, 1);
  }
  const ObjectiveTerms t = r.finish(false, 3.0);
  EXPECT_NEAR(t.fv, 0.0, 1e-12);
  EXPECT_NEAR(t.fd, 0.0, 1e-9);
  EXPECT_NEAR(t.fr, 0.0, 1e-12);
  // The acceleration of that walk is centripetal: v²/r = v·ω = 0.5 m/s².
  EXPECT_NEAR(t.fa, 0.25 / (9.81 * 9.81), 1e-6);
}

// The speed term f_s (ours): the horizontal speed against the goal speed, whatever the direction.
// A walker at the goal speed whose path has fallen behind a turning goal heading scores f_v for
// the lag, and a slower walker less (what searches of the canter's turns exploited), but f_s is 0
// for the first and counts the second's lost speed; weighted by w_s into the total.
TEST(OptimizeObjective, SpeedDeviationIgnoresDirectionAndCountsLostSpeed) {
  ObjectiveSettings s = settings();
  const auto sideways = [&](double speed) {
    return record(s, 1.0, [speed](double t) { return upright({speed * t, kStanding, 0}, {speed, 0, 0}); }, 3.0);
  };
  const ObjectiveTerms atGoal = sideways(1.0), slower = sideways(0.5);
  EXPECT_NEAR(atGoal.fv, 2.0, 1e-12);   // (0 − 1)² forward + 1² sideways
  EXPECT_NEAR(slower.fv, 1.25, 1e-12);  // (0 − 1)² + 0.5²: lower for the slower walker
  EXPECT_NEAR(atGoal.fs, 0.0, 1e-12);
  EXPECT_NEAR(slower.fs, 0.25, 1e-12);
  s.ws = 4.0;
  EXPECT_NEAR(sideways(0.5).total - slower.total, 4.0 * 0.25, 1e-9);
}

// The flight term f_f (ours) is the walk's share of time with no foot down, weighted by w_f into
// the total: a search for a walk can ask for double support, one for a run leaves w_f at 0.
TEST(OptimizeObjective, FlightCountsInTheTotalByItsWeight) {
  ObjectiveSettings s = settings();
  const auto total = [&](double wf, double flight) {
    s.wf = wf;
    ObjectiveRecorder r(s, 1.0, 0.0, kDt);
    for (int k = 1; k <= 360; ++k) {
      const LegFrameSample f = upright({0, kStanding, k * kDt}, {0, 0, 1.0});
      r.add(k * kDt, &f, 1);
    }
    const ObjectiveTerms t = r.finish(false, 3.0, 0.0, flight);
    EXPECT_EQ(t.ff, flight);
    return t.total;
  };
  EXPECT_NEAR(total(20, 0.1) - total(20, 0.0), 2.0, 1e-9);
  EXPECT_NEAR(total(0, 0.1), total(0, 0.0), 1e-12);
}

// The standing term f_p (ours) is the share of an episode held at goal 0 not standing on planted
// feet, weighted by w_p into the total; an episode with a goal above 0 or a scheduled goal has none.
TEST(OptimizeObjective, NotStandingCountsOnlyAtGoalZero) {
  ObjectiveSettings s = settings();
  s.wp = 20;
  const auto terms = [&](double goal, double standing, bool scheduled = false) {
    ObjectiveRecorder r(s, goal, 0.0, kDt);
    if (scheduled) r.setGoalSchedule({{0.0, 0.0}, {3.0, 0.0}});
    for (int k = 1; k <= 360; ++k) {
      const LegFrameSample f = upright({0, kStanding, goal * k * kDt}, {0, 0, goal});
      r.add(k * kDt, &f, 1);
    }
    return r.finish(false, 3.0, 0.0, 0.0, 0.0, standing);
  };
  EXPECT_NEAR(terms(0.0, 0.75).fp, 0.25, 1e-12);
  EXPECT_NEAR(terms(0.0, 0.75).total - terms(0.0, 1.0).total, 20 * 0.25, 1e-9);
  EXPECT_EQ(terms(1.0, 0.0).fp, 0.0);
  EXPECT_EQ(terms(0.0, 0.0, /*scheduled=*/true).fp, 0.0);
}

// A goal-0 episode reports how long it stood: a stand that holds gives f_p near 0 (it first
// settles), one knocked about by pushes steps to recover and stands less.
TEST(OptimizeObjective, AStandingEpisodeMeasuresItsStand) {
  ObjectiveSettings s = settings();
  s.speeds = {0.0};
  s.seconds = 10;
  s.wp = 1;
  const ObjectiveTerms still = evaluate(gait::Character::Biped, gait::defaultGait(gait::Character::Biped), s, 1);
  EXPECT_FALSE(still.fell);
  EXPECT_LT(still.fp, 0.2);
  s.pushImpulse = 60;
  s.pushDuration = 0.2;
  s.pushEvery = 2;
  const ObjectiveTerms pushed = evaluate(gait::Character::Biped, gait::defaultGait(gait::Character::Biped), s, 1);
  EXPECT_GT(pushed.fp, still.fp + 0.1);
}

// The stop term f_o (ours) is how far the root leg frame moves after a schedule's goal returns
// to 0 for good, weighted by w_o into the total; a schedule that does not end at 0, or a held
// goal, has none.
TEST(OptimizeObjective, TheStopsOvershootIsTheMoveAfterTheGoalReachesZero) {
  ObjectiveSettings s = settings();
  s.wo = 50;
  // Walks +z at 1 m/s until 2 s, then slides 0.3 m sideways (+x) by 2.3 s and stays.
  const auto at = [](double t) {
    return upright({0.3 * std::clamp((t - 2.0) / 0.3, 0.0, 1.0), kStanding, std::min(t, 2.0)}, {0, 0, t < 2 ? 1.0 : 0.0});
  };
  const auto terms = [&](std::vector<std::pair<double, double>> schedule) {
    ObjectiveRecorder r(s, 1.0, 0.0, kDt);
    if (!schedule.empty()) r.setGoalSchedule(schedule);
    for (int k = 1; k <= 480; ++k) {
      const LegFrameSample f = at(k * kDt);
      r.add(k * kDt, &f, 1);
    }
    return r.finish(false, 4.0);
  };
  // The goal is 0 from 2 s (the last three points): the 0.3 m slide counts.
  const ObjectiveTerms stopped = terms({{0.0, 1.0}, {2.0, 0.0}, {3.0, 0.0}, {4.0, 0.0}});
  EXPECT_NEAR(stopped.fo, 0.3, 1e-9);
  // From 1 s the goal is 0 as well: the last 1 m of the walk counts too.
  EXPECT_NEAR(terms({{0.0, 1.0}, {1.0, 0.0}, {4.0, 0.0}}).fo, std::hypot(1.0, 0.3), 1e-9);
  // Weighted into the total.
  const ObjectiveTerms unweighted = [&] { s.wo = 0; return terms({{0.0, 1.0}, {2.0, 0.0}, {4.0, 0.0}}); }();
  EXPECT_NEAR(stopped.total - unweighted.total, 50 * 0.3, 1e-9);
  // A schedule that ends above 0, and a held goal, have no stop.
  EXPECT_EQ(terms({{0.0, 1.0}, {2.0, 0.0}, {4.0, 0.5}}).fo, 0.0);
  EXPECT_EQ(terms({}).fo, 0.0);
}

// `stopFrom` adds, per start state, a walk up to that goal and back to 0 followed by a stand of
// kStopHoldSeconds, unpushed, and the shipped biped stops in it: it goes on after the goal
// returns to 0, but by less than the walking benchmark's 0.1 m.
TEST(OptimizeObjective, AStopEpisodeWalksStopsAndMeasuresTheOvershoot) {
  EXPECT_EQ(stopSchedule(0.8, 10.0),
            (std::vector<std::pair<double, double>>{{0.0, 0.0}, {5.0, 0.8}, {10.0, 0.0}, {10.0 + kStopHoldSeconds, 0.0}}));
  ObjectiveSettings s = settings();
  s.speeds = {};
  s.seconds = 10;
  s.stopFrom = 0.8;
  const gait::Gait preset = gait::defaultGait(gait::Character::Biped);
  const ObjectiveTerms stop = evaluate(gait::Character::Biped, preset, s, 1);
  ASSERT_FALSE(stop.fell);
  EXPECT_NEAR(stop.seconds, 10.0 + kStopHoldSeconds, 0.01);  // one episode: the stop
  EXPECT_GT(stop.fo, 0.0);
  EXPECT_LT(stop.fo, 0.1);
  // The same as the episode run alone.
  const std::vector<std::pair<double, double>> schedule = stopSchedule(0.8, 10.0);
  const ObjectiveTerms episode = runEpisode(gait::Character::Biped, preset, s, 0.8, 0, 1, Ground{}, nullptr, schedule);
  EXPECT_EQ(episode.fo, stop.fo);
  EXPECT_EQ(episode.total, stop.total);
  // Not pushed, as the benchmark's ramp is not: pushes asked of the search leave it as it was.
  s.pushImpulse = 60;
  s.pushEvery = 2;
  EXPECT_EQ(evaluate(gait::Character::Biped, preset, s, 1).total, stop.total);
  EXPECT_NE(runEpisode(gait::Character::Biped, preset, s, 0.8, 0, 1, Ground{}, nullptr, schedule).total, stop.total);
}

// The tracking term f_k (ours) is the share of a ramp episode's speed samples off the goal by
// more than 10 %, exactly what the walking benchmark's ramp counts (sim::runWalk's tracking),
// weighted by w_k into the total; an episode without a ramp has no samples and no f_k.
TEST(OptimizeObjective, TrackingIsTheRampCriterionsShareOfMisses) {
  EXPECT_EQ(trackingMisses(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(trackingMisses(528, 504), 24.0 / 528.0);

  const gait::Gait preset = gait::defaultGait(gait::Character::Quadruped);
  ObjectiveSettings s;
  s.seconds = 6.0;
  s.speeds = {2.9};
  const uint32_t seed = 3;
  const ObjectiveTerms steady = runEpisode(gait::Character::Quadruped, preset, s, 2.9, 0, seed);
  EXPECT_EQ(steady.fk, 0.0);
  const std::vector<std::pair<double, double>> schedule = rampSchedule(2.9, s.seconds);
  const ObjectiveTerms ramp =
      runEpisode(gait::Character::Quadruped, preset, s, 2.9, 0, seed, Ground{}, nullptr, schedule);
  ASSERT_FALSE(ramp.fell);
  // The same walk as the benchmark runs it: the episode's ramp, start 0 (no nudge, the gait's phase).
  sim::WalkOptions w;
  w.character = gait::Character::Quadruped;
  w.gait = &preset;
  w.seconds = s.seconds;
  w.speedSchedule = {{0.0, 0.0}, {0.5 * s.seconds, 2.9}, {s.seconds, 0.0}};
  EXPECT_EQ(schedule, w.speedSchedule);
  w.seed = seed;
  const sim::WalkResult r = sim::runWalk(w);
  // A ramp to 2.9 m/s in 3 s and back: the trot, which lags so steep a ramp and is walked about
  // 2.5 m/s at that goal, misses some samples.
  ASSERT_GT(r.trackingSamples, 0);
  ASSERT_GT(ramp.fk, 0.0);
  EXPECT_EQ(ramp.fk, trackingMisses(r.trackingSamples, r.trackingWithin));
  // Weighted into the total, and nothing else moves.
  s.wk = 100;
  const ObjectiveTerms weighted =
      runEpisode(gait::Character::Quadruped, preset, s, 2.9, 0, seed, Ground{}, nullptr, schedule);
  EXPECT_EQ(weighted.fk, ramp.fk);
  EXPECT_DOUBLE_EQ(weighted.total - ramp.total, 100 * ramp.fk);
  // In the mean over a steady episode and a ramp episode, as every term.
  s.ramp = 1;
  EXPECT_DOUBLE_EQ(evaluate(gait::Character::Quadruped, preset, s, seed).fk, ramp.fk / 2);
}

// Speed-change episodes (speedChanges) walk the walking benchmark's gait-change trial: the goal
// held 1–4 s at a time, alternating from the slowest goal speed to the fastest, nine holds. The
// holds follow from the evaluation's seed and the episode's index alone, so every candidate
// meets the same changes, and each episode is scored on its own schedule's length.
TEST(OptimizeObjective, SpeedChangeEpisodesAlternateBetweenTheSlowestAndFastestGoal) {
  const auto a = speedChangeSchedule(0.3, 1.0, 0, 11);
  ASSERT_EQ(a.size(), 2u * kSpeedChangeHolds);
  EXPECT_EQ(a.front().first, 0.0);
  for (int k = 0; k < kSpeedChangeHolds; ++k) {
    const auto& [start, goal] = a[2 * k];
    const auto& [end, held] = a[2 * k + 1];
    EXPECT_EQ(goal, k % 2 == 0 ? 0.3 : 1.0);
    EXPECT_EQ(held, goal);
    EXPECT_GE(end - start, 1.0 - 0.001);
    EXPECT_LT(end - start, 4.0);
    if (k > 0) EXPECT_NEAR(start, a[2 * k - 1].first, 0.0011);
  }
  EXPECT_EQ(speedChangeSchedule(0.3, 1.0, 0, 11), a);
  EXPECT_NE(speedChangeSchedule(0.3, 1.0, 1, 11), a);
  EXPECT_NE(speedChangeSchedule(0.3, 1.0, 0, 12), a);

  // An episode on that schedule lasts as long as it and follows its goal, not the held speed.
  const gait::Gait preset = gait::defaultGait(gait::Character::Biped);
  ObjectiveSettings s;
  s.seconds = 3.0;
  s.speeds = {1.0, 0.3};
  const ObjectiveTerms changing = runEpisode(gait::Character::Biped, preset, s, 0.3, 0, 11, Ground{}, nullptr, a);
  ASSERT_FALSE(changing.fell);
  EXPECT_NEAR(changing.seconds, a.back().first, 0.01);
  const ObjectiveTerms held = runEpisode(gait::Character::Biped, preset, s, 0.3, 0, 11);
  EXPECT_NEAR(held.seconds, s.seconds, 0.01);
  // Its goal changes: a walk judged against it moves the travel and velocity terms.
  EXPECT_NE(changing.fv, held.fv);

  // Beside the held goals' episodes: speedChanges more episodes per ground (`seconds` is the
  // simulated time of them all).
  const ObjectiveTerms without = evaluate(gait::Character::Biped, preset, s, 11);
  s.speedChanges = 2;
  const ObjectiveTerms with = evaluate(gait::Character::Biped, preset, s, 11);
  EXPECT_NE(speedChangeSeed(11, 0), speedChangeSeed(11, 1));
  double expected = 2 * s.seconds;
  for (int k = 0; k < 2; ++k)
    expected += runEpisode(gait::Character::Biped, preset, s, 0.3, 0, speedChangeSeed(11, k), Ground{}, nullptr,
                           speedChangeSchedule(0.3, 1.0, k, 11)).seconds;
  EXPECT_NEAR(without.seconds, 2 * s.seconds, 0.02);
  EXPECT_NEAR(with.seconds, expected, 1e-9);
}

// A ramp episode's goal changes with time (setGoalSchedule): a walker that follows the ramp
// exactly has no velocity or travel deviation; one that holds the top speed throughout does.
TEST(OptimizeObjective, ARampingGoalIsFollowedInTime) {
  const std::vector<std::pair<double, double>> ramp = {{0.0, 0.0}, {1.5, 1.2}, {3.0, 0.0}};
  const auto walk = [&](bool follows) {
    ObjectiveRecorder r(settings(), 1.2, 0.0, kDt);
    r.setGoalSchedule(ramp);
    double z = 0;
    for (int k = 1; k <= 360; ++k) {
      const double t = k * kDt;
      const double v = follows ? gaitlab::sim::scheduleAt(ramp, t) : 1.2;
      z += v * kDt;
      const LegFrameSample f = upright({0, kStanding, z}, {0, 0, v});
      r.add(t, &f, 1);
    }
    return r.finish(false, 3.0);
  };
  const ObjectiveTerms follows = walk(true), holds = walk(false);
  EXPECT_NEAR(follows.fv, 0.0, 1e-12);
  EXPECT_NEAR(follows.fd, 0.0, 1e-9);
  EXPECT_GT(holds.fv, 0.1);
  EXPECT_GT(holds.fd, 0.1);
}

TEST(OptimizeObjective, PostureDeviationIsRelativeHeightSquared) {
  const auto t = record(settings(), 1.0, [](double t) {
    return upright({0, 0.9, t}, {0, 0, 1.0}, 0.9);
  }, 3.0);
  EXPECT_NEAR(t.fd, 0.01, 1e-9);
}

TEST(OptimizeObjective, RotationDeviationIsTheSquaredAngleFromTheGoalFrame) {
  const Eigen::Quaterniond pitched(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond yawed = gait::headingQuat(-0.3);
  for (const auto& [q, angle] : {std::pair{pitched, 0.2}, std::pair{yawed, 0.3}}) {
    const auto t = record(settings(), 1.0, [&, q = q](double t) {
      LegFrameSample f = upright({0, kStanding, t}, {0, 0, 1.0});
      f.orientation = q;
      return f;
    }, 3.0);
    EXPECT_NEAR(t.fr, angle * angle, 1e-12);
  }
}

TEST(OptimizeObjective, AccelerationIsInUnitsOfGravitySquared) {
  // Constant forward acceleration of 0.1 g: f_a = 0.01.
  const double a = 0.981;
  const auto t = record(settings(), 1.0, [&](double t) {
    return upright({0, kStanding, 0.5 * a * t * t}, {0, 0, a * t});
  }, 3.0);
  EXPECT_NEAR(t.fa, 0.01, 1e-9);
}

TEST(OptimizeObjective, AFallDominatesAndAnEarlierFallScoresWorse) {
  ObjectiveSettings s = settings();
  const auto still = [](double) { return upright({0, kStanding, 0}, {0, 0, 0}); };
  const auto late = record(s, 1.0, still, 2.25, true);   // fell with a quarter left
  const auto early = record(s, 1.0, still, 0.75, true);  // three quarters left
  EXPECT_NEAR(late.fall, 100.0 * 1.25, 1e-9);
  EXPECT_NEAR(early.fall, 100.0 * 1.75, 1e-9);
  EXPECT_GT(early.total, late.total);
  EXPECT_GT(late.total, record(s, 1.0, still, 3.0).total);  // standing still beats falling
}

TEST(OptimizeObjective, WeightsScaleTheirTerms) {
  ObjectiveSettings s = settings();
  s.wd = 2;
  s.wv = 3;
  s.wa = 5;
  s.wr = 7;
  const auto t = record(s, 1.0, [](double t) {
    LegFrameSample f = upright({0.3 * t, 0.95, 0}, {0.3, 0, 0.2 * t}, 0.95);
    f.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()));
    return f;
  }, 3.0);
  EXPECT_GT(t.fd * t.fv * t.fa * t.fr, 0.0);
  EXPECT_NEAR(t.total, 2 * t.fd + 3 * t.fv + 5 * t.fa + 7 * t.fr, 1e-12);
}

// f_t (ours): the mean over legs of (measured − configured duty factor)², against hand sums; and
// in an episode it is what the walk measured, weighted by w_t into the total.
TEST(OptimizeObjective, TimingDeviationIsTheMeanSquaredDutyError) {
  EXPECT_EQ(timingDeviation({0.5, 0.5}, {0.5, 0.5}), 0.0);
  EXPECT_NEAR(timingDeviation({0.4, 0.6, 0.5, 0.5}, {0.5, 0.5, 0.5, 0.7}), (0.01 + 0.01 + 0 + 0.04) / 4, 1e-15);
  EXPECT_EQ(timingDeviation({}, {}), 0.0);

  ObjectiveSettings s;
  s.seconds = 3.0;
  s.speeds = {0.5};
  const gaitlab::gait::Gait p = gaitlab::gait::defaultGait(gaitlab::gait::Character::Quadruped);
  const ObjectiveTerms plain = runEpisode(gaitlab::gait::Character::Quadruped, p, s, 0.5, 0, 1);
  s.wt = 10.0;
  const ObjectiveTerms weighted = runEpisode(gaitlab::gait::Character::Quadruped, p, s, 0.5, 0, 1);
  gaitlab::sim::WalkOptions w;
  w.character = gaitlab::gait::Character::Quadruped;
  w.gait = &p;
  w.speed = 0.5;
  w.seconds = 3.0;
  w.seed = 1;
  const auto walk = gaitlab::sim::runWalk(w);
  EXPECT_GT(plain.ft, 0.0);
  EXPECT_EQ(plain.ft, timingDeviation(walk.dutyMeasured, walk.dutyConfig));
  EXPECT_EQ(weighted.ft, plain.ft);
  EXPECT_NEAR(weighted.total, plain.total + 10.0 * plain.ft, 1e-12);
}

// startPhases: start states after the first begin at their own gait phase (as a crowd starts),
// the first at the gait's own; with the setting off every start begins at the gait's own phase.
TEST(OptimizeObjective, StartPhasesGiveLaterStartsTheirOwnPhase) {
  using gaitlab::gait::Character;
  ObjectiveSettings s;
  s.seconds = 2.0;
  s.startImpulse = 0.0;  // the starts then differ by their phase alone
  const gaitlab::gait::Gait g = gaitlab::gait::defaultGait(Character::Biped);
  const ObjectiveTerms first = runEpisode(Character::Biped, g, s, 0.5, 0, 1);
  const ObjectiveTerms second = runEpisode(Character::Biped, g, s, 0.5, 1, 1);
  s.startPhases = 1.0;
  const ObjectiveTerms firstPhased = runEpisode(Character::Biped, g, s, 0.5, 0, 1);
  const ObjectiveTerms secondPhased = runEpisode(Character::Biped, g, s, 0.5, 1, 1);
  EXPECT_EQ(firstPhased.total, first.total);    // the first start: the gait's own phase either way
  EXPECT_EQ(second.total, first.total);         // no nudge, no phase: the same episode
  EXPECT_NE(secondPhased.total, second.total);  // the second start at phase 0.618
}

// turnBothWays: odd start states turn at −turnRate, so that a search of a gait that is not
// left-right symmetric (a canter with its lead) meets turns to both sides.
TEST(OptimizeObjective, TurnBothWaysTurnsOddStartsTheOtherWay) {
  using gaitlab::gait::Character;
  ObjectiveSettings s;
  s.seconds = 2.0;
  s.turnRate = 0.5;
  const gaitlab::gait::Gait g = gaitlab::gait::defaultGait(Character::Biped);
  const ObjectiveTerms leftFirst = runEpisode(Character::Biped, g, s, 0.5, 0, 1);
  const ObjectiveTerms leftSecond = runEpisode(Character::Biped, g, s, 0.5, 1, 1);
  s.turnRate = -0.5;
  const ObjectiveTerms rightSecond = runEpisode(Character::Biped, g, s, 0.5, 1, 1);
  s.turnRate = 0.5;
  s.turnBothWays = 1.0;
  EXPECT_EQ(episodeTurnRate(s, 0), 0.5);
  EXPECT_EQ(episodeTurnRate(s, 1), -0.5);
  EXPECT_EQ(episodeTurnRate(s, 2), 0.5);
  EXPECT_EQ(runEpisode(Character::Biped, g, s, 0.5, 0, 1).total, leftFirst.total);
  const ObjectiveTerms bothSecond = runEpisode(Character::Biped, g, s, 0.5, 1, 1);
  EXPECT_EQ(bothSecond.total, rightSecond.total);  // walked, and judged, turning right
  EXPECT_NE(bothSecond.total, leftSecond.total);
}

// turnStraight: start states cycle through a turn at turnRate, one at −turnRate and a straight
// walk, so that a search of a gait's turns also meets its straight walk.
TEST(OptimizeObjective, TurnStraightCyclesLeftRightAndStraight) {
  using gaitlab::gait::Character;
  ObjectiveSettings s;
  s.seconds = 2.0;
  s.turnRate = 0.5;
  s.turnBothWays = 1.0;  // overridden
  s.turnStraight = 1.0;
  for (int start = 0; start < 6; ++start)
    EXPECT_EQ(episodeTurnRate(s, start), start % 3 == 0 ? 0.5 : start % 3 == 1 ? -0.5 : 0.0) << start;
  const gaitlab::gait::Gait g = gaitlab::gait::defaultGait(Character::Biped);
  const ObjectiveTerms straightThird = runEpisode(Character::Biped, g, s, 0.5, 2, 1);
  ObjectiveSettings straight = s;
  straight.turnStraight = 0.0;
  straight.turnBothWays = 0.0;
  straight.turnRate = 0.0;
  EXPECT_EQ(straightThird.total, runEpisode(Character::Biped, g, straight, 0.5, 2, 1).total);  // walked straight
  ObjectiveSettings left = straight;
  left.turnRate = 0.5;
  EXPECT_NE(straightThird.total, runEpisode(Character::Biped, g, left, 0.5, 2, 1).total);
}

TEST(OptimizeObjective, SettingsAreCheckedAgainstTheirBounds) {
  ObjectiveSettings s;
  EXPECT_EQ(setSetting(s, "wr", 4.0), "");
  EXPECT_EQ(s.wr, 4.0);
  EXPECT_NE(setSetting(s, "wr", -1.0).find("outside"), std::string::npos);
  EXPECT_NE(setSetting(s, "wobble", 1.0).find("unknown"), std::string::npos);
  EXPECT_EQ(setSetting(s, "starts", 3.0), "");
  EXPECT_EQ(s.starts, 3);
}

// Grounds ("slope@3.14159"): a terrain name, optionally a start heading; anything else is
// refused with a message that names the field.
TEST(OptimizeObjective, GroundsAreParsedAndBadOnesRefusedNamingTheField) {
  Ground g;
  EXPECT_EQ(parseGround("slope@3.14159", &g), "");
  EXPECT_EQ(g.terrain, physics::TerrainKind::Slope);
  EXPECT_EQ(g.heading, 3.14159);
  EXPECT_EQ(groundText(g), "slope@3.14159");
  EXPECT_EQ(parseGround("bumps", &g), "");
  EXPECT_EQ(g.terrain, physics::TerrainKind::Bumps);
  EXPECT_EQ(g.heading, 0.0);
  EXPECT_EQ(groundText(g), "bumps");
  const Ground before = g;
  for (const char* bad : {"hill", "", "Slope", "slope@", "slope@down", "slope@1x", "slope@9", "slope@nan"}) {
    SCOPED_TRACE(bad);
    const std::string error = parseGround(bad, &g);
    EXPECT_EQ(error.rfind("grounds: ", 0), 0u) << error;
    EXPECT_EQ(g.terrain, before.terrain);  // nothing of a refused ground is used
  }
  EXPECT_NE(parseGround("hill", &g).find("'hill' is not flat, slope or bumps"), std::string::npos);
  // The default is the flat ground every search before grounds walked, and settingsJson records it.
  ObjectiveSettings s;
  ASSERT_EQ(s.grounds.size(), 1u);
  EXPECT_EQ(s.grounds[0].terrain, physics::TerrainKind::Flat);
  EXPECT_EQ(s.grounds[0].heading, 0.0);
  EXPECT_NE(settingsJson(s).find(R"("grounds":["flat"])"), std::string::npos) << settingsJson(s);
}

// ---- searches ----------------------------------------------------------------------------------

namespace {

SearchOptions quickSearch(Method method, int threads) {
  SearchOptions o;
  o.character = gait::Character::Biped;
  o.method = method;
  o.candidates = 4;
  o.seed = 99;
  o.threads = threads;
  o.objective.seconds = 1.5;
  o.objective.warmup = 0.5;
  return o;
}

struct Outcome {
  gait::GaitParams best;
  double objective;
  int mismatches;
};

Outcome search(const SearchOptions& o, int generations) {
  auto opt = Optimizer::create(o, gait::defaultParams(o.character));
  for (int g = 0; g < generations; ++g) opt->step();
  EXPECT_EQ(opt->evaluations(), generations * o.candidates);
  return {opt->best(), opt->bestObjective(), opt->determinismMismatches()};
}

// The biped preset with its leg-frame and joint gains detuned and a slow period: it falls
// early, so a short search has room to improve on it.
gait::GaitParams detunedBiped() {
  gait::GaitParams start = gait::defaultParams(gait::Character::Biped);
  start.legFrames[0].orientationKp *= 0.3;
  start.legFrames[0].heightKp *= 0.5;
  start.gains.hipKp *= 0.5;
  start.period = 1.6;
  start.speedProportionalGain = 0;  // the speed term steadies it enough to stay up for the 3 s
  return start;
}

}  // namespace

TEST(OptimizeSearch, TheSameSeedGivesTheSameSearchBitForBitWhateverTheThreadCount) {
  for (Method m : {Method::Greedy, Method::CmaEs}) {
    SCOPED_TRACE(methodName(m));
    const Outcome a = search(quickSearch(m, 1), 3);
    const Outcome b = search(quickSearch(m, 1), 3);
    const Outcome c = search(quickSearch(m, 2), 3);
    EXPECT_EQ(std::memcmp(&a.best, &b.best, sizeof(a.best)), 0);
    EXPECT_EQ(std::memcmp(&a.best, &c.best, sizeof(a.best)), 0);
    EXPECT_EQ(a.objective, b.objective);
    EXPECT_EQ(a.objective, c.objective);
    EXPECT_EQ(a.mismatches, 0);  // the re-evaluated incumbent scored the same every time
  }
  // A different seed draws different candidates.
  SearchOptions other = quickSearch(Method::Greedy, 1);
  other.seed = 100;
  // From a gait that falls, so that both searches find improvements (from a preset that walks
  // a short search may find none, whatever it draws).
  auto a = Optimizer::create(quickSearch(Method::Greedy, 1), detunedBiped());
  auto b = Optimizer::create(other, detunedBiped());
  for (int g = 0; g < 4; ++g) {
    a->step();
    b->step();
  }
  EXPECT_NE(a->bestObjective(), b->bestObjective());
}

// Episodes on terrain: the ground and the start heading reach the episode (the slope downhill
// scores differently from flat ground), and a search over several grounds is as reproducible
// as one over flat ground.
TEST(OptimizeSearch, GroundsAreWalkedAndTheSearchStaysReproducible) {
  const gait::Gait preset = gait::defaultGait(gait::Character::Biped);
  ObjectiveSettings s;
  s.seconds = 1.5;
  s.warmup = 0.5;
  const ObjectiveTerms flat = evaluate(gait::Character::Biped, preset, s, 5);
  ASSERT_EQ(parseGround("slope@3.14159", &s.grounds[0]), "");
  const ObjectiveTerms down = evaluate(gait::Character::Biped, preset, s, 5);
  EXPECT_NE(flat.total, down.total);
  EXPECT_EQ(down.total, evaluate(gait::Character::Biped, preset, s, 5).total);
  // Two grounds: the mean of the two single-ground objectives.
  Ground slope = s.grounds[0];
  s.grounds = {Ground{}, slope};
  const ObjectiveTerms both = evaluate(gait::Character::Biped, preset, s, 5);
  EXPECT_DOUBLE_EQ(both.total, (flat.total + down.total) / 2);

  SearchOptions o = quickSearch(Method::Greedy, 1);
  o.objective.seconds = 1.0;
  o.objective.grounds = {Ground{}, slope};
  const Outcome a = search(o, 2);
  o.threads = 2;
  const Outcome b = search(o, 2);
  EXPECT_EQ(std::memcmp(&a.best, &b.best, sizeof(a.best)), 0);
  EXPECT_EQ(a.objective, b.objective);
  EXPECT_EQ(a.mismatches, 0);
  EXPECT_EQ(b.mismatches, 0);
}

// Box-hit episodes (boxHits): each is one throw of the box-hit trial (sim/box_hits.h); its only
// term is the fall penalty, and they count in the mean beside the walking episodes. A crate of
// the demo's size knocks over a biped on some of these throws and not on others, so the count
// of falls is the trial's, throw for throw.
TEST(OptimizeObjective, BoxHitEpisodesScoreOnlyTheirFalls) {
  const gait::Gait preset = gait::defaultGait(gait::Character::Biped);
  ObjectiveSettings s;
  s.seconds = 1.5;
  s.warmup = 0.5;
  s.speeds = {0.5};
  const ObjectiveTerms walking = evaluate(gait::Character::Biped, preset, s, 5);
  ASSERT_FALSE(walking.fell);
  s.boxHits = 8;
  int falls = 0;
  double penalties = 0;
  for (int k = 0; k < s.boxHits; ++k) {
    const ObjectiveTerms t = runBoxHitEpisode(gait::Character::Biped, preset, s, 0.5, k, 5);
    EXPECT_EQ(t.fd + t.fv + t.fa + t.fr + t.ft + t.ff, 0.0);
    EXPECT_EQ(t.total, t.fall);
    if (t.fell) {
      ++falls;
      // Knocked over within the 3 s a hit is judged: between one and two fall penalties.
      EXPECT_GT(t.fall, s.fallPenalty);
      EXPECT_LE(t.fall, 2 * s.fallPenalty);
    } else {
      EXPECT_EQ(t.fall, 0.0);
    }
    penalties += t.fall;
    // The same throw again: the same outcome, bit for bit.
    EXPECT_EQ(t.total, runBoxHitEpisode(gait::Character::Biped, preset, s, 0.5, k, 5).total);
  }
  // The shipped biped is knocked over by some of the demo's boxes, not all (about 1 in 4).
  EXPECT_GT(falls, 0);
  EXPECT_LT(falls, s.boxHits);
  // The mean over 1 walking episode and 8 box-hit episodes.
  const ObjectiveTerms both = evaluate(gait::Character::Biped, preset, s, 5);
  EXPECT_DOUBLE_EQ(both.total, (walking.total + penalties) / 9);
  EXPECT_TRUE(both.fell);
}

TEST(OptimizeSearch, GreedyKeepsTheBestAndNeverGetsWorse) {
  auto opt = Optimizer::create(quickSearch(Method::Greedy, 1), gait::defaultParams(gait::Character::Biped));
  double last = opt->step().bestObjective;
  for (int g = 0; g < 4; ++g) {
    const Generation gen = opt->step();
    EXPECT_LE(gen.bestObjective, last);
    EXPECT_EQ(gen.improved, gen.bestObjective < last);
    last = gen.bestObjective;
  }
  // The best parameters score what the search says they score.
  const ObjectiveTerms again = opt->score(opt->best());
  EXPECT_EQ(again.total, opt->bestObjective());
}

TEST(OptimizeSearch, AShortSearchImprovesADetunedGait) {
  // The detuned biped falls early. Eight greedy generations must find something better.
  const gait::GaitParams start = detunedBiped();
  SearchOptions o = quickSearch(Method::Greedy, 2);
  o.candidates = 6;
  o.objective.seconds = 3.0;
  o.objective.warmup = 1.0;
  auto opt = Optimizer::create(o, start);
  const Generation first = opt->step();
  ASSERT_TRUE(first.bestTerms.fell) << "the detuned start is meant to fall";
  for (int g = 1; g < 8; ++g) opt->step();
  EXPECT_LT(opt->bestObjective(), first.bestObjective);
  EXPECT_GT(opt->bestTerms().seconds, first.bestTerms.seconds) << "it stays up longer";
  // Every parameter of the result is within the schema's bounds.
  gait::GaitParams best = opt->best();
  gait::forEachParam(gait::Character::Biped, best, [](const gait::ParamField& f) {
    for (int k = 0; k < f.spec.knots; ++k) {
      EXPECT_GE(f.values[k], f.spec.min);
      EXPECT_LE(f.values[k], f.spec.max);
    }
  });
}

// Held parameters (SearchOptions::held, `gaitlab optimize --hold`): a search for another gait
// keeps its footfall pattern. Every leg's step trigger and the pitch graph are held; the same
// search from the detuned biped still improves, by the parameters it may change.
TEST(OptimizeSearch, HeldParametersStayAsTheyStartWhileTheRestIsSearched) {
  const gait::GaitParams start = detunedBiped();
  for (Method m : {Method::Greedy, Method::CmaEs}) {
    SCOPED_TRACE(methodName(m));
    SearchOptions o = quickSearch(m, 2);
    o.candidates = 6;
    o.objective.seconds = 3.0;
    o.held = {"stepTrigger", "legFrame.pitch"};
    auto opt = Optimizer::create(o, start);
    const double first = opt->step().bestObjective;
    for (int g = 1; g < 8; ++g) opt->step();
    EXPECT_LT(opt->bestObjective(), first);
    const gait::GaitParams& best = opt->best();
    for (int l = 0; l < 2; ++l) EXPECT_EQ(best.legs[l].stepTrigger, start.legs[l].stepTrigger);
    for (int k = 0; k < gait::MotionGraph::kKnots; ++k)
      EXPECT_EQ(best.legFrames[0].pitch.knots[k], start.legFrames[0].pitch.knots[k]);
    // ... while what is not held moved.
    const std::vector<double> a = gait::toVector(gait::Character::Biped, start);
    const std::vector<double> b = gait::toVector(gait::Character::Biped, best);
    EXPECT_NE(a, b);
  }
}

// The start is the best until a candidate beats it (Optimizer::startTerms): from the walking
// preset, candidates drawn half the parameter ranges away all score worse, and both methods then
// return the start itself, not the least bad of them.
TEST(OptimizeSearch, ASearchNeverReturnsAGaitScoringWorseThanItsStart) {
  const gait::GaitParams start = gait::defaultParams(gait::Character::Biped);
  for (Method m : {Method::Greedy, Method::CmaEs}) {
    SCOPED_TRACE(methodName(m));
    SearchOptions o = quickSearch(m, 2);
    o.stepScale = 0.5;
    o.perturbProbability = 1.0;
    auto opt = Optimizer::create(o, start);
    const double own = opt->startTerms().total;
    EXPECT_EQ(opt->evaluations(), 0) << "the start is scored outside the search's evaluations";
    for (int g = 0; g < 2; ++g) {
      const Generation gen = opt->step();
      EXPECT_FALSE(gen.improved) << "generation " << gen.index << " scored " << gen.bestObjective << " against " << own;
    }
    EXPECT_EQ(opt->bestObjective(), own);
    EXPECT_EQ(opt->startTerms().total, own) << "the start's terms stay the start's";
    EXPECT_EQ(gait::toVector(gait::Character::Biped, opt->best()), gait::toVector(gait::Character::Biped, start));
  }
}

// What no episode measures is held too (unmeasuredParameters): the turn's parameters act only
// while the goal turns, so a search without a turn rate leaves them as they start, and a search
// with one moves them with the rest (CMA-ES's winners move every free coordinate). The biped's
// schema has no turnRollMoment (it acts in the stance of several leg frames): never a coordinate
// of its searches, it stays as it starts either way.
TEST(OptimizeSearch, TheTurnsParametersAreHeldUnlessTheEpisodesTurn) {
  gait::GaitParams start = detunedBiped();
  start.maxTurnSlip = 1.0;  // inside their bounds, where a move is not clamped away
  start.turnPlacement = 0.5;
  start.turnRollMoment = 1.0;
  for (const double turn : {0.0, 0.5}) {
    SCOPED_TRACE(turn);
    SearchOptions o = quickSearch(Method::CmaEs, 2);
    o.candidates = 6;
    o.objective.seconds = 3.0;
    o.objective.turnRate = turn;
    auto opt = Optimizer::create(o, start);
    const double first = opt->step().bestObjective;
    for (int g = 1; g < 6; ++g) opt->step();
    ASSERT_LT(opt->bestObjective(), first) << "the search found nothing better";
    const gait::GaitParams& best = opt->best();
    const bool held = turn == 0;
    EXPECT_EQ(best.maxTurnSlip == start.maxTurnSlip, held) << best.maxTurnSlip;
    EXPECT_EQ(best.turnPlacement == start.turnPlacement, held) << best.turnPlacement;
    EXPECT_EQ(best.turnRollMoment, start.turnRollMoment);
    EXPECT_NE(best.period, start.period);
  }
  EXPECT_EQ(unmeasuredParameters(gait::Character::Biped, ObjectiveSettings{}),
            (std::vector<std::string>{"maxTurnSlip", "turnPlacement"}));
  EXPECT_EQ(unmeasuredParameters(gait::Character::Quadruped, ObjectiveSettings{}),
            (std::vector<std::string>{"maxTurnSlip", "turnPlacement", "turnRollMoment"}));
}

TEST(OptimizeSearch, HeldNamesAreParametersOrFieldsAndOthersAreRefused) {
  std::vector<bool> mask;
  EXPECT_EQ(heldCoordinates(gait::Character::Quadruped, {"frontLeft.stepTrigger"}, &mask), "");
  EXPECT_EQ(std::count(mask.begin(), mask.end(), true), 1);
  EXPECT_EQ(heldCoordinates(gait::Character::Quadruped, {"stepTrigger"}, &mask), "");
  EXPECT_EQ(std::count(mask.begin(), mask.end(), true), 4);  // one per leg
  EXPECT_EQ(heldCoordinates(gait::Character::Quadruped, {"front.pitch", "period"}, &mask), "");
  EXPECT_EQ(std::count(mask.begin(), mask.end(), true), gait::MotionGraph::kKnots + 1);
  const std::string error = heldCoordinates(gait::Character::Biped, {"period", "frontLeft.stepTrigger"}, &mask);
  EXPECT_NE(error.find("'frontLeft.stepTrigger' is not a parameter of the biped"), std::string::npos) << error;
  EXPECT_EQ(std::count(mask.begin(), mask.end(), true), gait::MotionGraph::kKnots + 1) << "unchanged on a refusal";
}

// A search told to hold a name its character lacks is refused, rather than run with nothing held.
TEST(OptimizeSearch, ASearchHoldingANameThatIsNotAParameterIsRefused) {
  SearchOptions o;
  o.character = gait::Character::Biped;
  o.held = {"period", "frontLeft.stepTrigger"};
  EXPECT_THROW(Optimizer::create(o, gait::defaultParams(o.character)), std::invalid_argument);
  o.held = {"period"};
  EXPECT_NO_THROW(Optimizer::create(o, gait::defaultParams(o.character)));
}

TEST(OptimizeSearch, TheTunedKeyIsTheOneTheGoalSpeedsWalkWithMost) {
  const gait::Gait biped = gait::defaultGait(gait::Character::Biped);  // keys 0, 0.15, 0.5, 1.4, 1.8, 2.5
  ASSERT_GE(biped.keyAt(0.5), 0);
  EXPECT_EQ(tunedKey(biped, {0.4}), biped.keyAt(0.5)) << "a slow walk blends the keys at 0.15 and 0.5";
  EXPECT_EQ(tunedKey(biped, {1.0}), biped.primary) << "the primary key at 1.4 is the nearest to 1.0";
  EXPECT_EQ(tunedKey(biped, {-0.3, 0.7}), biped.keyAt(0.5)) << "by the mean of the magnitudes";
  EXPECT_EQ(tunedKey(biped, {2.4}), biped.keyAt(2.5));
  EXPECT_EQ(tunedKey(gait::Gait::single(gait::defaultParams(gait::Character::Biped), 1.4), {0.1}), 0);
}
