// Aiming a thrown box at a moving character (intercept.h).
#include "sim/intercept.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::sim {

Eigen::Vector3d predictedPosition(const Eigen::Vector3d& at, const Eigen::Vector3d& velocity,
                                  double turnRate, double t) {
  const double vx = velocity.x(), vz = velocity.z();
  const double turned = turnRate * t;
  if (std::abs(turned) < 1e-9) return at + t * Eigen::Vector3d(vx, 0, vz);
  // Heading ψ with forward (sin ψ, 0, cos ψ) (gait/heading.h): integrating s·forward(ψ + ω·τ)
  // over [0, t] gives (s/ω)·(cos ψ − cos(ψ + ωt), sin(ψ + ωt) − sin ψ), written with the
  // velocity's components (s·sin ψ = vx, s·cos ψ = vz) to need no angle: turning left (ω > 0)
  // from +z bends the path towards +x.
  const double c = std::cos(turned), s = std::sin(turned);
  const double dx = (vx * s + vz * (1 - c)) / turnRate;
  const double dz = (vz * s - vx * (1 - c)) / turnRate;
  return at + Eigen::Vector3d(dx, 0, dz);
}

Eigen::Vector3d ballisticVelocity(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double t,
                                  const Eigen::Vector3d& gravity, double substep) {
  return (to - from) / t - 0.5 * (t + substep) * gravity;
}

Intercept interceptThrow(const Eigen::Vector3d& from, const Eigen::Vector3d& at,
                         const Eigen::Vector3d& velocity, double turnRate, double speed,
                         const Eigen::Vector3d& gravity, double substep, double minFlight) {
  double t = std::max(minFlight, (at - from).norm() / speed);
  Eigen::Vector3d aim = predictedPosition(at, velocity, turnRate, t);
  // A contraction by |v|/speed a round: 8 rounds take a 1 m/s walker and a 14 m/s box to
  // (1/14)^8 of the first guess's error, far below a millimetre.
  for (int i = 0; i < 8; ++i) {
    t = std::max(minFlight, (aim - from).norm() / speed);
    aim = predictedPosition(at, velocity, turnRate, t);
  }
  return {aim, t, ballisticVelocity(from, aim, t, gravity, substep)};
}

}  // namespace gaitlab::sim
