// Proportional-derivative controllers (thesis §3.1.7, eq. 3.9): f = Kp·e + Kd·de/dt.
//
// The orientation PD fixes defect 4 of the original implementation (docs/original-implementation.md): the original computed the orientation error in
// the body frame but applied the result as a world-frame torque, and never checked for the short
// way round (a quaternion q and −q are the same rotation; without the check the error can be
// the 2π − θ "long way", and the torque flips sign as the rotation passes through π). Here the
// error, both angular velocities and the returned torque are all in WORLD axes, and the error is
// the shortest-arc rotation vector.
#pragma once
#include <Eigen/Dense>
#include <cmath>

namespace gaitlab::gait {

// Eq. 3.9 with the error and its rate given.
inline double pd(double kp, double kd, double error, double errorRate) {
  return kp * error + kd * errorRate;
}

// Eq. 3.9 tracking a desired value: e = desired − current, de/dt = desiredRate − currentRate.
inline double pdTrack(double kp, double kd, double current, double desired, double currentRate,
                      double desiredRate = 0.0) {
  return kp * (desired - current) + kd * (desiredRate - currentRate);
}

// Vector PD (e.g. the swing-foot force F_sw, §3.1.4, or the leg-frame height force F_h).
inline Eigen::Vector3d pdTrack(double kp, double kd, const Eigen::Vector3d& current,
                               const Eigen::Vector3d& desired, const Eigen::Vector3d& currentRate,
                               const Eigen::Vector3d& desiredRate = Eigen::Vector3d::Zero()) {
  return kp * (desired - current) + kd * (desiredRate - currentRate);
}

// Rotation vector (axis · angle, angle in [0, π]) of a unit-or-not quaternion, taking the short
// way: q and −q give the same result. Finite for any input (zero for a zero quaternion).
inline Eigen::Vector3d rotationVector(const Eigen::Quaterniond& qIn) {
  double w = qIn.w();
  Eigen::Vector3d v = qIn.vec();
  if (w < 0.0) {  // shortest arc: −q is the same rotation with w ≥ 0
    w = -w;
    v = -v;
  }
  const double s = v.norm();
  if (!(s > 1e-12)) {
    // Small angle: θ ≈ 2 s / w, so the rotation vector ≈ 2 v / w (w ≈ |q| here).
    return w > 0.0 ? Eigen::Vector3d(2.0 * v / w) : Eigen::Vector3d::Zero();
  }
  // θ = 2·atan2(|v|, w) is exact for non-unit q too (the scale cancels).
  return (2.0 * std::atan2(s, w) / s) * v;
}

// World-frame orientation error: the rotation vector of q_d·q_c⁻¹, i.e. the world-axes rotation
// that takes the current orientation to the desired one (left multiplication = world axes).
inline Eigen::Vector3d orientationError(const Eigen::Quaterniond& current,
                                        const Eigen::Quaterniond& desired) {
  return rotationVector(desired * current.conjugate());
}

// Orientation PD: world torque driving a body from `current` towards `desired`.
// ω's are world-frame angular velocities (what a physics engine reports).
inline Eigen::Vector3d orientationPd(double kp, double kd, const Eigen::Quaterniond& current,
                                     const Eigen::Quaterniond& desired,
                                     const Eigen::Vector3d& omega,
                                     const Eigen::Vector3d& omegaDesired = Eigen::Vector3d::Zero()) {
  return kp * orientationError(current, desired) + kd * (omegaDesired - omega);
}

// Joint PD: the torque a joint exerts on its CHILD body so that the child's orientation relative
// to its parent approaches `relativeDesired` (child orientation expressed in the parent's frame).
// World axes. Apply +τ to the child and −τ to the parent (defect 3 of the original implementation: the original
// applied it to the child only). The damping acts on the relative angular velocity, so a joint
// holding its target exerts nothing on a body that merely rotates as a whole.
inline Eigen::Vector3d jointPd(double kp, double kd, const Eigen::Quaterniond& parent,
                               const Eigen::Quaterniond& child,
                               const Eigen::Quaterniond& relativeDesired,
                               const Eigen::Vector3d& omegaParent,
                               const Eigen::Vector3d& omegaChild) {
  return orientationPd(kp, kd, child, parent * relativeDesired, omegaChild - omegaParent);
}

}  // namespace gaitlab::gait
