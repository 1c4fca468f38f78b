// A character's joints turn within the ranges its creature file gives (body/creature.h), in the
// file's sign: a hip's positive angle about x swings the leg backwards, its negative forwards.
// The biped's hips are the shipped joints whose ranges are not symmetric (forward 2.0 rad,
// backward 0.7 rad), so they show whether the physics reads a range the right way round
// (physics/character.cpp: Bullet's 6-DOF joint measures the opposite sign to ours). Its gaits
// stop the forward swing at 0.7 rad (GaitParams::hipForwardStop), on the same joint.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <vector>

#include "body/morphology.h"
#include "physics/character.h"
#include "physics/world.h"

namespace {

using Eigen::Vector3d;
using gaitlab::body::Morphology;
using gaitlab::physics::Character;
using gaitlab::physics::World;

// The left hip's angles after 2 s of a steady torque about the torso's x axis, weightless and out
// of reach of the ground: the thigh's rotation relative to the torso as Rz(z)·Ry(y)·Rx(x), the
// order in which the physics limits a ball joint's three angles.
// With `stop`, the gait's forward stop set on the hips first (Character::setHipForwardStop).
Vector3d hipAnglesUnderTorque(double torqueAboutX, double stop = -1) {
  World world;
  world.dynamics().setGravity(btVector3(0, 0, 0));
  const Morphology biped = gaitlab::body::shippedCreature("biped");
  Character character(world, biped, Vector3d(0, 3, 0), 0.0);
  if (stop > 0) character.setHipForwardStop(stop);
  const int thigh = biped.legs[0].upper, torso = biped.segments[thigh].parent;
  std::vector<Vector3d> torques(biped.segments.size(), Vector3d::Zero());
  for (int step = 0; step < 240; ++step) {
    torques[thigh] = character.segmentState(torso).orientation * Vector3d(torqueAboutX, 0, 0);
    character.applyJointTorques(torques.data());
    world.step();
  }
  const Eigen::Matrix3d r = (character.segmentState(torso).orientation.conjugate() *
                             character.segmentState(thigh).orientation).toRotationMatrix();
  return {std::atan2(r(2, 1), r(2, 2)), -std::asin(r(2, 0)), std::atan2(r(1, 0), r(0, 0))};
}

}  // namespace

TEST(JointRange, TheBipedsHipSwingsForwardAndBackwardAsFarAsItsFileSays) {
  const Morphology biped = gaitlab::body::shippedCreature("biped");
  const auto& hip = biped.segments[biped.legs[0].upper].joint;
  ASSERT_LT(hip.lower[0], -1.5) << "the file lets the thigh swing forwards 2.0 rad";
  ASSERT_LT(hip.upper[0], 1.0) << "and backwards 0.7 rad";
  for (double torque : {-15.0, 15.0}) {
    SCOPED_TRACE(torque < 0 ? "driven forwards" : "driven backwards");
    const Vector3d angles = hipAnglesUnderTorque(torque);
    // Driven into its limit, the swing rests there; the other two axes, pushed by the reaction,
    // stay inside their own ranges.
    EXPECT_NEAR(angles.x(), torque < 0 ? hip.lower[0] : hip.upper[0], 0.05);
    for (int a = 1; a < 3; ++a) {
      EXPECT_GE(angles[a], hip.lower[a] - 0.05) << "axis " << a;
      EXPECT_LE(angles[a], hip.upper[a] + 0.05) << "axis " << a;
    }
  }
}

// The gait's forward stop is a limit of the same joint: driven forwards the thigh rests on it, and
// set beyond the body's range (a get-up releases it so) the body's own limit holds again.
// Backwards nothing changes.
TEST(JointRange, TheGaitsForwardStopHoldsTheBipedsHipWhereItSays) {
  const Morphology biped = gaitlab::body::shippedCreature("biped");
  const auto& hip = biped.segments[biped.legs[0].upper].joint;
  EXPECT_NEAR(hipAnglesUnderTorque(-15.0, 0.7).x(), -0.7, 0.05);
  EXPECT_NEAR(hipAnglesUnderTorque(-15.0, 1.2).x(), -1.2, 0.05);
  EXPECT_NEAR(hipAnglesUnderTorque(-15.0, 3.2).x(), hip.lower[0], 0.05);
  EXPECT_NEAR(hipAnglesUnderTorque(15.0, 0.7).x(), hip.upper[0], 0.05);
}
