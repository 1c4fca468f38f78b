#include "physics/world.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>

#if GAITLAB_BULLET_MT
#include <BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h>
#include <BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h>
#endif

#include "physics/convert.h"
#include "physics/discrete_world.h"
#include "physics/solver.h"

namespace gaitlab::physics {

namespace {

// Bullet's sequential-impulse solver keeps its working arrays from step to step, but grows them
// whenever a step needs more rows than any step before (a joint reaching a limit adds rows, every
// new contact point three): a heap allocation in the middle of a step, at a moment nobody chose.
// This solver sizes them for the worst case of the world's contents instead, once per change of
// contents (World::reserve, at scene building, or else at the start of the next step), so that
// steps in a steady scene allocate nothing (docs/design.md, parallel execution;
// tests/native/sim/hot_path_test.cpp).
class ReservingSolver : public InterleavedSolver {
 public:
  void reserveFor(int bodies, int joints) {
    // With some room to spare, so that a prop arriving from another shard (sim::Simulation's
    // rehomeProps, between steps) does not make the next step reallocate.
    bodies = (bodies + 31) / 32 * 32;
    joints = (joints + 31) / 32 * 32;
    // A 6-DOF joint has at most 12 rows (a limit and a motor per axis); a body touches at most
    // the ground and a couple of props, 4 points per contact manifold, each point a normal row
    // and two friction rows.
    const int jointRows = 12 * joints, contactPoints = 3 * 4 * bodies;
    m_tmpSolverBodyPool.reserve(bodies + 1);
    m_tmpConstraintSizesPool.reserve(joints);
    m_tmpSolverNonContactConstraintPool.reserve(jointRows);
    m_orderNonContactConstraintPool.reserve(jointRows);
    m_tmpSolverContactConstraintPool.reserve(contactPoints);
    m_orderTmpConstraintPool.reserve(contactPoints);
    m_tmpSolverContactFrictionConstraintPool.reserve(2 * contactPoints);
    m_orderFrictionConstraintPool.reserve(2 * contactPoints);
    reserveSchedule(jointRows + 3 * contactPoints, bodies + 1);
  }
};

btDefaultCollisionConstructionInfo poolSizes(int contactPool) {
  btDefaultCollisionConstructionInfo info;
  info.m_defaultMaxPersistentManifoldPoolSize = contactPool;
  info.m_defaultMaxCollisionAlgorithmPoolSize = contactPool;
  return info;
}
}  // namespace

#if GAITLAB_BULLET_MT
// Only in the probe build `gaitlab_bullet_mt` (native/CMakeLists.txt, docs/parallel.md): Bullet's
// own multithreaded world, whose collision dispatch and island solving run on the task scheduler
// installed with btSetTaskScheduler, measured against gaitlab's physics shards.
World::World(int contactPool)
    : config_(std::make_unique<btDefaultCollisionConfiguration>(poolSizes(contactPool))),
      dispatcher_(std::make_unique<btCollisionDispatcherMt>(config_.get(), 40)),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btConstraintSolverPoolMt>(8)),
      dynamics_(std::make_unique<btDiscreteDynamicsWorldMt>(
          dispatcher_.get(), broadphase_.get(), static_cast<btConstraintSolverPoolMt*>(solver_.get()),
          nullptr, config_.get())) {
#else
World::World(int contactPool)
    : config_(std::make_unique<btDefaultCollisionConfiguration>(poolSizes(contactPool))),
      dispatcher_(std::make_unique<btCollisionDispatcher>(config_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<ReservingSolver>()),
      dynamics_(std::make_unique<DiscreteWorld>(dispatcher_.get(), broadphase_.get(),
                                                solver_.get(), config_.get())) {
#endif
  dynamics_->setGravity(btVector3(0, -9.81f, 0));
  dynamics_->getSolverInfo().m_numIterations = kSolverIterations;  // see world.h

  // Ground: a static plane at y = 0; setTerrain adds slopes or bumps (physics/terrain.h).
  shapes_.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0));
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
  info.m_friction = 1.0f;
  ground_ = new btRigidBody(info);
  dynamics_->addRigidBody(ground_, kGroundGroup, kGroundMask);
  bodies_.push_back(ground_);
}

