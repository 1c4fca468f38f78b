// Probe, built only on request (`ninja -C build/native gaitlab_walk_log`): one biped walking on a
// terrain, logged every fixed step, to see how and when it falls (docs/terrain.md).
//
//   build/native/gaitlab_walk_log TERRAIN SPEED SECONDS [HEADING] [SEED] [PUSH_T PUSH_LEFT] > log.txt
//
// With PUSH_T and PUSH_LEFT: an impulse of PUSH_LEFT N·s to the left (heading frame; negative:
// right) at the leg frame at time PUSH_T s, as the walking benchmark's lateral pushes.
//
// Per line: time; leg frame x, z, height above the ground under it, pitch and roll (degrees, in
// the heading frame) and velocity forward and left (m/s); then per leg: S (stance) or w (swing)
// and its progress, the lowest sole point's gap to the ground, the foot's pitch (+ = toe up) and
// roll (degrees, heading frame), the heel's and the toe's gap to the ground, the shin's lean
// (degrees, + = forward), the foot's distance ahead of and to the left of the leg frame, and the ankle torque about
// the foot's x axis (N·m, − = toe up). The line ends in STANDING while it stands on planted feet
// (gait/standing.cpp) and in FALLEN when walk_trial's criterion fires.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <btBulletDynamicsCommon.h>

#include "gait/heading.h"
#include "sim/simulation.h"
#include "sim/walk_trial.h"

using namespace gaitlab;

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: gaitlab_walk_log flat|slope|bumps SPEED SECONDS [HEADING] [SEED]\n");
    return 2;
  }
  physics::TerrainKind kind;
  if (!physics::parseTerrain(argv[1], &kind)) return 2;
  const double speed = std::atof(argv[2]), seconds = std::atof(argv[3]);
  const double heading = argc > 4 ? std::atof(argv[4]) : 0.0;
  const uint32_t seed = argc > 5 ? static_cast<uint32_t>(std::atol(argv[5])) : 1;
  const double pushTime = argc > 7 ? std::atof(argv[6]) : -1.0, pushLeft = argc > 7 ? std::atof(argv[7]) : 0.0;
  sim::Simulation sim(1, seed);
  if (kind != physics::TerrainKind::Flat) sim.setTerrain(kind);
  sim.spawn(gait::Character::Biped, 0, 0, heading);
  sim.setGoal(0, {speed, 0});
  const physics::Character& ch = sim.character(0);
  const body::Morphology& m = ch.morphology();
  const int lf = m.legFrames[0];
  const auto deg = [](double a) { return a * 180 / 3.14159265358979323846; };
  std::printf("# t x z above pitch roll vForward vLeft | per leg: role progress gap footPitch footRoll heel toe shin ahead left ankleTorque\n");
  for (int step = 0; step < seconds * 120; ++step) {
    if (pushTime >= 0 && sim.time() <= pushTime && pushTime < sim.time() + 1.0 / 120) {
      const double h = gait::headingOf(ch.segmentState(lf).orientation);
      const Eigen::Vector3d j = gait::headingLeft(h) * pushLeft;
      sim.character(0).body(lf)->applyCentralImpulse(btVector3(static_cast<btScalar>(j.x()), 0, static_cast<btScalar>(j.z())));
    }
    sim.step(1);
    const auto s = ch.segmentState(lf);
    const double yaw = gait::headingOf(s.orientation);
    const Eigen::Vector3d up = gait::headingQuat(yaw).conjugate() * (s.orientation * Eigen::Vector3d::UnitY());
    const Eigen::Vector3d v = gait::worldToHeading(yaw, s.linearVelocity);
    std::printf("%.3f %.3f %.3f %.3f %6.1f %6.1f %5.2f %5.2f |", sim.time(), s.position.x(), s.position.z(),
                s.position.y() - sim.groundHeight(s.position.x(), s.position.z()), deg(std::atan2(up.z(), up.y())),
                deg(std::atan2(-up.x(), up.y())), v.z(), v.x());
    for (size_t l = 0; l < m.legs.size(); ++l) {
      const body::Leg& leg = m.legs[l];
      const auto f = ch.segmentState(leg.foot);
      const Eigen::Vector3d h = m.segments[leg.foot].halfExtents;
      double gap = 1e9, heel = 1e9, toe = 1e9;
      for (int i = 0; i < 4; ++i) {
        const Eigen::Vector3d p = f.position + f.orientation * Eigen::Vector3d((i & 1 ? 1 : -1) * h.x(), -h.y(), (i & 2 ? 1 : -1) * h.z());
        const double g = p.y() - sim.terrain().height(p.x(), p.z());
        gap = std::min(gap, g);
        (i & 2 ? toe : heel) = std::min(i & 2 ? toe : heel, g);
      }
      const Eigen::Quaterniond fl = gait::headingQuat(yaw).conjugate() * f.orientation;
      const Eigen::Vector3d shin = gait::headingQuat(yaw).conjugate() * (ch.segmentState(leg.lower).orientation * Eigen::Vector3d::UnitY());
      const Eigen::Vector3d torque = f.orientation.conjugate() * sim.lastTorques(0)[leg.foot];
      const auto& state = sim.controller(0).player().leg(static_cast<int>(l));
      const Eigen::Vector3d rel = gait::worldToHeading(yaw, f.position - s.position);
      std::printf(" %c %.2f %6.3f %5.1f %5.1f %6.3f %6.3f %5.1f %6.3f %6.3f %6.1f |", state.stance ? 'S' : 'w', state.progress, gap,
                  deg(std::asin((fl * Eigen::Vector3d::UnitZ()).y())), deg(std::asin((fl * Eigen::Vector3d::UnitX()).y())), heel, toe,
                  deg(std::atan2(shin.z(), shin.y())), rel.z(), rel.x(), torque.x());
    }
    const bool fallen = sim::hasFallen(sim, 0);
    std::printf("%s%s\n", sim.controller(0).standing() ? " STANDING" : "", fallen ? " FALLEN" : "");
    if (fallen) break;
  }
  return 0;
}
