#include "physics/discrete_world.h"

#include <BulletCollision/BroadphaseCollision/btBroadphaseProxy.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btConvexPlaneCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

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

}  // namespace

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
    : btDiscreteDynamicsWorld(dispatcher, broadphase, solver, configuration) {
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

}  // namespace gaitlab::physics
