// Bullet's sequential-impulse solver with a faster setup of the joints' rows that computes bit for
// bit the same.
//
// Why. Before the solver's iterations, Bullet turns every joint into solver rows
// (btSequentialImpulseConstraintSolver::convertJoints): the joint fills in its Jacobians and
// errors (getInfo1/getInfo2), and the solver then finishes each row: the angular impulse
// directions (the world inverse inertia times the angular Jacobian, for both bodies), the row's
// effective mass (jacDiagABInv) and its right-hand side from the bodies' velocities. After the
// fast sweep (physics/solver.h) this setup was the largest part of the physics step left to
// Bullet's scalar code: 14 % of a walking biped crowd's native step in a perf profile, a third of
// it in clearing each row with `rep stos` (docs/parallel.md, "Where the physics time goes").
//
// What is different, and why the results are the same:
// - The world inverse inertia is kept as its three columns, so that a matrix times a vector is
//   three 4-wide products and two 4-wide sums: each lane computes m[i][0]*x + m[i][1]*y, then
//   + m[i][2]*z, which is btMatrix3x3's row-by-row dot product in its own order. Both builds have
//   no fused multiply-add (docs/parallel.md), so every operation rounds as Bullet's does.
// - Bullet computes the inverse inertia times the angular Jacobian twice per body (once for the
//   angular component, once for the effective mass); it is computed once here. The angular
//   component is that product times the body's angular factor.
// - What belongs to a body rather than a row (its velocities plus the step's external impulses,
//   its inverse mass and inertia) is loaded once per joint, not once per row.
// - Rows are cleared with fixed-size stores rather than one variable-length memset.
// - Dot products are summed in Bullet's order: x*x' + y*y', then + z*z'.
// tests/native/physics/joint_rows_test.cpp steps walking bipeds, quadrupeds falling and lying with
// joints at their limits, and props on characters with each setup, and with the two alternating
// every step, and requires the same state hash; changing the order of one addition in the row
// arithmetic makes it fail.
#pragma once
#include <BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h>

namespace gaitlab::physics {

class JointRowSolver : public btSequentialImpulseConstraintSolver {
 public:
  // Off: Bullet's own convertJoints (for tests and measurements; the rows are the same).
  void setFastJointRows(bool on) { fastJointRows_ = on; }
  bool fastJointRows() const { return fastJointRows_; }

 protected:
  void convertJoints(btTypedConstraint** constraints, int numConstraints,
                     const btContactSolverInfo& infoGlobal) override;

 private:
  // Bullet's convertJoint, for one joint's rows (see above).
  void convertJointRows(btSolverConstraint* rows, btTypedConstraint* constraint, int numRows,
                        int solverBodyIdA, int solverBodyIdB, const btContactSolverInfo& infoGlobal);

  bool fastJointRows_ = true;
};

}  // namespace gaitlab::physics
