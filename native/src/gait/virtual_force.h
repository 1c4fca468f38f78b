// Virtual forces by the Jacobian transpose (thesis §3.1.2, eq. 3.1–3.3): the torques a chain of
// joints must exert so that its end point pushes with force F,
//     τ_F = J(p)ᵀ F,   one row per DOF:   τ_i = (α_i × (p − b_i)) · F        (eq. 3.3)
// with α_i the DOF's unit rotation axis and b_i a point on it, both in world axes.
//
// A chain is a fixed-capacity list of DOFs ordered from the base (e.g. the leg frame) towards
// the end effector (e.g. the foot). A 3-DOF joint contributes three rows. Everything is on the
// stack: these run per character per step inside the parallel loop (defect 10 of the original implementation, docs/original-implementation.md).
#pragma once
#include <Eigen/Dense>

namespace gaitlab::gait {

struct Dof {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();   // α_i: unit rotation axis, world
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();   // b_i: a point on the axis (joint pivot), world
  // Caller's joint id, for accumulating torque VECTORS per physical joint (see
  // accumulateJointTorques); −1 = not a joint (e.g. rows for a free base's own rotation):
  // such a row still gets its scalar τ_i but contributes to no joint.
  int joint = -1;
  // False: walking the chain from base to end crosses this joint from its parent to its child
  // (the usual case: leg frame → foot). True: from child to parent (e.g. the spine chain based
  // at the front leg frame when the morphology's parent links point the other way).
  bool reversed = false;
};

struct DofChain {
  static constexpr int kMaxDofs = 16;
  Dof dofs[kMaxDofs];
  int count = 0;

  void clear() { count = 0; }
  // Appends a DOF; returns false (and appends nothing) when the chain is full.
  bool push(const Eigen::Vector3d& axis, const Eigen::Vector3d& pivot, int joint = -1,
            bool reversed = false) {
    if (count >= kMaxDofs) return false;
    Dof& d = dofs[count++];
    d.axis = axis;
    d.pivot = pivot;
    d.joint = joint;
    d.reversed = reversed;
    return true;
  }
};

// Eq. 3.3 for the first `dofCount` DOFs of the chain (clamped to [0, chain.count]); pass −1 for
// all of them. out[i] = τ_i, so `out` must hold that many doubles. Overwrites out.
void jacobianTransposeTorques(const DofChain& chain, const Eigen::Vector3d& p,
                              const Eigen::Vector3d& force, double* out, int dofCount = -1);

// Same, as torque VECTORS α_i τ_i (world). A torque vector is what the physics side applies:
// +α_i τ_i on the body on the END side of DOF i (the part of the chain the DOF moves, which holds
// p) and −α_i τ_i on the body on the BASE side — an equal and opposite pair, so the virtual force
// adds no net angular momentum (defect 3 of the original implementation).
void jointTorqueVectors(const DofChain& chain, const Eigen::Vector3d& p,
                        const Eigen::Vector3d& force, Eigen::Vector3d* out, int dofCount = -1);

// Adds the virtual force's torques, summed per physical joint, into jointTorques[joint]
// (size jointCount; DOFs with joint outside [0, jointCount) are skipped). Convention of the
// accumulated array: jointTorques[j] is the world torque joint j exerts on its CHILD body; the
// physics side applies +jointTorques[j] to the child and −jointTorques[j] to the parent. A DOF
// marked `reversed` therefore adds −α_i τ_i (its end side is the parent).
void accumulateJointTorques(const DofChain& chain, const Eigen::Vector3d& p,
                            const Eigen::Vector3d& force, Eigen::Vector3d* jointTorques,
                            int jointCount, int dofCount = -1);

}  // namespace gaitlab::gait
