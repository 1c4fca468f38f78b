#include "physics/joint_rows.h"

#include <BulletDynamics/ConstraintSolver/btTypedConstraint.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cstddef>
#include <cstring>

#include "physics/float4.h"

namespace gaitlab::physics {

namespace {

// Clears a row as Bullet's memset does, with 16-byte stores: GCC turns a memset of a row's size
// into `rep stos`, whose start-up cost made up half of this setup's time (perf, 100 bipeds). A row
// is 144 bytes natively and 136 in WebAssembly (4-byte pointers): the tail is a small memset.
// (Unaligned stores: btSolverConstraint declares no alignment in a build without Bullet's SSE.)
typedef float ZeroStore __attribute__((vector_size(16), may_alias, aligned(4)));
inline void clear(btSolverConstraint& row) {
  constexpr std::size_t kBlocks = sizeof(btSolverConstraint) / sizeof(ZeroStore);
  constexpr std::size_t kTail = sizeof(btSolverConstraint) % sizeof(ZeroStore);
  ZeroStore* p = reinterpret_cast<ZeroStore*>(&row);
  for (std::size_t k = 0; k < kBlocks; ++k) p[k] = ZeroStore{};
  if (kTail) std::memset(reinterpret_cast<char*>(p + kBlocks), 0, kTail);
}

// What the row setup reads of a rigid body, once per joint.
struct Body {
  Float4 column[3];    // the world inverse inertia tensor's columns
  Float4 angularFactor;
  btScalar invMass;
  Float4 linear;       // linear velocity + the step's external force impulse (if any)
  Float4 angular;      // angular velocity + the step's external torque impulse (if any)

  Body(const btRigidBody& rb, const btSolverBody& solverBody) {
    const btMatrix3x3& m = rb.getInvInertiaTensorWorld();
    for (int j = 0; j < 3; ++j) column[j] = Float4{m[0][j], m[1][j], m[2][j], 0};
    angularFactor = load(rb.getAngularFactor());
    invMass = rb.getInvMass();
    // Bullet adds the external impulses only for a solver body that has a rigid body (not the
    // shared static one), and adds zero vectors otherwise: x + 0 is x for every x but -0, and
    // -0 + 0 is +0, so the zero is added here too.
    const Float4 zero = {0, 0, 0, 0};
    const bool external = solverBody.m_originalBody != nullptr;
    linear = load(rb.getLinearVelocity()) +
             (external ? load(solverBody.m_externalForceImpulse) : zero);
    angular = load(rb.getAngularVelocity()) +
              (external ? load(solverBody.m_externalTorqueImpulse) : zero);
  }

