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
// DiscreteWorld skips these and keeps the rest (damping of damped bodies, hit fractions, dropping
// predictive contacts, Bullet's algorithm for every box near the plane), so it computes bit for bit
// what btDiscreteDynamicsWorld computes with m_useContinuous = false:
// tests/native/physics/discrete_world_test.cpp.
#pragma once
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h>

class btCollisionDispatcher;
class btStaticPlaneShape;

namespace gaitlab::physics {

class DiscreteWorld final : public btDiscreteDynamicsWorld {
 public:
  // As btDiscreteDynamicsWorld's constructor; also installs the box-plane contact algorithm in
  // `dispatcher` and turns continuous collision detection off.
  DiscreteWorld(btCollisionDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                btConstraintSolver* solver, btCollisionConfiguration* configuration);

 protected:
  void predictUnconstraintMotion(btScalar timeStep) override;
  void createPredictiveContacts(btScalar timeStep) override;
};

// Whether every point of `box` (a convex shape with its margin) lies more than `threshold` above
// `plane`, judged from the box's bounding box with 1 mm to spare for rounding.
bool boxClearOfPlane(const btCollisionShape& box, const btTransform& boxTransform,
                     const btStaticPlaneShape& plane, const btTransform& planeTransform,
                     btScalar threshold);

}  // namespace gaitlab::physics
