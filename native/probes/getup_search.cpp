// Probe, built only on request (`ninja -C build/native gaitlab_getup_search`): CMA-ES (Hansen
// 2016, the tutorial's update with its default weights) over one routine of the get-up on two
// legs (gait/get_up_two_legs.h), the biped laid down still on its back, front or left side and
// rolled by −10°, −5°, 0, 5° and 10° about its long axis. Each candidate runs as the controller
// runs it (waiting to lie still, the routine, the hand-over to the stand); the score, averaged
// over the five starts, over the last second of the run:
//   - back: how high and upright the torso stands (its centre's height / 1.16 m times its up
//     axis's height), plus a tenth of the best of that over the run;
//   - front, side: how squarely it lies on its back (the forward axis's height), plus a tenth of
//     the best. (Not less while it turns: lying on the ground its bodies read angular velocities
//     of several rad/s that the contacts cancel.)
// Prints the best so far every 10 generations and writes it, 12 numbers a key in GetUpKey's
// order, to /tmp/getup-LYING-SEED.txt. With GENERATIONS 0 it scores START_FILE and prints the run.
// With STARTS_FILE (written by getup_log.cpp from real falls) the starts are the first COUNT
// bodies in it instead of the five laid down, every other one at goal 0 and the rest at
// GOAL_SPEED, each watched kHold s after the routine. With HORIZON, every run lasts HORIZON s
// from the start, however long the routine, and is scored over its last second: a routine that
// takes longer has less time to stand (the get-up is judged 10 s after a fall). With
// OTHERS_PREFIX the whole get-up runs, the other two routines read from PREFIX-back.txt,
// -front.txt and -side.txt, and every run is scored on how the torso stands, as for the kip-up:
// with starts taken at the moment of a fall (with their velocities), what the benchmark judges.
//
//   build/native/gaitlab_getup_search back|front|side KEYS GENERATIONS SEED [START_FILE] [SIGMA] [POPULATION] [GOAL_SPEED] [STARTS_FILE COUNT] [HORIZON] [OTHERS_PREFIX]
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <array>
#include <random>
#include <string>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "gait/heading.h"
#include "optimize/cma_es.h"
#include "sim/simulation.h"
#include "sim/walk_trial.h"

using namespace gaitlab;

