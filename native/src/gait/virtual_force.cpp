#include "gait/virtual_force.h"

namespace gaitlab::gait {

namespace {

int effectiveCount(const DofChain& chain, int dofCount) {
  if (dofCount < 0 || dofCount > chain.count) return chain.count;
  return dofCount;
}

// Eq. 3.3: τ_i = (α_i × (p − b_i)) · F. The moment arm is taken from the pivot to the point of
// application; only the component of the moment along α_i is something DOF i can produce.
inline double dofTorque(const Dof& d, const Eigen::Vector3d& p, const Eigen::Vector3d& force) {
  return d.axis.cross(p - d.pivot).dot(force);
}

}  // namespace

void jacobianTransposeTorques(const DofChain& chain, const Eigen::Vector3d& p,
                              const Eigen::Vector3d& force, double* out, int dofCount) {
  const int n = effectiveCount(chain, dofCount);
  for (int i = 0; i < n; ++i) out[i] = dofTorque(chain.dofs[i], p, force);
}

void jointTorqueVectors(const DofChain& chain, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& force, Eigen::Vector3d* out, int dofCount) {
  const int n = effectiveCount(chain, dofCount);
  for (int i = 0; i < n; ++i) {
    const Dof& d = chain.dofs[i];
    out[i] = d.axis * dofTorque(d, p, force);
  }
}

void accumulateJointTorques(const DofChain& chain, const Eigen::Vector3d& p,
                            const Eigen::Vector3d& force, Eigen::Vector3d* jointTorques,
                            int jointCount, int dofCount) {
  const int n = effectiveCount(chain, dofCount);
  for (int i = 0; i < n; ++i) {
    const Dof& d = chain.dofs[i];
    if (d.joint < 0 || d.joint >= jointCount) continue;
    const double tau = dofTorque(d, p, force);
    jointTorques[d.joint] += (d.reversed ? -tau : tau) * d.axis;
  }
}

}  // namespace gaitlab::gait
