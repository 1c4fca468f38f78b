// Heading frame: the character's yaw frame (rotation about world +y only). At heading 0 the
// character faces +z and its left is +x (y up, right-handed, as three.js and body/morphology.h).
//
// The original implementation worked in world axes throughout, so its characters could only walk
// along +z on flat ground (defect 7 of the original implementation, docs/original-implementation.md). Everything the controller expresses relative
// to the character (step lengths, desired velocity, the forward sign of F_D, swing trajectories)
// goes through these conversions instead.
#pragma once
#include <Eigen/Dense>
#include <cmath>

namespace gaitlab::gait {

constexpr double kPi = 3.14159265358979323846;

// Wraps an angle to (-π, π].
inline double wrapAngle(double a) {
  if (!std::isfinite(a)) return 0.0;
  a = std::remainder(a, 2.0 * kPi);  // [-π, π]
  return a <= -kPi ? a + 2.0 * kPi : a;
}

// Yaw of an orientation about +y: the direction the body's forward axis (+z) points, projected
// onto the ground plane. This is exact for any yaw-pitch-roll (three.js 'YXZ') decomposition as
// long as |pitch| < π/2. When the forward axis is (nearly) vertical the projection is
// meaningless; then the twist of q about +y (swing-twist decomposition) is used. Always finite.
inline double headingOf(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d f = q * Eigen::Vector3d::UnitZ();
  const double h2 = f.x() * f.x() + f.z() * f.z();
  const double n2 = q.squaredNorm();
  if (h2 > 1e-12 * n2) return std::atan2(f.x(), f.z());
  return wrapAngle(2.0 * std::atan2(q.y(), q.w()));
}

// Rotation by `yaw` about +y.
inline Eigen::Quaterniond headingQuat(double yaw) {
  return Eigen::Quaterniond(std::cos(0.5 * yaw), 0.0, std::sin(0.5 * yaw), 0.0);
}

// The yaw-only part of an orientation (the heading frame's orientation).
inline Eigen::Quaterniond yawOnly(const Eigen::Quaterniond& q) { return headingQuat(headingOf(q)); }

// Unit forward (+z of the heading frame) and left (+x of the heading frame) in world axes.
inline Eigen::Vector3d headingForward(double yaw) {
  return Eigen::Vector3d(std::sin(yaw), 0.0, std::cos(yaw));
}
inline Eigen::Vector3d headingLeft(double yaw) {
  return Eigen::Vector3d(std::cos(yaw), 0.0, -std::sin(yaw));
}

// Direction vector from heading-frame axes to world axes: R_y(yaw) v.
inline Eigen::Vector3d headingToWorld(double yaw, const Eigen::Vector3d& v) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return Eigen::Vector3d(c * v.x() + s * v.z(), v.y(), -s * v.x() + c * v.z());
}

// Direction vector from world axes to heading-frame axes: R_y(-yaw) v.
inline Eigen::Vector3d worldToHeading(double yaw, const Eigen::Vector3d& v) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return Eigen::Vector3d(c * v.x() - s * v.z(), v.y(), s * v.x() + c * v.z());
}

// Points: the heading frame's origin is `origin` (usually the leg frame's position).
inline Eigen::Vector3d headingPointToWorld(double yaw, const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& p) {
  return origin + headingToWorld(yaw, p);
}
inline Eigen::Vector3d worldPointToHeading(double yaw, const Eigen::Vector3d& origin,
                                           const Eigen::Vector3d& p) {
  return worldToHeading(yaw, p - origin);
}

}  // namespace gaitlab::gait
