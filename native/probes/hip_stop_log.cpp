// Probe, built only on request (`ninja -C build/native gaitlab_hip_stop_log`): how much of a walk
// the biped's hips spend against the ends of their swing range (docs/controller-notes.md, "The
// ball joints' ranges were mirrored"). For each goal speed: the share of stance and of swing time
// a hip's swing about x is within 0.05 rad of its forward or backward limit, and the furthest
// it swung each way. The angle is the x angle of the thigh's rotation Rz·Ry·Rx relative to its
// leg frame, the one the physics limits (physics/character.cpp).
//
//   build/native/gaitlab_hip_stop_log [SECONDS] [SPEED...]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "sim/simulation.h"
#include "sim/walk_trial.h"

using namespace gaitlab;

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
  std::vector<double> speeds;
  for (int i = 2; i < argc; ++i) speeds.push_back(std::atof(argv[i]));
  if (speeds.empty()) speeds = {0.0, 0.5, 1.0, 1.6, 2.0, 2.5, 2.9};
  std::printf("goal m/s | stance: at fwd stop, at back stop | swing: at fwd stop, at back stop | furthest fwd, back (rad) | fell\n");
  for (double speed : speeds) {
    sim::WalkOptions o;
    o.character = gait::Character::Biped;
    o.speed = speed;
    sim::Simulation sim(1, 1);
    sim::setUpWalk(sim, o);
    const body::Morphology& m = sim.character(0).morphology();
    double time[2] = {0, 0}, fwd[2] = {0, 0}, back[2] = {0, 0}, furthestFwd = 0, furthestBack = 0;
    bool fell = false;
    const int steps = static_cast<int>(std::lround(seconds / physics::kFixedStep));
    for (int k = 0; k < steps && !fell; ++k) {
      sim.step(1);
      fell = sim::hasFallen(sim, 0);
      if (k * physics::kFixedStep < 2.0) continue;  // the start
      for (size_t l = 0; l < m.legs.size(); ++l) {
        const body::Segment& thigh = m.segments[m.legs[l].upper];
        const Eigen::Matrix3d r = (sim.character(0).segmentState(thigh.parent).orientation.conjugate() *
                                   sim.character(0).segmentState(m.legs[l].upper).orientation).toRotationMatrix();
        const double x = std::atan2(r(2, 1), r(2, 2));  // − forwards
        const int role = sim.controller(0).player().leg(static_cast<int>(l)).stance ? 0 : 1;
        time[role] += 1;
        if (x < thigh.joint.lower[0] + 0.05) fwd[role] += 1;
        if (x > thigh.joint.upper[0] - 0.05) back[role] += 1;
        furthestFwd = std::min(furthestFwd, x);
        furthestBack = std::max(furthestBack, x);
      }
    }
    std::printf("%8.1f | %6.1f %%, %6.1f %% | %6.1f %%, %6.1f %% | %6.2f, %5.2f | %s\n", speed,
                100 * fwd[0] / std::max(1.0, time[0]), 100 * back[0] / std::max(1.0, time[0]),
                100 * fwd[1] / std::max(1.0, time[1]), 100 * back[1] / std::max(1.0, time[1]), -furthestFwd,
                furthestBack, fell ? "yes" : "no");
  }
  return 0;
}