World::~World() {
  for (int i = dynamics_->getNumConstraints() - 1; i >= 0; --i) {
    btTypedConstraint* c = dynamics_->getConstraint(i);
    dynamics_->removeConstraint(c);
    delete c;
  }
  for (btRigidBody* b : bodies_) {
    dynamics_->removeRigidBody(b);
    delete b->getMotionState();
    delete b;
  }
}

btRigidBody* World::addBox(const Eigen::Vector3d& halfExtents, double mass,
                           const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                           int group, int mask, double friction) {
  // Bullet keeps a collision margin inside each box (0.04 m by default): more than a foot's
  // half height (0.02-0.03 m), which left feet sinking through the ground. A margin of a fifth
  // of the smallest half extent, at most 1 cm, keeps contacts stable and boxes their true size.
  auto box = std::make_unique<btBoxShape>(toBt(halfExtents));
  box->setMargin(static_cast<btScalar>(std::min(0.01, 0.2 * halfExtents.minCoeff())));
  shapes_.push_back(std::move(box));
  btCollisionShape* shape = shapes_.back().get();
  btVector3 inertia(0, 0, 0);
  if (mass > 0) shape->calculateLocalInertia(static_cast<btScalar>(mass), inertia);
  btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, shape,
                                                inertia);
  info.m_startWorldTransform = btTransform(toBt(orientation), toBt(position));
  info.m_friction = static_cast<btScalar>(friction);
  auto* body = new btRigidBody(info);
  body->setActivationState(DISABLE_DEACTIVATION);  // characters must never be put to sleep
  dynamics_->addRigidBody(body, group, mask);
  bodies_.push_back(body);
  return body;
}

Eigen::Vector3d World::gravity() const {
  const btVector3 g = dynamics_->getGravity();
  return {g.x(), g.y(), g.z()};
}

void World::removeBody(btRigidBody* body) {
  auto it = std::find(bodies_.begin(), bodies_.end(), body);
  if (it == bodies_.end()) return;
  dynamics_->removeRigidBody(body);
  bodies_.erase(it);
  btCollisionShape* shape = body->getCollisionShape();
  delete body;
  shapes_.erase(std::remove_if(shapes_.begin(), shapes_.end(),
                               [&](const auto& s) { return s.get() == shape; }),
                shapes_.end());
}

void World::moveBodyTo(btRigidBody* body, World& other) {
  auto it = std::find(bodies_.begin(), bodies_.end(), body);
  if (it == bodies_.end() || &other == this) return;
  const int group = body->getBroadphaseHandle()->m_collisionFilterGroup;
  const int mask = body->getBroadphaseHandle()->m_collisionFilterMask;
  dynamics_->removeRigidBody(body);  // also drops its contact manifolds in this world
  bodies_.erase(it);
  btCollisionShape* shape = body->getCollisionShape();
  auto s = std::find_if(shapes_.begin(), shapes_.end(), [&](const auto& p) { return p.get() == shape; });
  if (s != shapes_.end()) {
    other.shapes_.push_back(std::move(*s));
    shapes_.erase(s);
  }
  other.dynamics_->addRigidBody(body, group, mask);
  other.bodies_.push_back(body);
}

void World::setFastSolver(bool on) {
#if !GAITLAB_BULLET_MT
  static_cast<ReservingSolver*>(solver_.get())->setInterleaving(on);
#else
  (void)on;
#endif
}

void World::setFastJointRows(bool on) {
#if !GAITLAB_BULLET_MT
  static_cast<ReservingSolver*>(solver_.get())->setFastJointRows(on);
#else
  (void)on;
#endif
}

std::pair<long, long> World::solverBatches() const {
#if !GAITLAB_BULLET_MT
  const auto& c = static_cast<const ReservingSolver*>(solver_.get())->counts();
  return {c.batches, c.fast};
#else
  return {0, 0};
#endif
}

void World::reserve() {
  const int bodies = dynamics_->getNumCollisionObjects(), joints = dynamics_->getNumConstraints();
  if (bodies != reservedBodies_ || joints != reservedJoints_) {
#if !GAITLAB_BULLET_MT
    static_cast<ReservingSolver*>(solver_.get())->reserveFor(bodies, joints);
#endif
    reservedBodies_ = bodies;
    reservedJoints_ = joints;
  }
  applied_.reserve(bodies_.size());
}

