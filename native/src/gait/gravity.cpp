#include "gait/gravity.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::gait {

void gravityCompensationTorques(const DofChain& chain, const SegmentLoad* segments,
                                int segmentCount, const Eigen::Vector3d& gravity, double* out) {
  for (int i = 0; i < chain.count; ++i) out[i] = 0.0;
  for (int k = 0; k < segmentCount; ++k) {
    const SegmentLoad& s = segments[k];
    const Eigen::Vector3d force = -s.mass * s.weight * gravity;  // F_g = −m·g (§3.1.5)
    const int n = std::min(std::max(s.dofCount, 0), chain.count);
    for (int i = 0; i < n; ++i) {
      const Dof& d = chain.dofs[i];
      out[i] += d.axis.cross(s.com - d.pivot).dot(force);  // eq. 3.3
    }
  }
}

void accumulateGravityCompensation(const DofChain& chain, const SegmentLoad* segments,
                                   int segmentCount, const Eigen::Vector3d& gravity,
                                   Eigen::Vector3d* jointTorques, int jointCount) {
  for (int k = 0; k < segmentCount; ++k) {
    const SegmentLoad& s = segments[k];
    const int n = std::min(std::max(s.dofCount, 0), chain.count);
    accumulateJointTorques(chain, s.com, -s.mass * s.weight * gravity, jointTorques, jointCount,
                           n);
  }
}

SpineWeights spineGravityWeights(double distanceToBack, double distanceToFront) {
  const double a = std::isfinite(distanceToBack) ? std::fabs(distanceToBack) : 0.0;
  const double b = std::isfinite(distanceToFront) ? std::fabs(distanceToFront) : 0.0;
  const double sum = a + b;
  if (!(sum > 0.0)) return {0.5, 0.5};
  const double dBack = a / sum;  // normalised distance to the back base
  const double dFront = 1.0 - dBack;  // to the front base; d_back + d_front = 1 exactly
  return {1.0 - dBack, 1.0 - dFront};
}

SpineWeights spineGravityWeights(const Eigen::Vector3d& backBase, const Eigen::Vector3d& frontBase,
                                 const Eigen::Vector3d& linkCom) {
  return spineGravityWeights((linkCom - backBase).norm(), (linkCom - frontBase).norm());
}

}  // namespace gaitlab::gait