namespace {

std::string gLying = "back";
int gKeys = 5;
double gGoalSpeed = 0.0;
bool gVerbose = false;
constexpr double kHold = 4.0;  // s after the routine's keys
double gHorizon = 0;           // s a run lasts, if not 0
// Starts from real falls (STARTS_FILE): per start, every body's position, orientation and
// velocities (zero where the file gives none).
std::vector<std::vector<std::array<double, 13>>> gStarts;
// The whole get-up (OTHERS_PREFIX): the routines not searched, from PREFIX-back.txt, -front.txt and
// -side.txt; every run is then scored on how the torso stands, whatever the routine searched.
std::vector<gait::GetUpKey> gOthers[3];
bool gWhole = false;
constexpr int kPerKey = 12;

// A key's numbers in GetUpKey's order and their bounds: seconds, gain, hip, knee, ankle, twist,
// outwards (each of the last five for both legs).
void bounds(int j, double* lo, double* hi) {
  static const double l[kPerKey] = {0.15, 0.3, -0.7, -0.7, 0.0, 0.0, -0.9, -0.9, -0.5, -0.5, -0.6, -0.6};
  static const double h[kPerKey] = {1.5, 2.0, 2.0, 2.0, 2.4, 2.4, 0.9, 0.9, 0.5, 0.5, 0.6, 0.6};
  *lo = l[j];
  *hi = h[j];
}

bool searched(int j) { return gLying == "side" || j < 8; }  // on its back or front the hips neither twist nor swing out

gait::GetUpKey keyOf(const double* x) {
  return gait::GetUpKey{x[0], x[1], {x[2], x[3]}, {x[4], x[5]}, {x[6], x[7]}, {x[8], x[9]}, {x[10], x[11]}};
}

// Moves one body to `t` with velocities v and w, as if it had been there (the interpolation and
// the motion state too, which the render and the next step read).
void place(btRigidBody* b, const btTransform& t, const btVector3& v, const btVector3& w) {
  b->setWorldTransform(t);
  b->setInterpolationWorldTransform(t);
  if (b->getMotionState()) b->getMotionState()->setWorldTransform(t);
  b->setLinearVelocity(v);
  b->setAngularVelocity(w);
  b->setInterpolationLinearVelocity(v);
  b->setInterpolationAngularVelocity(w);
  b->activate(true);
}

// The biped, standing as spawned, turned as a rigid whole to lie on its back, front or left
// side, rolled by `roll` about its long axis, and lowered onto the ground, at rest.
void layDown(sim::Simulation& sim, double roll) {
  physics::Character& c = sim.character(0);
  Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
  if (gLying == "front") r = Eigen::AngleAxisd(gait::kPi / 2, Eigen::Vector3d::UnitX());
  if (gLying == "back") r = Eigen::AngleAxisd(-gait::kPi / 2, Eigen::Vector3d::UnitX());
  if (gLying == "side") r = Eigen::AngleAxisd(gait::kPi / 2, Eigen::Vector3d::UnitZ());
  r = Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()) * r;
  const btVector3 pivot = c.body(0)->getWorldTransform().getOrigin();
  const btQuaternion q(r.x(), r.y(), r.z(), r.w());
  const btTransform rotation(q, btVector3(0, 0, 0));
  double lowest = 1e9;
  for (int k = 0; k < c.segmentCount(); ++k) {
    btRigidBody* b = c.body(k);
    btTransform t = b->getWorldTransform();
    t.setOrigin(pivot + rotation(t.getOrigin() - pivot));
    t.setRotation(q * t.getRotation());
    b->setWorldTransform(t);
    btVector3 low, high;
    b->getCollisionShape()->getAabb(t, low, high);
    lowest = std::min(lowest, static_cast<double>(low.y()));
  }
  for (int k = 0; k < c.segmentCount(); ++k) {
    btTransform t = c.body(k)->getWorldTransform();
    t.setOrigin(t.getOrigin() + btVector3(0, 0.01 - lowest, 0));
    place(c.body(k), t, btVector3(0, 0, 0), btVector3(0, 0, 0));
  }
}

// Puts every body where a start from a real fall had it, moving as it was.
void placeAt(sim::Simulation& sim, const std::vector<std::array<double, 13>>& start) {
  physics::Character& c = sim.character(0);
  for (int k = 0; k < c.segmentCount() && k < static_cast<int>(start.size()); ++k) {
    const std::array<double, 13>& p = start[k];
    place(c.body(k), btTransform(btQuaternion(p[3], p[4], p[5], p[6]), btVector3(p[0], p[1] + 0.005, p[2])),
          btVector3(p[7], p[8], p[9]), btVector3(p[10], p[11], p[12]));
  }
}

