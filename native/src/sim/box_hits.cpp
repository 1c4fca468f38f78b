#include "sim/box_hits.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <btBulletDynamicsCommon.h>

#include "gait/heading.h"
#include "physics/world.h"

namespace gaitlab::sim {

namespace {

constexpr double kMissMargin = 0.3;    // s after the flight time, then a throw is a miss

}  // namespace

int BoxHitResult::falls() const {
  return static_cast<int>(std::count_if(hits.begin(), hits.end(), [](const BoxHit& h) { return h.fell; }));
}

int BoxHitResult::getUps() const {
  return static_cast<int>(std::count_if(hits.begin(), hits.end(), [](const BoxHit& h) { return h.gotUpAfter >= 0; }));
}

namespace {

// After a fall at `fellAt` (simulated time): steps `seconds` more and returns the seconds from the
// fall until the controller last left its get-up (Controller::down; 0 if it never went down, a
// stumble that tipped a leg frame past the fall test's 60° and caught itself), or -1 if at the
// end it is down or fallen.
double watchGetUp(Simulation& sim, double fellAt, double seconds) {
  double upAt = fellAt;
  bool wasDown = sim.controller(0).down();
  const int steps = static_cast<int>(std::lround(seconds / physics::kFixedStep));
  for (int step = 0; step < steps; ++step) {
    sim.step(1);
    const bool down = sim.controller(0).down();
    if (wasDown && !down) upAt = sim.time();
    wasDown = down;
  }
  if (wasDown || hasFallen(sim, 0)) return -1;
  return upAt - fellAt;
}

}  // namespace

double pageThrowSpeed(double distance) { return std::min(30.0, std::max(14.0, distance / 1.0)); }

bool boxTouches(const Simulation& sim, int i) {
  const physics::Character& c = sim.character(i);
  std::set<const btCollisionObject*> own;
  for (int k = 0; k < c.segmentCount(); ++k) own.insert(c.body(k));
  btDispatcher& d = *const_cast<physics::World&>(sim.world(sim.shardOf(i))).dynamics().getDispatcher();
  for (int m = 0; m < d.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = d.getManifoldByIndexInternal(m);
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    if (own.count(b)) std::swap(a, b);
    if (!own.count(a) || own.count(b) || b->isStaticObject()) continue;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      if (manifold->getContactPoint(p).getDistance() < 0.01) return true;
    }
  }
  return false;
}

bool throwBox(const BoxHitOptions& o, TrialDraws& draw, BoxHit* out) {
  Simulation sim(1, o.walk.seed);
  setUpWalk(sim, o.walk);
  // Every draw is taken before the episode runs, so an episode's fall does not shift the next
  // episode's draws.
  const double walkFor = 2.0 + 2.0 * draw.unit();
  const int segment = std::min(sim.character(0).segmentCount() - 1,
                               static_cast<int>(draw.unit() * sim.character(0).segmentCount()));
  const double azimuth = 2 * gait::kPi * draw.unit(), distance = 8 + 10 * draw.unit(), height = 1.5 + 2.5 * draw.unit();

  sim.step(static_cast<int>(std::lround(walkFor / physics::kFixedStep)));
  if (hasFallen(sim, 0)) {  // fell before the throw: the gait, not the box (counted as a fall)
    *out = {segment, sim.time(), 0.0, true, 0.0};
    return true;
  }
  const Eigen::Vector3d trunk = sim.character(0).segmentState(0).position;
  const Eigen::Vector3d from(trunk.x() + distance * std::cos(azimuth), height, trunk.z() + distance * std::sin(azimuth));
  const Eigen::Vector3d target = sim.character(0).segmentState(segment).position;
  const double speed = pageThrowSpeed((target - from).norm());
  const Intercept aim = sim.aimAt(0, segment, Eigen::Vector3d::Zero(), from, speed);
  BoxHit hit{segment, sim.time(), speed, false, -1.0};
  sim.throwBox(from, aim.velocity, o.half);

  bool touched = false;
  const int judgeSteps = static_cast<int>(std::lround(kBoxJudgeSeconds / physics::kFixedStep));
  const int missSteps = static_cast<int>(std::lround((aim.flightTime + kMissMargin) / physics::kFixedStep));
  for (int step = 0; step < judgeSteps; ++step) {
    sim.step(1);
    touched = touched || boxTouches(sim, 0);
    if (!touched && step >= missSteps) break;
    if (touched && hasFallen(sim, 0)) {
      hit.fell = true;
      hit.fallAfter = sim.time() - hit.throwTime;
      if (o.getUpSeconds > 0) hit.gotUpAfter = watchGetUp(sim, sim.time(), o.getUpSeconds);
      break;
    }
  }
  if (touched) *out = hit;
  return touched;
}

BoxHitResult runBoxHits(const BoxHitOptions& o) {
  BoxHitResult r;
  TrialDraws draw(o.walk.seed);
  const int maxThrows = 3 * o.hits;  // misses are rare (the aim leads the walker); never loop forever
  while (static_cast<int>(r.hits.size()) < o.hits && r.throws < maxThrows) {
    ++r.throws;
    BoxHit hit;
    if (throwBox(o, draw, &hit)) r.hits.push_back(hit);
  }
  return r;
}

}  // namespace gaitlab::sim
