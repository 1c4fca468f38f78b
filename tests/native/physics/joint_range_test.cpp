// A character's joints turn within the ranges its creature file gives (body/creature.h), in the
// file's sign: a hip's positive angle about x swings the leg backwards, its negative forwards.
// The biped's hips are the shipped joints whose ranges are not symmetric (forward 0.7 rad,
// backward 2.0 rad), so they show whether the physics reads a range the right way round
// (physics/character.cpp: Bullet's 6-DOF joint measures the opposite sign to ours).
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
Vector3d hipAnglesUnderTorque(double torqueAboutX) {
  World world;
  world.dynamics().setGravity(btVector3(0, 0, 0));
  const Morphology biped = gaitlab::body::shippedCreature("biped");
  Character character(world, biped, Vector3d(0, 3, 0), 0.0);
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
  ASSERT_GT(hip.lower[0], -1.0) << "the file lets the thigh swing forwards 0.7 rad";
  ASSERT_GT(hip.upper[0], 1.5) << "and backwards 2.0 rad";
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
