#include "physics/solver.h"

#include <BulletDynamics/ConstraintSolver/btTypedConstraint.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cstring>

namespace gaitlab::physics {

namespace {

using Row = InterleavedSolver::Row;

// One row: Bullet 3.24's gResolveSingleConstraintRowGeneric_scalar_reference (lowerOnly = false)
// or gResolveSingleConstraintRowLowerLimit_scalar_reference (true), from
// btSequentialImpulseConstraintSolver.cpp, with btSolverBody::internalApplyImpulse. Every
// arithmetic operation is Bullet's, in Bullet's order; vector operations act per component as
// Bullet's btVector3 operators do; the fourth component is never read back into the first three.
template <bool lowerOnly>
inline btScalar resolveRow(const Row& r) {
  btSolverConstraint& c = *r.c;
  btSolverBody& bodyA = *r.a;
  btSolverBody& bodyB = *r.b;
  btScalar deltaImpulse = c.m_rhs - btScalar(c.m_appliedImpulse) * c.m_cfm;
  const Float4 linA = load(bodyA.m_deltaLinearVelocity), angA = load(bodyA.m_deltaAngularVelocity);
  const Float4 linB = load(bodyB.m_deltaLinearVelocity), angB = load(bodyB.m_deltaAngularVelocity);
  const btScalar deltaVel1Dotn =
      dot3(load(c.m_contactNormal1), linA) + dot3(load(c.m_relpos1CrossNormal), angA);
  const btScalar deltaVel2Dotn =
      dot3(load(c.m_contactNormal2), linB) + dot3(load(c.m_relpos2CrossNormal), angB);
  deltaImpulse -= deltaVel1Dotn * c.m_jacDiagABInv;
  deltaImpulse -= deltaVel2Dotn * c.m_jacDiagABInv;

  const btScalar sum = btScalar(c.m_appliedImpulse) + deltaImpulse;
  if (sum < c.m_lowerLimit) {
    deltaImpulse = c.m_lowerLimit - c.m_appliedImpulse;
    c.m_appliedImpulse = c.m_lowerLimit;
  } else if (!lowerOnly && sum > c.m_upperLimit) {
    deltaImpulse = c.m_upperLimit - c.m_appliedImpulse;
    c.m_appliedImpulse = c.m_upperLimit;
  } else {
    c.m_appliedImpulse = sum;
  }

  // internalApplyImpulse(linearComponent, angularComponent, impulse), for a body that is not the
  // static one: deltaLinear += linearComponent * impulse * linearFactor;
  //             deltaAngular += angularComponent * (impulse * angularFactor).
  // linearComponent = contactNormal * invMass is r.linearA/B, computed once; a factor of exactly
  // 1 (kUnit) leaves a product unchanged and is skipped.
  const Float4 impulse = {deltaImpulse, deltaImpulse, deltaImpulse, deltaImpulse};
  if (r.flags & InterleavedSolver::kWriteA) {
    if (r.flags & InterleavedSolver::kUnitA) {
      store(bodyA.m_deltaLinearVelocity, linA + r.linearA * impulse);
      store(bodyA.m_deltaAngularVelocity, angA + load(c.m_angularComponentA) * impulse);
    } else {
      store(bodyA.m_deltaLinearVelocity, linA + (r.linearA * impulse) * load(bodyA.m_linearFactor));
      store(bodyA.m_deltaAngularVelocity,
            angA + load(c.m_angularComponentA) * (impulse * load(bodyA.m_angularFactor)));
    }
  }
  if (r.flags & InterleavedSolver::kWriteB) {
    if (r.flags & InterleavedSolver::kUnitB) {
      store(bodyB.m_deltaLinearVelocity, linB + r.linearB * impulse);
      store(bodyB.m_deltaAngularVelocity, angB + load(c.m_angularComponentB) * impulse);
    } else {
      store(bodyB.m_deltaLinearVelocity, linB + (r.linearB * impulse) * load(bodyB.m_linearFactor));
      store(bodyB.m_deltaAngularVelocity,
            angB + load(c.m_angularComponentB) * (impulse * load(bodyB.m_angularFactor)));
    }
  }
  // Bullet's residual: deltaImpulse * (1. / c.m_jacDiagABInv), in double, returned as btScalar.
  return static_cast<btScalar>(deltaImpulse * r.inverseJacDiag);
}

}  // namespace

void InterleavedSolver::reserveSchedule(int rows, int bodies) {
  schedule_.reserve(rows);
  rows_.reserve(rows);
  rowGroup_.reserve(rows);
  byGroup_.reserve(rows);
  parent_.reserve(bodies);
  group_.reserve(bodies);
  bodyFlags_.reserve(bodies);
  groupStart_.reserve(bodies + 2);
  groupFill_.reserve(bodies + 2);
}

int InterleavedSolver::find(int body) {
  while (parent_[body] != body) {
    parent_[body] = parent_[parent_[body]];
    body = parent_[body];
  }
  return body;
}

btScalar InterleavedSolver::solveGroupCacheFriendlySetup(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifoldPtr,
    int numManifolds, btTypedConstraint** constraints, int numConstraints,
    const btContactSolverInfo& infoGlobal, btIDebugDraw* debugDrawer) {
  const btScalar r = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
      bodies, numBodies, manifoldPtr, numManifolds, constraints, numConstraints, infoGlobal,
      debugDrawer);
  scheduled_ = interleave_ && buildSchedule(constraints, numConstraints, infoGlobal);
  ++counts_.batches;
  if (scheduled_) ++counts_.fast;
  return r;
}