double evaluateOne(const std::vector<double>& x, double roll, int startIndex = -1) {
  std::vector<gait::GetUpKey> keys;
  double total = 0;
  for (int k = 0; k < gKeys; ++k) {
    keys.push_back(keyOf(&x[kPerKey * k]));
    total += keys.back().seconds;
  }
  sim::Simulation sim(1, 7);
  sim::WalkOptions o;
  o.character = sim::Character::Biped;
  o.speed = startIndex >= 0 && startIndex % 2 == 0 ? 0.0 : gGoalSpeed;
  sim::setUpWalk(sim, o);
  const gait::Lying lying = gLying == "back" ? gait::Lying::OnBack : gLying == "front" ? gait::Lying::OnFront : gait::Lying::OnSide;
  for (gait::Lying l : {gait::Lying::OnBack, gait::Lying::OnFront, gait::Lying::OnSide}) {
    const bool bySide = l == gait::Lying::OnSide;
    const std::vector<gait::GetUpKey>& other = gOthers[static_cast<int>(l)];
    sim.controller(0).setGetUpRoutine(l, l == lying ? gait::GetUpRoutine{keys.data(), gKeys, bySide}
                                         : gWhole ? gait::GetUpRoutine{other.data(), static_cast<int>(other.size()), bySide}
                                                  : gait::GetUpRoutine{});
  }
  if (startIndex >= 0) placeAt(sim, gStarts[startIndex]);
  else layDown(sim, roll);
  const int steps = static_cast<int>((gHorizon > 0 ? gHorizon : 0.6 + total + kHold) / physics::kFixedStep);
  const int lastSecond = static_cast<int>(1.0 / physics::kFixedStep);
  double score = 0, best = 0;
  for (int i = 0; i < steps; ++i) {
    sim.step(1);
    const physics::SegmentState st = sim.character(0).segmentState(0);
    const double up = (st.orientation * Eigen::Vector3d::UnitY()).y();
    const double forward = (st.orientation * Eigen::Vector3d::UnitZ()).y();
    const double h = st.position.y();
    const double v = lying == gait::Lying::OnBack || gWhole
                         ? std::min(1.0, h / 1.16) * std::max(0.0, up)
                         : std::max(0.0, forward);
    best = std::max(best, v);
    if (i >= steps - lastSecond) score += v / lastSecond;
    if (gVerbose && i % 12 == 0)
      std::printf("t %5.2f down %d torso height %.2f up %5.2f forward %5.2f score %.2f\n", sim.time(),
                  sim.controller(0).down() ? 1 : 0, h, up, forward, v);
  }
  return score + 0.1 * best;
}

