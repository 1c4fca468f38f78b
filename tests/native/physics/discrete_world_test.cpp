// physics::DiscreteWorld skips work whose results gaitlab never uses (physics/discrete_world.h).
// It must compute bit for bit what Bullet's own world computes with discrete collision detection,
// and its skip of the ground-plane algorithm must both happen and never hide a contact.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "physics/discrete_world.h"

namespace {

using gaitlab::physics::boxClearOfPlane;
using gaitlab::physics::DiscreteWorld;

// One Bullet world with a ground plane and a pile of tumbling boxes, two of them jointed, one
// damped, one pushed every step. `ours` builds a DiscreteWorld, else Bullet's world with
// m_useContinuous = false.
struct Scene {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::unique_ptr<btTypedConstraint> joint;
  std::vector<std::unique_ptr<btTypedConstraint>> chainJoints;

  // `chains` more islands: chains of four boxes joined by hinges and 6-DOF joints, falling onto
  // the ground side by side; neighbours touch (their islands merge), most do not. With 40, the
  // solver's batches (m_minimumSolverBatchSize) hold the constraints of many islands.
  Scene(bool ours, const btVector3& planeNormal, int chains = 0) {
    if (ours) {
      world = std::make_unique<DiscreteWorld>(&dispatcher, &broadphase, &solver, &config);
    } else {
      world = std::make_unique<btDiscreteDynamicsWorld>(&dispatcher, &broadphase, &solver, &config);
      world->getDispatchInfo().m_useContinuous = false;
    }
    world->setGravity(btVector3(0, -9.81f, 0));
    world->getSolverInfo().m_numIterations = 10;
    shapes.push_back(std::make_unique<btStaticPlaneShape>(planeNormal.normalized(), 0));
    add(0, btTransform::getIdentity())->setFriction(1);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int i = 0; i < 12; ++i) {
      shapes.push_back(std::make_unique<btBoxShape>(btVector3(0.05f + 0.1f * (i % 3), 0.04f + 0.05f * (i % 2), 0.12f)));
      btTransform t(btQuaternion(btVector3(u(rng), u(rng), u(rng)).normalized(), 3 * u(rng)),
                    btVector3(1.5f * (i % 4) - 2, 0.3f + 0.25f * i, 1.5f * (i / 4) - 1.5f));
      btRigidBody* b = add(1 + i % 3, t);
      b->setAngularVelocity(btVector3(u(rng), u(rng), u(rng)) * 4);
      b->setLinearVelocity(btVector3(u(rng), 0, u(rng)));
      b->setFriction(0.8f);
    }
    bodies[5]->setDamping(0.2f, 0.3f);
    joint = std::make_unique<btGeneric6DofSpring2Constraint>(
        *bodies[1], *bodies[2], btTransform(btQuaternion::getIdentity(), btVector3(0.3f, 0, 0)),
        btTransform(btQuaternion::getIdentity(), btVector3(-0.3f, 0, 0)));
    world->addConstraint(joint.get(), true);
    for (int c = 0; c < chains; ++c) {
      shapes.push_back(std::make_unique<btBoxShape>(btVector3(0.08f, 0.08f, 0.2f)));
      const btVector3 base(0.7f * (c % 8) + 6, 0.6f + 0.1f * (c % 3), 0.9f * (c / 8) - 2);
      btRigidBody* previous = nullptr;
      for (int k = 0; k < 4; ++k) {
        btTransform t(btQuaternion(btVector3(1, 0, 0), 0.3f * u(rng)), base + btVector3(0, 0.05f * k, 0.42f * k));
        btRigidBody* b = add(1, t);
        b->setFriction(0.9f);
        b->setAngularVelocity(btVector3(u(rng), u(rng), u(rng)));
        if (previous) {
          const btTransform a(btQuaternion::getIdentity(), btVector3(0, 0, 0.21f)), bb(btQuaternion::getIdentity(), btVector3(0, 0, -0.21f));
          if (k % 2) {
            auto h = std::make_unique<btHingeConstraint>(*previous, *b, a, bb);
            h->setLimit(-0.8f, 0.6f);
            chainJoints.push_back(std::move(h));
          } else {
            auto d = std::make_unique<btGeneric6DofSpring2Constraint>(*previous, *b, a, bb);
            d->setAngularLowerLimit(btVector3(-0.5f, -0.4f, -0.3f));
            d->setAngularUpperLimit(btVector3(0.5f, 0.4f, 0.3f));
            chainJoints.push_back(std::move(d));
          }
          world->addConstraint(chainJoints.back().get(), true);
        }
        previous = b;
      }
    }
  }
  ~Scene() {
    for (auto& j : chainJoints) world->removeConstraint(j.get());
    world->removeConstraint(joint.get());
    for (auto& b : bodies) world->removeRigidBody(b.get());
  }

  btRigidBody* add(float mass, const btTransform& t) {
    btCollisionShape* shape = shapes.back().get();
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform = t;
    bodies.push_back(std::make_unique<btRigidBody>(info));
    bodies.back()->setActivationState(DISABLE_DEACTIVATION);
    world->addRigidBody(bodies.back().get());
    return bodies.back().get();
  }