bool InterleavedSolver::buildSchedule(btTypedConstraint** constraints, int numConstraints,
                                      const btContactSolverInfo& infoGlobal) {
  // What the fast sweep reproduces: Bullet's plain sweep (joint rows, then contact rows, then
  // friction rows, each in its order array's order) with its scalar reference row solvers.
  if (infoGlobal.m_solverMode &
      (SOLVER_RANDMIZE_ORDER | SOLVER_INTERLEAVE_CONTACT_AND_FRICTION_CONSTRAINTS))
    return false;
  if (infoGlobal.m_numIterations <= 0) return false;
  if (m_tmpSolverContactRollingFrictionConstraintPool.size() > 0) return false;
  if (getActiveConstraintRowSolverGeneric() != getScalarConstraintRowSolverGeneric() ||
      getActiveConstraintRowSolverLowerLimit() != getScalarConstraintRowSolverLowerLimit())
    return false;
  for (int i = 0; i < numConstraints; ++i)
    if (constraints[i]->getConstraintType() == CONETWIST_CONSTRAINT_TYPE) return false;

  // Bullet's sweep looks up (and, for a body it has not met yet, creates) the solver bodies of
  // every enabled constraint in each iteration. Do it here, once, before any row is solved: the
  // body pool then never grows while the schedule points into it.
  for (int i = 0; i < numConstraints; ++i) {
    if (!constraints[i]->isEnabled()) continue;
    getOrInitSolverBody(constraints[i]->getRigidBodyA(), infoGlobal.m_timeStep);
    getOrInitSolverBody(constraints[i]->getRigidBodyB(), infoGlobal.m_timeStep);
  }

  // Every row, in the order of Bullet's sweep.
  const int numJoint = m_tmpSolverNonContactConstraintPool.size();
  const int numContact = m_tmpSolverContactConstraintPool.size();
  const int numFriction = m_tmpSolverContactFrictionConstraintPool.size();
  const int numRows = numJoint + numContact + numFriction;
  rows_.resize(numRows);
  for (int j = 0; j < numJoint; ++j)
    rows_[j] = &m_tmpSolverNonContactConstraintPool[m_orderNonContactConstraintPool[j]];
  for (int j = 0; j < numContact; ++j)
    rows_[numJoint + j] = &m_tmpSolverContactConstraintPool[m_orderTmpConstraintPool[j]];
  for (int j = 0; j < numFriction; ++j)
    rows_[numJoint + numContact + j] =
        &m_tmpSolverContactFrictionConstraintPool[m_orderFrictionConstraintPool[j]];
  const int firstFriction = numJoint + numContact;

  // A row with no effective mass (zero Jacobian) has a residual that is not a number, and
  // Bullet's running maximum then depends on the order of the rows.
  // (1. / x in double is infinite or NaN exactly when the float x is 0 or NaN.)
  for (int s = 0; s < numRows; ++s) {
    const btScalar j = rows_[s]->m_jacDiagABInv;
    if (j == 0 || j != j) return false;
  }

  // Per solver body: written by rows (it stands for a body, not for the static world), and
  // whether its linear and angular factors are exactly 1.
  const int numBodies = m_tmpSolverBodyPool.size();
  bodyFlags_.resize(numBodies);
  const btVector3 one(1, 1, 1);
  for (int i = 0; i < numBodies; ++i) {
    const btSolverBody& b = m_tmpSolverBodyPool[i];
    const bool unit = b.m_linearFactor == one && b.m_angularFactor == one;
    bodyFlags_[i] = static_cast<unsigned char>((b.m_originalBody ? kWriteA : 0) | (unit ? kUnitA : 0));
  }
  const auto live = [&](int id) { return (bodyFlags_[id] & kWriteA) != 0; };

  // Groups: bodies tied together by rows (union-find). The static body ties nothing together.
  parent_.resize(numBodies);
  for (int i = 0; i < numBodies; ++i) parent_[i] = i;
  const auto unite = [&](int a, int b) {
    if (!live(a) || !live(b)) return;
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  };
  int lastA = -1, lastB = -1;
  for (int s = 0; s < numRows; ++s) {
    const btSolverConstraint& c = *rows_[s];
    if (c.m_solverBodyIdA != lastA || c.m_solverBodyIdB != lastB) {
      lastA = c.m_solverBodyIdA;
      lastB = c.m_solverBodyIdB;
      unite(lastA, lastB);
    }
    if (s >= firstFriction) {  // a friction row goes with its contact row
      const btSolverConstraint& n = m_tmpSolverContactConstraintPool[c.m_frictionIndex];
      if (n.m_solverBodyIdA != c.m_solverBodyIdA || n.m_solverBodyIdB != c.m_solverBodyIdB) {
        unite(c.m_solverBodyIdA, n.m_solverBodyIdA);
        unite(c.m_solverBodyIdA, n.m_solverBodyIdB);
        unite(c.m_solverBodyIdB, n.m_solverBodyIdA);
      }
    }
  }

  // The group of each row, groups numbered in order of first appearance. Rows that write no body
  // at all (between two static objects) share one group.
  group_.assign(numBodies, -1);
  int groups = 0, staticGroup = -1;
  rowGroup_.resize(numRows);
  lastA = lastB = -1;
  int lastGroup = -1;
  for (int s = 0; s < numRows; ++s) {
    const btSolverConstraint* c = rows_[s];
    if (s >= firstFriction) c = &m_tmpSolverContactConstraintPool[c->m_frictionIndex];
    if (c->m_solverBodyIdA == lastA && c->m_solverBodyIdB == lastB) {  // as the row before
      rowGroup_[s] = lastGroup;
      continue;
    }
    lastA = c->m_solverBodyIdA;
    lastB = c->m_solverBodyIdB;
    const int key = live(lastA) ? lastA : live(lastB) ? lastB : -1;
    int g;
    if (key < 0) {
      if (staticGroup < 0) staticGroup = groups++;
      g = staticGroup;
    } else {
      const int root = find(key);
      if (group_[root] < 0) group_[root] = groups++;
      g = group_[root];
    }
    rowGroup_[s] = lastGroup = g;
  }

  // Each group's rows in sweep order (a stable counting sort).
  groupStart_.assign(groups + 1, 0);
  for (int s = 0; s < numRows; ++s) ++groupStart_[rowGroup_[s] + 1];
  for (int g = 0; g < groups; ++g) groupStart_[g + 1] += groupStart_[g];
  groupFill_.assign(groupStart_.begin(), groupStart_.end() - 1);
  byGroup_.resize(numRows);
  for (int s = 0; s < numRows; ++s) byGroup_[groupFill_[rowGroup_[s]]++] = s;

  // The sweep: kLanes groups at a time, their rows alternating.
  schedule_.resize(numRows);
  int out = 0;
  for (int g0 = 0; g0 < groups; g0 += kLanes) {
    const int lanes = std::min(kLanes, groups - g0);
    int longest = 0;
    for (int l = 0; l < lanes; ++l)
      longest = std::max(longest, groupStart_[g0 + l + 1] - groupStart_[g0 + l]);
    for (int k = 0; k < longest; ++k) {
      for (int l = 0; l < lanes; ++l) {
        if (groupStart_[g0 + l] + k >= groupStart_[g0 + l + 1]) continue;
        const int s = byGroup_[groupStart_[g0 + l] + k];
        btSolverConstraint& c = *rows_[s];
        Row& r = schedule_[out++];
        r.c = &c;
        r.a = &m_tmpSolverBodyPool[c.m_solverBodyIdA];
        r.b = &m_tmpSolverBodyPool[c.m_solverBodyIdB];
        r.kind = s < numJoint ? kJoint : s < firstFriction ? kContact : kFriction;
        r.normal = r.kind == kFriction ? &m_tmpSolverContactConstraintPool[c.m_frictionIndex] : nullptr;
        r.inverseJacDiag = 1. / c.m_jacDiagABInv;
        // btVector3 * btVector3 is per component: Bullet's linearComponent, computed once.
        r.linearA = load(c.m_contactNormal1) * load(r.a->m_invMass);
        r.linearB = load(c.m_contactNormal2) * load(r.b->m_invMass);
        const int fa = bodyFlags_[c.m_solverBodyIdA], fb = bodyFlags_[c.m_solverBodyIdB];
        r.flags = (fa & kWriteA ? kWriteA : 0) | (fa & kUnitA ? kUnitA : 0) |
                  (fb & kWriteA ? kWriteB : 0) | (fb & kUnitA ? kUnitB : 0);
      }
    }
  }
  return true;
}