double evaluate(const std::vector<double>& x) {
  if (!gStarts.empty()) {
    double sum = 0;
    for (size_t k = 0; k < gStarts.size(); ++k) {
      const double v = evaluateOne(x, 0, static_cast<int>(k));
      if (gVerbose) std::printf("start %zu score %.3f\n", k, v);
      sum += v;
    }
    return sum / gStarts.size();
  }
  constexpr int kStarts = 5;
  double sum = 0;
  for (int k = 0; k < kStarts; ++k) {
    const double roll = (k - 0.5 * (kStarts - 1)) * 0.35 / (kStarts - 1);  // −10° … 10°
    if (gVerbose) std::printf("rolled %.0f°\n", roll * 180 / gait::kPi);
    sum += evaluateOne(x, roll);
  }
  return sum / kStarts;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: gaitlab_getup_search back|front|side KEYS GENERATIONS SEED [START_FILE] [SIGMA] [POPULATION] [GOAL_SPEED]\n");
    return 2;
  }
  gLying = argv[1];
  if (gLying != "back" && gLying != "front" && gLying != "side") {
    std::fprintf(stderr, "%s: not back, front or side\n", argv[1]);
    return 2;
  }
  gKeys = std::max(1, std::atoi(argv[2]));
  if (argc > 8) gGoalSpeed = std::atof(argv[8]);
  if (argc > 11) gHorizon = std::atof(argv[11]);
  if (argc > 12) {
    gWhole = true;
    const char* names[3] = {"back", "front", "side"};  // gait::Lying's order
    for (int l = 0; l < 3; ++l) {
      FILE* f = std::fopen((std::string(argv[12]) + "-" + names[l] + ".txt").c_str(), "r");
      double v[kPerKey];
      while (f && std::fscanf(f, "%lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                              &v[6], &v[7], &v[8], &v[9], &v[10], &v[11]) == kPerKey)
        gOthers[l].push_back(keyOf(v));
      if (f) std::fclose(f);
      if (gOthers[l].empty()) {
        std::fprintf(stderr, "%s-%s.txt: no keys\n", argv[12], names[l]);
        return 2;
      }
    }
  }
  if (argc > 10) {
    FILE* f = std::fopen(argv[9], "r");
    if (!f) {
      std::fprintf(stderr, "%s: cannot read\n", argv[9]);
      return 2;
    }
    const int count = std::atoi(argv[10]);
    char line[256];
    while (std::fgets(line, sizeof line, f)) {
      if (std::strncmp(line, "start", 5) == 0) {
        if (static_cast<int>(gStarts.size()) == count) break;
        gStarts.emplace_back();
        continue;
      }
      std::array<double, 13> p{};  // position, orientation and, if given, velocities
      const int read = std::sscanf(line, "%lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", &p[0], &p[1], &p[2], &p[3],
                                   &p[4], &p[5], &p[6], &p[7], &p[8], &p[9], &p[10], &p[11], &p[12]);
      if (!gStarts.empty() && read >= 7) gStarts.back().push_back(p);
    }
    std::fclose(f);
  }
  const int generations = std::atoi(argv[3]);
  const unsigned seed = static_cast<unsigned>(std::atoi(argv[4]));
  const int n = kPerKey * gKeys;
  std::vector<double> lo(n), hi(n);
  for (int i = 0; i < n; ++i) bounds(i % kPerKey, &lo[i], &hi[i]);
  auto decode = [&](const Eigen::VectorXd& z) {
    std::vector<double> x(n);
    for (int i = 0; i < n; ++i) {
      double u = z[i];
      u = std::fmod(std::abs(u), 2.0);
      if (u > 1) u = 2 - u;  // reflect into [0, 1]
      x[i] = searched(i % kPerKey) ? lo[i] + u * (hi[i] - lo[i]) : 0.0;
    }
    return x;
  };
  Eigen::VectorXd mean = Eigen::VectorXd::Constant(n, 0.5);
  if (argc > 5) {
    FILE* f = std::fopen(argv[5], "r");
    for (int i = 0; i < n && f; ++i) {
      double v;
      if (std::fscanf(f, "%lf", &v) == 1) mean[i] = (v - lo[i]) / (hi[i] - lo[i]);
    }
    if (f) std::fclose(f);
    if (generations == 0) {
      gVerbose = true;
      std::printf("score %.4f\n", evaluate(decode(mean)));
      return 0;
    }
  }
  // CMA-ES (optimize/cma_es.h) in the unit box of the keys' ranges, maximising the score.
  const int lambda = argc > 7 ? std::max(4, std::atoi(argv[7])) : 24;
  optimize::CmaEs cma(mean, argc > 6 ? std::atof(argv[6]) : 0.25, lambda, /*maxSigma=*/1.0);
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  double bestEver = -1, generationBest = -1;
  std::vector<double> bestX;
  for (int g = 0; g < generations; ++g) {
    const std::vector<Eigen::VectorXd>& zs = cma.ask([&] { return normal(rng); });
    std::vector<double> costs(lambda);
    generationBest = -1;
    for (int k = 0; k < lambda; ++k) {
      const std::vector<double> x = decode(zs[k]);
      const double score = evaluate(x);
      costs[k] = -score;
      generationBest = std::max(generationBest, score);
      if (score > bestEver) { bestEver = score; bestX = x; }
    }
    cma.tell(costs);
    if (g % 10 == 0 || g == generations - 1) {
      std::fprintf(stderr, "gen %d best %.4f gen-best %.4f sigma %.3f\n", g, bestEver, generationBest, cma.sigma());
      FILE* out = std::fopen(("/tmp/getup-" + gLying + "-" + std::to_string(seed) + ".txt").c_str(), "w");
      for (int i = 0; i < n; ++i) std::fprintf(out, "%.5f%s", bestX[i], i % kPerKey == kPerKey - 1 ? "\n" : " ");
      std::fclose(out);
    }
  }
  return 0;
}
