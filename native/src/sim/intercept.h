// Aiming a thrown box at a moving character (the demo page's shift-click on a character): the
// throw is computed in the simulation, from the character's simulated state when the throw
// happens, not on the page from a picture that is a frame time and a worker round trip old.
//
// The target moves as a walker does on average over a stride: horizontally, at its centre of
// mass's horizontal velocity, a direction that turns at its goal's turn rate (a wandering
// character's heading drifts at up to 0.3 rad/s, wander.h). Its height is kept: a walker's centre
// of mass bobs a few centimetres about a constant height. The box flies a ballistic arc under
// gravity, integrated as Bullet integrates it (semi-implicit Euler in sub-steps of h seconds), so
// it passes through the aim point at the flight time by construction, not to within the error of
// the continuous formula (g·h·t/2, 2 cm after a second).
#pragma once
#include <Eigen/Core>

namespace gaitlab::sim {

// Where a target now at `at`, moving horizontally at `velocity` (its y ignored) whose direction
// turns at `turnRate` rad/s about +y (positive = left, as gait::Goal), will be after `t` seconds:
// a circular arc of radius |v|/ω, a straight line when ω = 0.
Eigen::Vector3d predictedPosition(const Eigen::Vector3d& at, const Eigen::Vector3d& velocity,
                                  double turnRate, double t);

struct Intercept {
  Eigen::Vector3d aim;       // where the box meets the target, m
  double flightTime;         // s
  Eigen::Vector3d velocity;  // the box's initial velocity, m/s
};

// The throw from `from` that meets the target of predictedPosition at the moment the box
// arrives, the box covering the straight distance at `speed` m/s (as a person throws: harder for
// farther, the flight time the distance over the speed, at least `minFlight` s). The meeting
// time solves t = |p(t) − from| / speed by fixed-point iteration, which converges while the
// target moves slower than the box (a 1 m/s walker, a 14 m/s box: a contraction by 1/14 a round).
// `gravity` is the world's (m/s², pointing down), `substep` Bullet's integration step (s).
Intercept interceptThrow(const Eigen::Vector3d& from, const Eigen::Vector3d& at,
                         const Eigen::Vector3d& velocity, double turnRate, double speed,
                         const Eigen::Vector3d& gravity, double substep, double minFlight = 0.05);

// The initial velocity of a box from `from` that is at `to` after `t` seconds of semi-implicit
// Euler integration under `gravity` in sub-steps of `substep` seconds: after n sub-steps
// x = x0 + t·v0 + g·t·(t + h)/2 (t = n·h), so v0 = (to − from)/t − g·(t + h)/2.
Eigen::Vector3d ballisticVelocity(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double t,
                                  const Eigen::Vector3d& gravity, double substep);

}  // namespace gaitlab::sim
