// Gravity compensation (thesis §3.1.5): for each compensated segment a virtual force
// F_g = −m·g (g the gravity vector, pointing down) at its centre of mass, turned into torques for
// the DOFs that precede that segment in a chain by the Jacobian transpose (eq. 3.3). Applied to
// the swing legs and the spine, so that the PD targets need not fight gravity.
//
// Defect 5 of the original implementation (docs/original-implementation.md): the original used the wrong segment masses and spine weights that did
// not sum to one. Here the caller passes each segment's own mass and COM, and the two spine
// weights of a link always sum to one, so each link is compensated exactly once in total.
#pragma once
#include <Eigen/Dense>

#include "gait/virtual_force.h"

namespace gaitlab::gait {

// A mass the chain should hold up.
struct SegmentLoad {
  double mass = 0.0;                              // kg
  Eigen::Vector3d com = Eigen::Vector3d::Zero();  // centre of mass, world
  int dofCount = 0;  // the first dofCount DOFs of the chain precede (move) this segment
  double weight = 1.0;  // share of the compensation this chain provides (spine: see below)
};

// τ_i = Σ_k [i < dofCount_k] (α_i × (c_k − b_i)) · (−m_k w_k g)  for every DOF of the chain.
// Overwrites out[0 .. chain.count). `gravity` is the gravity vector, e.g. (0, −9.81, 0).
// By construction τ_i = +∂V/∂α_i with V = Σ m_k w_k (−g)·c_k the potential energy: the torque
// that statically balances gravity.
void gravityCompensationTorques(const DofChain& chain, const SegmentLoad* segments,
                                int segmentCount, const Eigen::Vector3d& gravity, double* out);

// Same, added into per-joint torque vectors (convention of accumulateJointTorques: torque on the
// joint's child; apply the opposite to its parent).
void accumulateGravityCompensation(const DofChain& chain, const SegmentLoad* segments,
                                   int segmentCount, const Eigen::Vector3d& gravity,
                                   Eigen::Vector3d* jointTorques, int jointCount);

// Spine link weights for its two gravity-compensation forces, one per leg frame as base:
// w = 1 − d with d the link's distance to that base normalised by the sum of its distances to
// both bases, so d_back + d_front = 1 and w_back + w_front = 1 (the thesis's "0 < d < 1").
// A link next to the back leg frame is held up mostly through the back leg frame's chain.
struct SpineWeights {
  double back;
  double front;
};

// From the two distances (e.g. measured along the spine chain). Both zero → ½, ½.
SpineWeights spineGravityWeights(double distanceToBack, double distanceToFront);

// From positions: Euclidean distances from the link's COM to each leg frame's base point.
SpineWeights spineGravityWeights(const Eigen::Vector3d& backBase, const Eigen::Vector3d& frontBase,
                                 const Eigen::Vector3d& linkCom);

}  // namespace gaitlab::gait
