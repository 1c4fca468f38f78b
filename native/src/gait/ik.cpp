#include "gait/ik.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::gait {

namespace {

constexpr double kTiny = 1e-12;

double clampUnit(double c) { return std::min(1.0, std::max(-1.0, c)); }

// A unit vector perpendicular to u (unit). Deterministic, no branches on history.
Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& u) { return u.unitOrthogonal(); }

}  // namespace

TwoLinkIk solveTwoLinkIk(const Eigen::Vector3d& hip, const Eigen::Vector3d& target, double thigh,
                         double shin, const Eigen::Vector3d& bendDir) {
  // Negative or non-finite lengths make no leg; treat them as zero so the result stays finite.
  const double l1 = std::isfinite(thigh) ? std::max(0.0, thigh) : 0.0;
  const double l2 = std::isfinite(shin) ? std::max(0.0, shin) : 0.0;

  Eigen::Vector3d toTarget = target - hip;
  if (!toTarget.allFinite()) toTarget.setZero();
  double d = toTarget.norm();

  // Bend direction: unit, or a default (−y would be parallel to a hanging leg, so +z).
  Eigen::Vector3d bend = bendDir.allFinite() ? bendDir : Eigen::Vector3d::Zero();
  const double bendNorm = bend.norm();
  bend = bendNorm > kTiny ? Eigen::Vector3d(bend / bendNorm) : Eigen::Vector3d::UnitZ();

  // Direction of the line hip → target. With the target at the hip it is undefined; pick the
  // direction perpendicular to bend that is closest to straight down (a hanging leg).
  Eigen::Vector3d e;
  if (d > kTiny) {
    e = toTarget / d;
  } else {
    e = -Eigen::Vector3d::UnitY() + bend * bend.y();  // −y minus its component along bend
    const double n = e.norm();
    e = n > 1e-6 ? Eigen::Vector3d(e / n) : anyPerpendicular(bend);
    d = 0.0;
  }

  // In-plane unit normal n: the part of bend perpendicular to e (the knee goes towards +n).
  Eigen::Vector3d n = bend - e * bend.dot(e);
  const double nn = n.norm();
  n = nn > 1e-9 ? Eigen::Vector3d(n / nn) : anyPerpendicular(e);

  const double reachMax = l1 + l2;
  const double reachMin = std::fabs(l1 - l2);
  const bool reachable = d >= reachMin && d <= reachMax;
  const double dc = std::min(reachMax, std::max(reachMin, d));  // saturated distance

  // Law of cosines. Interior knee angle γ: dc² = l1² + l2² − 2 l1 l2 cos γ.
  // Hip angle β between hip→target and hip→knee: l2² = l1² + dc² − 2 l1 dc cos β.
  double cosGamma, cosBeta;
  if (l1 > kTiny && l2 > kTiny) {
    cosGamma = clampUnit((l1 * l1 + l2 * l2 - dc * dc) / (2.0 * l1 * l2));
  } else {
    cosGamma = -1.0;  // a one-link leg is "straight"
  }
  if (l1 > kTiny && dc > kTiny) {
    cosBeta = clampUnit((l1 * l1 + dc * dc - l2 * l2) / (2.0 * l1 * dc));
  } else if (l1 > kTiny) {
    // dc = 0 (only when l1 = l2): the shin folds straight back onto the hip; put the thigh
    // perpendicular to the target line, towards the bend side.
    cosBeta = 0.0;
  } else {
    cosBeta = 1.0;
  }
  const double sinBeta = std::sqrt(std::max(0.0, 1.0 - cosBeta * cosBeta));

  TwoLinkIk r;
  r.thighDir = cosBeta * e + sinBeta * n;
  r.knee = hip + l1 * r.thighDir;
  r.foot = hip + dc * e;
  const Eigen::Vector3d shin3 = r.foot - r.knee;
  const double shinLen = shin3.norm();
  // A zero-length shin has no direction; continue the thigh (a straight leg).
  r.shinDir = shinLen > kTiny ? Eigen::Vector3d(shin3 / shinLen) : r.thighDir;
  r.kneeAngle = std::acos(cosGamma);
  r.kneeFlexion = std::acos(-1.0) - r.kneeAngle;
  r.reachable = reachable;
  return r;
}

LegIk solveLegIk(const Eigen::Vector3d& hip, const Eigen::Vector3d& target, double thigh, double shin,
                 double tarsus, const Eigen::Vector3d& bendDir) {
  LegIk r;
  static_cast<TwoLinkIk&>(r) = solveTwoLinkIk(hip, target, thigh + tarsus, shin, bendDir);
  r.ankleLimb = tarsus > 0 ? r.thighDir : r.shinDir;
  return r;
}

Eigen::Quaterniond limbOrientation(const Eigen::Vector3d& down, const Eigen::Vector3d& forward) {
  const Eigen::Vector3d y = -down.normalized();
  Eigen::Vector3d z = forward - forward.dot(y) * y;
  if (z.squaredNorm() < 1e-12) z = y.unitOrthogonal();
  z.normalize();
  Eigen::Matrix3d r;
  r.col(0) = y.cross(z);
  r.col(1) = y;
  r.col(2) = z;
  return Eigen::Quaterniond(r);
}

}  // namespace gaitlab::gait