void World::step() {
  reserve();
  // Each stepSimulation() call ends by clearing the applied forces and torques, so the
  // controller's joint torques, applied once per control step, are saved and applied again
  // before every later sub-step: they act for the whole 1/120 s, not only its first half.
  const auto h = static_cast<btScalar>(kFixedStep / kPhysicsSubsteps);
  applied_.resize(bodies_.size());
  for (size_t b = 0; b < bodies_.size(); ++b)
    applied_[b] = {bodies_[b]->getTotalForce(), bodies_[b]->getTotalTorque()};
  for (int i = 0; i < kPhysicsSubsteps; ++i) {
    if (i > 0) {
      for (size_t b = 0; b < bodies_.size(); ++b) {
        bodies_[b]->applyCentralForce(applied_[b].first);
        bodies_[b]->applyTorque(applied_[b].second);
      }
    }
    dynamics_->stepSimulation(h, 0, h);
  }
}

double World::terrainHeight(double x, double z, double fallback) const {
  const btVector3 from(static_cast<btScalar>(x), 100, static_cast<btScalar>(z));
  const btVector3 to(static_cast<btScalar>(x), -100, static_cast<btScalar>(z));
  // The relief lies above the plane wherever it exists (terrain.h), so its hit is the ground.
  if (relief_) {
    btCollisionWorld::ClosestRayResultCallback hit(from, to);
    btCollisionWorld::rayTestSingle(btTransform(btQuaternion::getIdentity(), from),
                                    btTransform(btQuaternion::getIdentity(), to), relief_,
                                    relief_->getCollisionShape(), relief_->getWorldTransform(), hit);
    if (hit.hasHit()) return hit.m_hitPointWorld.y();
  }
  // The plane is horizontal: its height is its origin's, where the ray (y from 100 to -100)
  // crosses it. Bullet's ray test against a plane shape cuts two triangles out of it first, and
  // it ran for every character and step (the controller's and the fall test's ground queries).
  const btScalar plane = ground_->getWorldTransform().getOrigin().y();
  return plane < from.y() && plane > to.y() ? plane : fallback;
}

void World::setTerrain(std::shared_ptr<const Terrain> terrain) {
  if (relief_) {
    removeBody(relief_);  // its contact manifolds go with it
    relief_ = nullptr;
  }
  terrain_ = std::move(terrain);
  btTransform plane = btTransform::getIdentity();
  plane.setOrigin(btVector3(0, static_cast<btScalar>(terrain_ ? terrain_->planeHeight() : 0.0), 0));
  ground_->setWorldTransform(plane);
  ground_->setInterpolationWorldTransform(plane);
  dynamics_->updateSingleAabb(ground_);
  if (!terrain_ || terrain_->flat()) return;
  registerTerrainCollision(*dispatcher_);
  btTransform where;
  shapes_.push_back(makeHeightfieldShape(*terrain_, &where));
  btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, shapes_.back().get());
  info.m_friction = ground_->getFriction();
  info.m_startWorldTransform = where;
  relief_ = new btRigidBody(info);
  dynamics_->addRigidBody(relief_, kGroundGroup, kGroundMask);
  bodies_.push_back(relief_);
}

void World::updateContacts() const {
  btDispatcher* d = dynamics_->getDispatcher();
  for (int i = 0; i < d->getNumManifolds(); ++i) {
    const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
    int touching = 0;
    for (int c = 0; c < m->getNumContacts(); ++c)
      if (m->getContactPoint(c).getDistance() < 0.01f) ++touching;
    if (touching == 0) continue;
    const btCollisionObject* a = m->getBody0();
    const btCollisionObject* b = m->getBody1();
    // Only contacts with the ground or props count as foot strikes.
    const bool aEnv = !(a->getBroadphaseHandle()->m_collisionFilterGroup & kCharacterGroup);
    const bool bEnv = !(b->getBroadphaseHandle()->m_collisionFilterGroup & kCharacterGroup);
    if (bEnv && a->getUserPointer()) *static_cast<bool*>(a->getUserPointer()) = true;
    if (aEnv && b->getUserPointer()) *static_cast<bool*>(b->getUserPointer()) = true;
  }
}

}  // namespace gaitlab::physics
