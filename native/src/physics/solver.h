// Bullet's sequential-impulse solver with a faster sweep that computes bit for bit the same.
//
// Where the physics time goes (docs/parallel.md, "Where the physics time goes"): about 70 % of a
// crowd's physics step is the solver's iterations, each a sweep over every constraint row (a joint
// has 5-9 rows, a contact point 2), 10 iterations, twice per fixed step. Bullet solves each row
// through a function pointer, with scalar arithmetic, in pool order. This solver replaces only that
// sweep (solveSingleIteration), and computes exactly what Bullet's computes:
//
// - Each row is solved with Bullet's own arithmetic, operation for operation in the same order
//   (gResolveSingleConstraintRowGeneric_scalar_reference and ...LowerLimit_...), but on 4-wide
//   vectors where Bullet works component by component (a product or a sum of two vectors is the
//   same IEEE operation per component either way; the dot products are summed in Bullet's order).
// - What does not change from one iteration to the next is computed once per row: the linear
//   impulse direction (normal times inverse mass), Bullet's (1. / jacDiagABInv), and whether the
//   bodies' linear and angular factors are exactly 1, in which case the multiplications by them
//   (exact identities) are skipped.
// - Rows of independent groups of bodies alternate. Bullet solves islands (a character and the
//   props touching it) in batches (btContactSolverInfo::m_minimumSolverBatchSize); rows of
//   different islands share no body but the static ground, which no row writes. Every group still
//   sees its rows in exactly Bullet's order, but the processor gets several independent chains of
//   dependent arithmetic to overlap instead of one.
//
// The iterations, the early exit (on the largest squared residual over the batch, which does not
// depend on the order of the rows) and the batches are Bullet's. For anything it does not reproduce
// exactly it falls back to Bullet's own sweep: randomised order, interleaved contact and friction
// rows, rolling friction, cone-twist constraints (the only ones with a solveConstraintObsolete),
// row solvers other than Bullet's scalar reference ones, or a row with a zero Jacobian (whose
// residual is not a number, which makes Bullet's running maximum depend on the order).
// tests/native/physics/solver_test.cpp checks the results against Bullet's own sweep.
#pragma once
#include "physics/float4.h"
#include "physics/joint_rows.h"

#include <vector>

namespace gaitlab::physics {

// Its setup of the joints' rows is JointRowSolver's (physics/joint_rows.h), also bit for bit Bullet's.
class InterleavedSolver : public JointRowSolver {
 public:
  // Independent groups whose rows alternate in the sweep.
  static constexpr int kLanes = 4;

  // Off: Bullet's own sweep (for tests and measurements; the results are the same either way).
  void setInterleaving(bool on) { interleave_ = on; }
  bool interleaving() const { return interleave_; }

  // Batches solved so far, and how many of them by the fast sweep (the rest by Bullet's own).
  struct Counts {
    long batches = 0, fast = 0;
  };
  const Counts& counts() const { return counts_; }

  // Capacity for `rows` solver rows (joints, contacts and friction) and `bodies` solver bodies,
  // so that the steps of a steady scene allocate nothing (World::step).
  void reserveSchedule(int rows, int bodies);

 protected:
  btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies,
                                        btPersistentManifold** manifoldPtr, int numManifolds,
                                        btTypedConstraint** constraints, int numConstraints,
                                        const btContactSolverInfo& infoGlobal,
                                        btIDebugDraw* debugDrawer) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                btPersistentManifold** manifoldPtr, int numManifolds,
                                btTypedConstraint** constraints, int numConstraints,
                                const btContactSolverInfo& infoGlobal,
                                btIDebugDraw* debugDrawer) override;

 public:
  enum RowKind : int { kJoint, kContact, kFriction };
  enum RowFlags : int { kWriteA = 1, kWriteB = 2, kUnitA = 4, kUnitB = 8 };
  struct Row {
    Float4 linearA, linearB;           // contact normal times the body's inverse mass
    btSolverConstraint* c;
    btSolverBody* a;
    btSolverBody* b;
    const btSolverConstraint* normal;  // kFriction: the contact row whose impulse bounds it
    double inverseJacDiag;             // Bullet's (1. / c->m_jacDiagABInv), for the residual
    int kind;
    int flags;
  };

 private:
  // Whether this batch can be solved by the fast sweep; builds its schedule if so.
  bool buildSchedule(btTypedConstraint** constraints, int numConstraints,
                     const btContactSolverInfo& infoGlobal);
  int find(int body);

  bool interleave_ = true;
  Counts counts_;
  bool scheduled_ = false;     // the current batch uses schedule_
  std::vector<Row> schedule_;  // one iteration's rows, groups alternating
  std::vector<btSolverConstraint*> rows_;  // every row in Bullet's sweep order
  std::vector<int> parent_;    // union-find over solver bodies: bodies that rows tie together
  std::vector<int> group_;     // per solver body: its group (roots only), or -1
  std::vector<int> rowGroup_;  // per row in sweep order: its group
  std::vector<int> groupStart_, groupFill_, byGroup_;  // rows (sweep indices) grouped
  std::vector<unsigned char> bodyFlags_;               // per solver body: kWriteA | kUnitA
};

}  // namespace gaitlab::physics