btScalar InterleavedSolver::solveSingleIteration(int iteration, btCollisionObject** bodies,
                                                 int numBodies, btPersistentManifold** manifoldPtr,
                                                 int numManifolds, btTypedConstraint** constraints,
                                                 int numConstraints,
                                                 const btContactSolverInfo& infoGlobal,
                                                 btIDebugDraw* debugDrawer) {
  if (!scheduled_)
    return btSequentialImpulseConstraintSolver::solveSingleIteration(
        iteration, bodies, numBodies, manifoldPtr, numManifolds, constraints, numConstraints,
        infoGlobal, debugDrawer);
  // As Bullet's sweep: joint rows while the iteration is below their own count; contact and
  // friction rows in the first m_numIterations iterations, each friction row bounded by its
  // contact's impulse of this iteration. The result, the largest squared residual, does not depend
  // on the order in which the rows are visited.
  btScalar leastSquaresResidual = 0.f;
  const bool contacts = iteration < infoGlobal.m_numIterations;
  for (const Row& r : schedule_) {
    btScalar residual;
    if (r.kind == kJoint) {
      if (!(iteration < r.c->m_overrideNumSolverIterations)) continue;
      residual = resolveRow<false>(r);
    } else if (!contacts) {
      continue;
    } else if (r.kind == kContact) {
      residual = resolveRow<true>(r);
    } else {
      const btScalar totalImpulse = r.normal->m_appliedImpulse;
      if (!(totalImpulse > btScalar(0))) continue;
      r.c->m_lowerLimit = -(r.c->m_friction * totalImpulse);
      r.c->m_upperLimit = r.c->m_friction * totalImpulse;
      residual = resolveRow<false>(r);
    }
    leastSquaresResidual = btMax(leastSquaresResidual, residual * residual);
  }
  return leastSquaresResidual;
}

}  // namespace gaitlab::physics
