#include "physics/discrete_world.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <BulletCollision/CollisionDispatch/btSimulationIslandManager.h>
#include <BulletDynamics/ConstraintSolver/btConstraintSolver.h>
#include <BulletDynamics/ConstraintSolver/btContactSolverInfo.h>
#include <BulletDynamics/ConstraintSolver/btTypedConstraint.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <vector>

#include "physics/collision_algorithm.h"

namespace gaitlab::physics {

namespace {

// Bounding boxes and support points come from different arithmetic; boxClearOfPlane leaves this
// much room (metres) beyond the contact threshold for their rounding.
constexpr btScalar kSlack = 1e-3f;

// Bullet's convex-plane algorithm, skipped for a box clear of the plane with an empty manifold.
class GroundContact final : public btConvexPlaneCollisionAlgorithm {
 public:
  GroundContact(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* w0,
                const btCollisionObjectWrapper* w1, bool swapped)
      : btConvexPlaneCollisionAlgorithm(nullptr, ci, w0, w1, swapped,
                                        bullets().m_numPerturbationIterations,
                                        bullets().m_minimumPointsPerturbationThreshold),
        swapped_(swapped) {
    btManifoldArray own;  // the manifold Bullet's constructor made, if any (once per pair)
    getAllContactManifolds(own);
    manifold_ = own.size() > 0 ? own[0] : nullptr;
  }

  void processCollision(const btCollisionObjectWrapper* w0, const btCollisionObjectWrapper* w1,
                        const btDispatcherInfo& info, btManifoldResult* out) override {
    if (manifold_ && manifold_->getNumContacts() == 0) {
      const btCollisionObjectWrapper* box = swapped_ ? w1 : w0;
      const btCollisionObjectWrapper* ground = swapped_ ? w0 : w1;
      if (boxClearOfPlane(*box->getCollisionShape(), box->getWorldTransform(),
                          *static_cast<const btStaticPlaneShape*>(ground->getCollisionShape()),
                          ground->getWorldTransform(),
                          manifold_->getContactBreakingThreshold() + out->m_closestPointDistanceThreshold)) {
        out->setPersistentManifold(manifold_);  // as Bullet's algorithm leaves it
        return;
      }
    }
    btConvexPlaneCollisionAlgorithm::processCollision(w0, w1, info, out);
  }

 private:
  // Bullet's settings for its convex-plane algorithm (btDefaultCollisionConfiguration's).
  static const btConvexPlaneCollisionAlgorithm::CreateFunc& bullets() {
    static const btConvexPlaneCollisionAlgorithm::CreateFunc defaults;
    return defaults;
  }

  btPersistentManifold* manifold_;
  bool swapped_;
};

// The dispatcher's algorithm pool holds elements the size of its largest default algorithm.
static_assert(sizeof(GroundContact) <= sizeof(btConvexConvexAlgorithm),
              "GroundContact fits the dispatcher's collision algorithm pool");

// A constraint's island, as Bullet's btGetConstraintIslandId (btDiscreteDynamicsWorld.cpp): its
// first body's, or its second's when the first is in none (a static body).
int constraintIsland(const btTypedConstraint* c) {
  const int a = c->getRigidBodyA().getIslandTag();
  return a >= 0 ? a : c->getRigidBodyB().getIslandTag();
}

// Bullet's ordering of the constraints by island (btSortConstraintOnIslandPredicate), the same
// comparisons so that its quickSort leaves the same order.
struct ByIsland {
  bool operator()(const btTypedConstraint* lhs, const btTypedConstraint* rhs) const {
    return constraintIsland(lhs) < constraintIsland(rhs);
  }
};

}  // namespace

// Bullet's island callback (InplaceSolverIslandCallback, btDiscreteDynamicsWorld.cpp), which
// gathers islands into batches of at least m_minimumSolverBatchSize constraints and contact
// manifolds and solves each batch with one solveGroup, with one change: the constraints of island
// `id` are found by binary search over the islands of the sorted constraints, computed once per
// sub-step, instead of by a scan of every constraint per island. The sorted array is ordered by
// island, so the island's constraints are one run of it: the run Bullet's scan finds (its first
// constraint with the island, and as many as follow with it), in the same order.
class ConstraintRuns final : public btSimulationIslandManager::IslandCallback {
 public:
  ConstraintRuns(btConstraintSolver* solver, btDispatcher* dispatcher) : solver_(solver), dispatcher_(dispatcher) {}

  void setup(btConstraintSolver* solver, btContactSolverInfo* info, btTypedConstraint** sorted, int count,
             btIDebugDraw* debugDrawer) {
    solver_ = solver;
    info_ = info;
    sorted_ = sorted;
    count_ = count;
    debugDrawer_ = debugDrawer;
    islands_.resize(count);
    for (int i = 0; i < count; ++i) islands_[i] = constraintIsland(sorted[i]);
    bodies_.resize(0);
    manifolds_.resize(0);
    constraints_.resize(0);
  }