  // btMatrix3x3 * btVector3 = (m[0]·v, m[1]·v, m[2]·v); lane i computes m[i][0]*x + m[i][1]*y,
  // then + m[i][2]*z, the row's dot product in its own order.
  Float4 inverseInertiaTimes(Float4 v) const {
    return (column[0] * splat(v[0]) + column[1] * splat(v[1])) + column[2] * splat(v[2]);
  }
};

}  // namespace

// Bullet 3.24's btSequentialImpulseConstraintSolver::convertJoints, step for step.
void JointRowSolver::convertJoints(btTypedConstraint** constraints, int numConstraints,
                                   const btContactSolverInfo& infoGlobal) {
  if (!fastJointRows_) {
    btSequentialImpulseConstraintSolver::convertJoints(constraints, numConstraints, infoGlobal);
    return;
  }
  for (int j = 0; j < numConstraints; ++j) {
    constraints[j]->buildJacobian();
    constraints[j]->internalSetAppliedImpulse(0.0f);
  }
  int totalNumRows = 0;
  m_tmpConstraintSizesPool.resizeNoInitialize(numConstraints);
  for (int i = 0; i < numConstraints; ++i) {
    btTypedConstraint::btConstraintInfo1& info1 = m_tmpConstraintSizesPool[i];
    if (btJointFeedback* fb = constraints[i]->getJointFeedback()) {
      fb->m_appliedForceBodyA.setZero();
      fb->m_appliedTorqueBodyA.setZero();
      fb->m_appliedForceBodyB.setZero();
      fb->m_appliedTorqueBodyB.setZero();
    }
    if (constraints[i]->isEnabled()) {
      constraints[i]->getInfo1(&info1);
    } else {
      info1.m_numConstraintRows = 0;
      info1.nub = 0;
    }
    totalNumRows += info1.m_numConstraintRows;
  }
  m_tmpSolverNonContactConstraintPool.resizeNoInitialize(totalNumRows);

  int currentRow = 0;
  for (int i = 0; i < numConstraints; ++i) {
    const int numRows = m_tmpConstraintSizesPool[i].m_numConstraintRows;
    if (numRows) {
      btTypedConstraint* constraint = constraints[i];
      const int solverBodyIdA = getOrInitSolverBody(constraint->getRigidBodyA(), infoGlobal.m_timeStep);
      const int solverBodyIdB = getOrInitSolverBody(constraint->getRigidBodyB(), infoGlobal.m_timeStep);
      convertJointRows(&m_tmpSolverNonContactConstraintPool[currentRow], constraint, numRows,
                       solverBodyIdA, solverBodyIdB, infoGlobal);
    }
    currentRow += numRows;
  }
}

// Bullet 3.24's btSequentialImpulseConstraintSolver::convertJoint: every value it writes, in the
// same arithmetic (see joint_rows.h).
void JointRowSolver::convertJointRows(btSolverConstraint* rows, btTypedConstraint* constraint,
                                      int numRows, int solverBodyIdA, int solverBodyIdB,
                                      const btContactSolverInfo& infoGlobal) {
  const int iterations = constraint->getOverrideNumSolverIterations() > 0
                             ? constraint->getOverrideNumSolverIterations()
                             : infoGlobal.m_numIterations;
  if (iterations > m_maxOverrideNumSolverIterations) m_maxOverrideNumSolverIterations = iterations;

  for (int j = 0; j < numRows; ++j) {
    btSolverConstraint& row = rows[j];
    clear(row);
    row.m_lowerLimit = -SIMD_INFINITY;
    row.m_upperLimit = SIMD_INFINITY;
    row.m_solverBodyIdA = solverBodyIdA;
    row.m_solverBodyIdB = solverBodyIdB;
    row.m_overrideNumSolverIterations = iterations;
  }

  btTypedConstraint::btConstraintInfo2 info2;
  info2.fps = 1.f / infoGlobal.m_timeStep;
  info2.erp = infoGlobal.m_erp;
  info2.m_J1linearAxis = rows->m_contactNormal1;
  info2.m_J1angularAxis = rows->m_relpos1CrossNormal;
  info2.m_J2linearAxis = rows->m_contactNormal2;
  info2.m_J2angularAxis = rows->m_relpos2CrossNormal;
  info2.rowskip = sizeof(btSolverConstraint) / sizeof(btScalar);
  info2.m_constraintError = &rows->m_rhs;
  rows->m_cfm = infoGlobal.m_globalCfm;  // the first row only, as Bullet does
  info2.m_damping = infoGlobal.m_damping;
  info2.cfm = &rows->m_cfm;
  info2.m_lowerLimit = &rows->m_lowerLimit;
  info2.m_upperLimit = &rows->m_upperLimit;
  info2.m_numIterations = infoGlobal.m_numIterations;
  constraint->getInfo2(&info2);

  const btRigidBody& rbA = constraint->getRigidBodyA();
  const btRigidBody& rbB = constraint->getRigidBodyB();
  const Body a(rbA, m_tmpSolverBodyPool[solverBodyIdA]);
  const Body b(rbB, m_tmpSolverBodyPool[solverBodyIdB]);
  const btScalar breaking = constraint->getBreakingImpulseThreshold();
  const btScalar damping = info2.m_damping;
  for (int j = 0; j < numRows; ++j) {
    btSolverConstraint& row = rows[j];
    if (row.m_upperLimit >= breaking) row.m_upperLimit = breaking;
    if (row.m_lowerLimit <= -breaking) row.m_lowerLimit = -breaking;
    row.m_originalContactPoint = constraint;

    const Float4 n1 = load(row.m_contactNormal1), r1 = load(row.m_relpos1CrossNormal);
    const Float4 n2 = load(row.m_contactNormal2), r2 = load(row.m_relpos2CrossNormal);
    // Bullet: angularComponent = (I⁻¹ · r) * angularFactor, and I⁻¹ · r again for the mass.
    const Float4 iMJaA = a.inverseInertiaTimes(r1), iMJaB = b.inverseInertiaTimes(r2);
    store(row.m_angularComponentA, iMJaA * a.angularFactor);
    store(row.m_angularComponentB, iMJaB * b.angularFactor);

    btScalar sum = dot3(n1 * splat(a.invMass), n1);
    sum += dot3(iMJaA, r1);
    sum += dot3(n2 * splat(b.invMass), n2);
    sum += dot3(iMJaB, r2);
    const btScalar sorRelaxation = 1.f;
    row.m_jacDiagABInv = btFabs(sum) > SIMD_EPSILON ? sorRelaxation / sum : 0.f;

    const btScalar vel1Dotn = dot3(n1, a.linear) + dot3(r1, a.angular);
    const btScalar vel2Dotn = dot3(n2, b.linear) + dot3(r2, b.angular);
    const btScalar relVel = vel1Dotn + vel2Dotn;
    const btScalar restitution = 0.f;
    const btScalar positionalError = row.m_rhs;  // filled in by getInfo2
    const btScalar velocityError = restitution - relVel * damping;
    const btScalar penetrationImpulse = positionalError * row.m_jacDiagABInv;
    const btScalar velocityImpulse = velocityError * row.m_jacDiagABInv;
    row.m_rhs = penetrationImpulse + velocityImpulse;
    row.m_appliedImpulse = 0.f;
  }
}

}  // namespace gaitlab::physics
