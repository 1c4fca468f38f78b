#include "sim/state_hash.h"

#include <btBulletDynamicsCommon.h>

#include <cstdio>

#include "physics/fnv1a.h"

namespace gaitlab::sim {

std::string stateHash(const RenderPublisher& bodies) {
  Fnv1a h;
  for (int i = 0; i < bodies.count(); ++i) {
    const btRigidBody* b = bodies.body(i);
    const btTransform& t = b->getCenterOfMassTransform();
    const btQuaternion q = t.getRotation();
    const btScalar v[] = {t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z(),
                          q.x(), q.y(), q.z(), q.w(),
                          b->getLinearVelocity().x(), b->getLinearVelocity().y(),
                          b->getLinearVelocity().z(), b->getAngularVelocity().x(),
                          b->getAngularVelocity().y(), b->getAngularVelocity().z()};
    h.bytes(v, sizeof(v));
  }
  char out[17];
  std::snprintf(out, sizeof(out), "%016llx", static_cast<unsigned long long>(h.h));
  return out;
}

}  // namespace gaitlab::sim