  void processIsland(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
                     int islandId) override {
    if (islandId < 0) {
      // Bullet does not split islands: everything in one group.
      solver_->solveGroup(bodies, numBodies, manifolds, numManifolds, count_ ? sorted_ : nullptr, count_, *info_,
                          debugDrawer_, dispatcher_);
      return;
    }
    const auto run = std::equal_range(islands_.begin(), islands_.end(), islandId);
    btTypedConstraint** first = run.first == run.second ? nullptr : sorted_ + (run.first - islands_.begin());
    const int n = static_cast<int>(run.second - run.first);
    if (info_->m_minimumSolverBatchSize <= 1) {
      solver_->solveGroup(bodies, numBodies, manifolds, numManifolds, first, n, *info_, debugDrawer_, dispatcher_);
      return;
    }
    for (int i = 0; i < numBodies; ++i) bodies_.push_back(bodies[i]);
    for (int i = 0; i < numManifolds; ++i) manifolds_.push_back(manifolds[i]);
    for (int i = 0; i < n; ++i) constraints_.push_back(first[i]);
    if (constraints_.size() + manifolds_.size() > info_->m_minimumSolverBatchSize) processConstraints();
  }

  // Solves the batch gathered so far.
  void processConstraints() {
    solver_->solveGroup(bodies_.size() ? &bodies_[0] : nullptr, bodies_.size(),
                        manifolds_.size() ? &manifolds_[0] : nullptr, manifolds_.size(),
                        constraints_.size() ? &constraints_[0] : nullptr, constraints_.size(), *info_, debugDrawer_,
                        dispatcher_);
    bodies_.resize(0);
    manifolds_.resize(0);
    constraints_.resize(0);
  }

 private:
  btConstraintSolver* solver_;
  btDispatcher* dispatcher_;
  btContactSolverInfo* info_ = nullptr;
  btTypedConstraint** sorted_ = nullptr;
  int count_ = 0;
  btIDebugDraw* debugDrawer_ = nullptr;
  std::vector<int> islands_;  // the island of each sorted constraint: ascending
  btAlignedObjectArray<btCollisionObject*> bodies_;
  btAlignedObjectArray<btPersistentManifold*> manifolds_;
  btAlignedObjectArray<btTypedConstraint*> constraints_;
};

bool boxClearOfPlane(const btCollisionShape& box, const btTransform& boxTransform,
                     const btStaticPlaneShape& plane, const btTransform& planeTransform,
                     btScalar threshold) {
  // The plane in world coordinates: n . p = c.
  const btVector3 n = planeTransform.getBasis() * plane.getPlaneNormal();
  const btScalar c = plane.getPlaneConstant() + n.dot(planeTransform.getOrigin());
  // The lowest n . p over the bounding box, which holds the shape and its margin.
  btVector3 lo, hi;
  box.getAabb(boxTransform, lo, hi);
  btScalar lowest = 0;
  for (int i = 0; i < 3; ++i) lowest += n[i] * (n[i] > 0 ? lo[i] : hi[i]);
  return lowest - c > threshold + kSlack;
}

DiscreteWorld::DiscreteWorld(btCollisionDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                             btConstraintSolver* solver, btCollisionConfiguration* configuration)
    : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration),
      islands_(std::make_unique<ConstraintRuns>(solver, dispatcher)) {
  getDispatchInfo().m_useContinuous = false;
  registerCollisionAlgorithm<GroundContact>(*dispatcher, BOX_SHAPE_PROXYTYPE, STATIC_PLANE_PROXYTYPE);
}

void DiscreteWorld::predictUnconstraintMotion(btScalar timeStep) {
  for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) {
    btRigidBody* body = m_nonStaticRigidBodies[i];
    if (body->isStaticOrKinematicObject()) continue;
    // (Bullet's "additional damping" is off unless a body is built with it; none is.)
    if (body->getLinearDamping() != 0 || body->getAngularDamping() != 0) body->applyDamping(timeStep);
  }
}

void DiscreteWorld::createPredictiveContacts(btScalar) {
  releasePredictiveContacts();
  for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) m_nonStaticRigidBodies[i]->setHitFraction(1.f);
}

DiscreteWorld::~DiscreteWorld() = default;

// btDiscreteDynamicsWorld::solveConstraints, step for step, with ConstraintRuns for Bullet's
// island callback.
void DiscreteWorld::solveConstraints(btContactSolverInfo& solverInfo) {
  m_sortedConstraints.resize(m_constraints.size());
  for (int i = 0; i < getNumConstraints(); ++i) m_sortedConstraints[i] = m_constraints[i];
  m_sortedConstraints.quickSort(ByIsland());
  btTypedConstraint** sorted = getNumConstraints() ? &m_sortedConstraints[0] : nullptr;
  islands_->setup(m_constraintSolver, &solverInfo, sorted, m_sortedConstraints.size(), getDebugDrawer());
  m_constraintSolver->prepareSolve(getCollisionWorld()->getNumCollisionObjects(),
                                   getCollisionWorld()->getDispatcher()->getNumManifolds());
  m_islandManager->buildAndProcessIslands(getCollisionWorld()->getDispatcher(), getCollisionWorld(), islands_.get());
  islands_->processConstraints();
  m_constraintSolver->allSolved(solverInfo, m_debugDrawer);
}

}  // namespace gaitlab::physics
