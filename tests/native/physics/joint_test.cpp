// physics::Joint: a 6-DOF joint whose angular limit rows exist only near a limit (physics/joint.h).
// It must drop the rows only where they are idle, and hold its limits as Bullet's joint does.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <memory>

#include "physics/joint.h"
#include "physics/world.h"

namespace {

using gaitlab::physics::Joint;
using gaitlab::physics::World;

constexpr double kRange = 1.0;  // every angular axis turns within [-1, 1] rad

// A 1 kg box hanging from a static box by a ball joint at the static box's centre, out of reach
// of the ground (no collisions at all). `plain` makes it Bullet's own 6-DOF joint instead.
struct Pendulum {
  World world;
  btRigidBody* parent;
  btRigidBody* child;
  std::unique_ptr<btGeneric6DofSpring2Constraint> joint;

  explicit Pendulum(bool plain = false) {
    const Eigen::Quaterniond upright = Eigen::Quaterniond::Identity();
    parent = world.addBox({0.1, 0.1, 0.1}, 0.0, {0, 5, 0}, upright, 0, 0, 0.5);
    child = world.addBox({0.05, 0.2, 0.05}, 1.0, {0, 4.8, 0}, upright, 0, 0, 0.5);
    const btTransform pivot(btQuaternion::getIdentity(), btVector3(0, 5, 0));
    const btTransform inParent = parent->getWorldTransform().inverse() * pivot;
    const btTransform inChild = child->getWorldTransform().inverse() * pivot;
    if (plain) {
      joint = std::make_unique<btGeneric6DofSpring2Constraint>(*parent, *child, inParent, inChild, RO_XYZ);
    } else {
      joint = std::make_unique<Joint>(*parent, *child, inParent, inChild,
                                      static_cast<btScalar>(gaitlab::physics::kFixedStep / gaitlab::physics::kPhysicsSubsteps),
                                      world.dynamics().getSolverInfo().m_erp);
    }
    joint->setLinearLowerLimit(btVector3(0, 0, 0));
    joint->setLinearUpperLimit(btVector3(0, 0, 0));
    joint->setAngularLowerLimit(btVector3(-kRange, -kRange, -kRange));
    joint->setAngularUpperLimit(btVector3(kRange, kRange, kRange));
    world.dynamics().addConstraint(joint.get(), true);
  }
  ~Pendulum() { world.dynamics().removeConstraint(joint.get()); }

  // Turns the child about the pivot to `angle` about x, spinning at `rate` rad/s about x.
  void pose(double angle, double rate) {
    const btTransform turn(btQuaternion(btVector3(1, 0, 0), static_cast<btScalar>(angle)));
    const btTransform aroundPivot = btTransform(btQuaternion::getIdentity(), btVector3(0, 5, 0)) * turn *
                                    btTransform(btQuaternion::getIdentity(), btVector3(0, -5, 0));
    child->setWorldTransform(aroundPivot * btTransform(btQuaternion::getIdentity(), btVector3(0, 4.8, 0)));
    child->setAngularVelocity(btVector3(static_cast<btScalar>(rate), 0, 0));
    child->setLinearVelocity(btVector3(0, 0, 0));
  }
  int rows() {
    btTypedConstraint::btConstraintInfo1 info;
    joint->getInfo1(&info);
    return info.m_numConstraintRows;
  }
  double angleX() const {
    const btQuaternion q = child->getWorldTransform().getRotation();
    return 2 * std::atan2(q.x(), q.w());
  }
};

TEST(Joint, FarFromItsLimitsAJointHasOnlyItsLockedRows) {
  Pendulum p;
  p.pose(0.0, 0.0);
  EXPECT_EQ(p.rows(), 3) << "3 locked translations, no limit rows";
  EXPECT_EQ(static_cast<Joint&>(*p.joint).droppedAxes(), 0b111);
  Pendulum bullet(true);
  bullet.pose(0.0, 0.0);
  EXPECT_EQ(bullet.rows(), 3 + 3 * 2) << "Bullet's joint: a lower and an upper row per ranged axis";
}

TEST(Joint, NearALimitTheAxisKeepsBothRows) {
  Pendulum p;
  p.pose(kRange - 0.02, 0.0);
  EXPECT_EQ(p.rows(), 3 + 2);
  EXPECT_EQ(static_cast<Joint&>(*p.joint).droppedAxes(), 0b110) << "x keeps its rows, y and z not";
}

TEST(Joint, AJointApproachingItsLimitFastKeepsTheRows) {
  // 0.5 rad from the limit, a row acts once the approach is faster than fps·erp·0.5 = 24 rad/s.
  Pendulum p;
  p.pose(kRange - 0.5, 1.0);
  EXPECT_EQ(p.rows(), 3) << "1 rad/s, with the headroom of 8, is well below it";
  p.pose(kRange - 0.5, 5.0);
  EXPECT_EQ(p.rows(), 3 + 2) << "5 rad/s with the headroom of 8 is above it";
}

// Driven hard into its limit, the joint stops there as Bullet's joint does.
TEST(Joint, HoldsItsLimitAsBulletsJointDoes) {
  double largest[2] = {0, 0};
  for (bool plain : {false, true}) {
    Pendulum p(plain);
    for (int step = 0; step < 120; ++step) {
      p.child->applyTorque(btVector3(4, 0, 0));  // 4 N·m about x on a 1 kg, 0.4 m stick
      p.world.step();
      largest[plain] = std::max(largest[plain], p.angleX());
    }
    EXPECT_NEAR(p.angleX(), kRange, 0.05) << (plain ? "Bullet" : "Joint") << " rests at the limit";
  }
  EXPECT_LT(largest[0], kRange + 0.05) << "overshoot";
  EXPECT_NEAR(largest[0], largest[1], 0.01) << "the same overshoot as Bullet's joint";
}

}  // namespace
