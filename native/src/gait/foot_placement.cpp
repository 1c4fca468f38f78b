#include "gait/foot_placement.h"

#include <cmath>

#include "gait/heading.h"

namespace gaitlab::gait {

Eigen::Vector3d rampDesiredVelocity(const Eigen::Vector3d& desired, const Eigen::Vector3d& goal,
                                    double maxAccel, double dt) {
  const double maxStep = maxAccel * dt;
  const Eigen::Vector3d delta = goal - desired;
  const double len = delta.norm();
  if (!(maxStep > 0.0)) return desired;  // no acceleration allowed (or nonsense input)
  if (len <= maxStep) return goal;       // reaches the goal exactly, never overshoots
  return desired + delta * (maxStep / len);
}

Eigen::Vector3d footPlacementTarget(const Eigen::Vector3d& legFramePos, double yaw,
                                    const Eigen::Vector3d& nominalOffsetHeading,
                                    const Eigen::Vector3d& velocityHeading,
                                    const Eigen::Vector3d& desiredVelocityHeading, double scale,
                                    double groundY) {
  Eigen::Vector3d offset = nominalOffsetHeading + (velocityHeading - desiredVelocityHeading) * scale;
  offset.y() = 0.0;
  Eigen::Vector3d p = legFramePos + headingToWorld(yaw, offset);
  p.y() = groundY;
  return p;
}

Eigen::Vector3d swingFootTarget(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double phi,
                                const MotionGraph& tSw, const MotionGraph& hSw,
                                double lateStrikeOffset) {
  const double f = tSw.eval(phi);  // fraction of the way (the easing graph t_sw)
  Eigen::Vector3d p = p0 + (p1 - p0) * f;
  p.y() += hSw.eval(phi) - lateStrikeOffset;
  return p;
}

double footProgress(const Eigen::Vector3d& legFramePos, const Eigen::Vector3d& footPos, double yaw) {
  const Eigen::Vector3d d = footPos - legFramePos;
  return d.x() * std::sin(yaw) + d.z() * std::cos(yaw);  // · headingForward(yaw); y drops out
}

Eigen::Vector3d phaseForce(const PhaseForceCoefficients& c, double D, double yaw) {
  const double vertical = c.c0 + c.c1 * D;
  const double horizontal = c.c2 + c.c3 * D;
  Eigen::Vector3d f = headingForward(yaw) * horizontal;
  f.y() = vertical;
  return f;
}

}  // namespace gaitlab::gait