  void step() {
    bodies[3]->applyTorque(btVector3(0, 2, 0));
    bodies[4]->applyCentralForce(btVector3(8, 0, 0));
    world->stepSimulation(1.0f / 240, 0, 1.0f / 240);
  }

  int contactPoints() {
    int n = 0;
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m) n += dispatcher.getManifoldByIndexInternal(m)->getNumContacts();
    return n;
  }
};

bool same(const btVector3& a, const btVector3& b) { return std::memcmp(a.m_floats, b.m_floats, 3 * sizeof(btScalar)) == 0; }

void expectBulletsResults(const btVector3& planeNormal, int chains = 0) {
  Scene bullet(false, planeNormal, chains), ours(true, planeNormal, chains);
  int touched = 0;
  for (int s = 0; s < 4 * 240; ++s) {
    bullet.step();
    ours.step();
    const int points = bullet.contactPoints();
    ASSERT_EQ(ours.contactPoints(), points) << "step " << s;
    touched = std::max(touched, points);
    for (size_t i = 0; i < bullet.bodies.size(); ++i) {
      const btRigidBody& a = *bullet.bodies[i];
      const btRigidBody& b = *ours.bodies[i];
      ASSERT_TRUE(same(a.getWorldTransform().getOrigin(), b.getWorldTransform().getOrigin())) << "body " << i << " step " << s;
      for (int r = 0; r < 3; ++r)
        ASSERT_TRUE(same(a.getWorldTransform().getBasis()[r], b.getWorldTransform().getBasis()[r])) << "body " << i << " step " << s;
      ASSERT_TRUE(same(a.getLinearVelocity(), b.getLinearVelocity())) << "body " << i << " step " << s;
      ASSERT_TRUE(same(a.getAngularVelocity(), b.getAngularVelocity())) << "body " << i << " step " << s;
    }
  }
  // The boxes fell, landed and piled up: both the skip (boxes in the air) and Bullet's algorithm
  // (boxes on the ground) have been exercised.
  EXPECT_GT(touched, 12);
  EXPECT_LT(bullet.bodies[12]->getWorldTransform().getOrigin().y(), 1.0f);
}

TEST(DiscreteWorld, ComputesWhatBulletsWorldComputesOnFlatGround) {
  expectBulletsResults(btVector3(0, 1, 0));
}

TEST(DiscreteWorld, ComputesWhatBulletsWorldComputesOnATiltedPlane) {
  expectBulletsResults(btVector3(0.3f, 1, -0.2f));
}

// Many jointed islands: DiscreteWorld finds each island's joints by binary search where Bullet
// scans every joint per island; the solver must get the same batches, in the same order.
TEST(DiscreteWorld, ComputesWhatBulletsWorldComputesWithManyJointedIslands) {
  expectBulletsResults(btVector3(0, 1, 0), 40);
}

TEST(DiscreteWorld, ABoxIsClearOfThePlaneOnlyWhenAllOfItIsAboveTheThreshold) {
  const btBoxShape box(btVector3(0.1f, 0.05f, 0.2f));  // Bullet's margin lies within these
  const btStaticPlaneShape ground(btVector3(0, 1, 0), 0);
  const btTransform level = btTransform::getIdentity();
  const auto at = [](float y, const btQuaternion& q = btQuaternion::getIdentity()) {
    return btTransform(q, btVector3(0, y, 0));
  };
  EXPECT_TRUE(boxClearOfPlane(box, at(1.0f), ground, level, 0.02f));
  EXPECT_FALSE(boxClearOfPlane(box, at(0.05f), ground, level, 0.02f));   // resting on it
  EXPECT_FALSE(boxClearOfPlane(box, at(0.06f), ground, level, 0.02f));   // 1 cm above: within
  EXPECT_TRUE(boxClearOfPlane(box, at(0.1f), ground, level, 0.02f));    // 5 cm above: beyond
  EXPECT_FALSE(boxClearOfPlane(box, at(1.0f), ground, level, 1.0f));     // a larger threshold
  // Tipped about x, its bounding box reaches 0.2 m below its centre.
  const btQuaternion tipped(btVector3(1, 0, 0), 1.2f);
  EXPECT_FALSE(boxClearOfPlane(box, at(0.2f, tipped), ground, level, 0.02f));
  EXPECT_TRUE(boxClearOfPlane(box, at(0.5f, tipped), ground, level, 0.02f));
  // The plane raised to 0.95 m (as World::setTerrain moves it) or turned upside down.
  const btTransform raised(btQuaternion::getIdentity(), btVector3(0, 0.95f, 0));
  EXPECT_FALSE(boxClearOfPlane(box, at(1.0f), ground, raised, 0.02f));
  const btTransform flipped(btQuaternion(btVector3(1, 0, 0), SIMD_PI), btVector3(0, 2, 0));
  EXPECT_TRUE(boxClearOfPlane(box, at(1.0f), ground, flipped, 0.02f));
}

}  // namespace
