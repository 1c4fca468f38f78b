// Bullet's discrete dynamics world without the work whose results gaitlab never uses.
//
// Profiled on walking crowds (docs/parallel.md, "Work Bullet does for nothing"), a sub-step of
// btDiscreteDynamicsWorld spends time on things gaitlab's scenes do not need:
//
// - Continuous collision detection (CCD). Bullet integrates every body's transform twice before
//   the real integration: once for swept bounding boxes (predictUnconstraintMotion) and once to
//   test the motion against the body's CCD threshold (createPredictiveContacts). gaitlab detects
//   collisions at the present transforms only (m_useContinuous = false, set here), and no body has
//   motion states to interpolate, so both results go unused.
// - Damping. No gaitlab body is damped, and Bullet multiplies undamped velocities by
//   pow(1 - 0, h), which is exactly 1.
// - The ground plane. Bullet gives a plane an infinite bounding box, so the ground is paired with
//   every body and its convex-plane algorithm runs for each in every sub-step, though of a walking
//   biped's 7 boxes usually only the feet are near the ground. For a box whose bounding box is
//   farther from the plane than the contact threshold, and whose contact manifold with the plane
//   holds no points, that algorithm finds the box's lowest point beyond the threshold and adds and
//   refreshes nothing: the bounding box alone says as much (boxClearOfPlane).
//
// And one thing it does in time that grows with the square of the crowd:
//
// - Finding an island's joints. Bullet sorts the world's constraints by island, then for every
//   island (here one per character) its island callback (InplaceSolverIslandCallback,
//   btDiscreteDynamicsWorld.cpp) scans the sorted array from its start for the island's first
//   constraint and on to its end counting the island's constraints: every island reads every
//   constraint, twice per fixed step. A profile of one world of 250 quadrupeds (the peer
//   benchmark's reference scene, docs/peers.md) spends 37 % of the step there, of 400 quadrupeds
//   48 %, of 100 7 %. DiscreteWorld finds the same run of constraints by binary search in the
//   same sorted array (ConstraintRuns) and hands the solver the same batches.
//
// DiscreteWorld skips these and keeps the rest (damping of damped bodies, hit fractions, dropping
// predictive contacts, Bullet's algorithm for every box near the plane), so it computes bit for bit
// what btDiscreteDynamicsWorld computes with m_useContinuous = false:
// tests/native/physics/discrete_world_test.cpp.
#pragma once
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>

#include <memory>

class btCollisionDispatcher;
class btStaticPlaneShape;

namespace gaitlab::physics {

class ConstraintRuns;

class DiscreteWorld final : public btDiscreteDynamicsWorld {
 public:
  // As btDiscreteDynamicsWorld's constructor; also installs the box-plane contact algorithm in
  // `dispatcher` and turns continuous collision detection off.
  DiscreteWorld(btCollisionDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                btConstraintSolver* solver, btCollisionConfiguration* configuration);
  ~DiscreteWorld() override;

 protected:
  void predictUnconstraintMotion(btScalar timeStep) override;
  void createPredictiveContacts(btScalar timeStep) override;
  // btDiscreteDynamicsWorld::solveConstraints with ConstraintRuns as the island callback.
  void solveConstraints(btContactSolverInfo& solverInfo) override;

 private:
  std::unique_ptr<ConstraintRuns> islands_;
};

// Whether every point of `box` (a convex shape with its margin) lies more than `threshold` above
// `plane`, judged from the box's bounding box with 1 mm to spare for rounding.
bool boxClearOfPlane(const btCollisionShape& box, const btTransform& boxTransform,
                     const btStaticPlaneShape& plane, const btTransform& planeTransform,
                     btScalar threshold);

}  // namespace gaitlab::physics
