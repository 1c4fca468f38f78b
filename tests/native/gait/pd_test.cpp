// PD controllers (thesis §3.1.7, eq. 3.9), and the orientation PD that fixes the original implementation's
// defect 4: shortest arc, one frame (world) for error, velocities and torque.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "gait/pd.h"

namespace gaitlab::gait {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Quaterniond randomRot(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized();
}

Eigen::Vector3d randomVec(std::mt19937& rng, double s) {
  std::uniform_real_distribution<double> u(-s, s);
  return Eigen::Vector3d(u(rng), u(rng), u(rng));
}

Eigen::Quaterniond negated(const Eigen::Quaterniond& q) {
  return Eigen::Quaterniond(-q.w(), -q.x(), -q.y(), -q.z());
}

TEST(GaitPd, ScalarPdIsEquation39) {
  EXPECT_DOUBLE_EQ(pd(300.0, 30.0, 0.1, -2.0), 300.0 * 0.1 + 30.0 * -2.0);
  // Tracking: e = desired − current, ė = desiredRate − currentRate.
  EXPECT_DOUBLE_EQ(pdTrack(300.0, 30.0, 0.5, 0.7, 1.0), 300.0 * 0.2 - 30.0 * 1.0);
  EXPECT_DOUBLE_EQ(pdTrack(300.0, 30.0, 0.7, 0.7, 0.0), 0.0);
  const Eigen::Vector3d f = pdTrack(10.0, 1.0, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 3, 3),
                                    Eigen::Vector3d(0, 0, 1));
  EXPECT_NEAR((f - Eigen::Vector3d(0, 10, -1)).norm(), 0.0, 1e-12);
}

TEST(GaitPd, ShortestArcQAndMinusQGiveTheSameTorque) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Quaterniond c = randomRot(rng), d = randomRot(rng);
    const Eigen::Vector3d w = randomVec(rng, 3.0);
    const Eigen::Vector3d t = orientationPd(300, 30, c, d, w);
    EXPECT_NEAR((orientationPd(300, 30, negated(c), d, w) - t).norm(), 0.0, 1e-9);
    EXPECT_NEAR((orientationPd(300, 30, c, negated(d), w) - t).norm(), 0.0, 1e-9);
    EXPECT_NEAR((orientationPd(300, 30, negated(c), negated(d), w) - t).norm(), 0.0, 1e-9);
    // The error angle is the short way: never more than π.
    EXPECT_LE(orientationError(c, d).norm(), kPi + 1e-12);
  }
}

TEST(GaitPd, ZeroAtTarget) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Quaterniond q = randomRot(rng);
    EXPECT_NEAR(orientationPd(300, 30, q, q, Eigen::Vector3d::Zero()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(orientationPd(300, 30, q, negated(q), Eigen::Vector3d::Zero()).norm(), 0.0, 1e-12);
    const Eigen::Vector3d w = randomVec(rng, 2.0);
    EXPECT_NEAR(orientationPd(300, 30, q, q, w, w).norm(), 0.0, 1e-12);
  }
}

TEST(GaitPd, SmallKnownRotationSignAndMagnitude) {
  const double theta = 0.05, kp = 300.0;
  // From identity towards +θ about x: torque +kp·θ about +x.
  const Eigen::Quaterniond d(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitX()));
  const Eigen::Vector3d t = orientationPd(kp, 30.0, Eigen::Quaterniond::Identity(), d,
                                          Eigen::Vector3d::Zero());
  EXPECT_NEAR((t - Eigen::Vector3d(kp * theta, 0, 0)).norm(), 0.0, 1e-12);
  // Reverse roles: the torque reverses.
  const Eigen::Vector3d back = orientationPd(kp, 30.0, d, Eigen::Quaterniond::Identity(),
                                             Eigen::Vector3d::Zero());
  EXPECT_NEAR((back + t).norm(), 0.0, 1e-12);
  // Damping opposes the angular velocity.
  const Eigen::Vector3d damp = orientationPd(kp, 30.0, d, d, Eigen::Vector3d(0, 2, 0));
  EXPECT_NEAR((damp - Eigen::Vector3d(0, -60, 0)).norm(), 0.0, 1e-12);
}

TEST(GaitPd, ErrorIsExpressedInWorldAxes) {
  // Body yawed 90° about +y (its local +x now points along world −z); desired = the same body
  // pitched by θ about ITS local x. The world torque must be about world −z, not world +x
  // (the body-frame/world-frame mix-up of the original).
  const double theta = 0.1, kp = 100.0;
  const Eigen::Quaterniond current(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond desired = current * Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitX());
  const Eigen::Vector3d t = orientationPd(kp, 0.0, current, desired, Eigen::Vector3d::Zero());
  EXPECT_NEAR((t - Eigen::Vector3d(0, 0, -kp * theta)).norm(), 0.0, 1e-12);
  // Integrating the error as a world angular velocity for one unit of time reaches the target.
  const Eigen::Vector3d e = orientationError(current, desired);
  const Eigen::Quaterniond reached = Eigen::Quaterniond(Eigen::AngleAxisd(e.norm(), e.normalized())) * current;
  EXPECT_NEAR(reached.angularDistance(desired), 0.0, 1e-12);
}

TEST(GaitPd, LargeRotationsTakeTheShortWay) {
  // Desired = 190° about +z from identity: the short way is −170° about +z.
  const Eigen::Quaterniond d(Eigen::AngleAxisd(kPi * 190.0 / 180.0, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d e = orientationError(Eigen::Quaterniond::Identity(), d);
  EXPECT_NEAR((e - Eigen::Vector3d(0, 0, -kPi * 170.0 / 180.0)).norm(), 0.0, 1e-12);
  // Random: error magnitude equals the angular distance, and exp(error)·current = desired.
  std::mt19937 rng(23);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Quaterniond c = randomRot(rng), des = randomRot(rng);
    const Eigen::Vector3d err = orientationError(c, des);
    EXPECT_NEAR(err.norm(), c.angularDistance(des), 1e-9);
    if (err.norm() > 1e-9) {
      const Eigen::Quaterniond r = Eigen::Quaterniond(Eigen::AngleAxisd(err.norm(), err.normalized())) * c;
      EXPECT_NEAR(r.angularDistance(des), 0.0, 1e-9);
    }
  }
}

TEST(GaitPd, RotationVectorHandlesScaleAndZero) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0, 1, 1).normalized()));
  const Eigen::Quaterniond scaled(3.0 * q.w(), 3.0 * q.x(), 3.0 * q.y(), 3.0 * q.z());
  EXPECT_NEAR((rotationVector(scaled) - rotationVector(q)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((rotationVector(q) - 0.7 * Eigen::Vector3d(0, 1, 1).normalized()).norm(), 0.0, 1e-12);
  EXPECT_EQ(rotationVector(Eigen::Quaterniond(0, 0, 0, 0)).norm(), 0.0);
  const Eigen::Quaterniond tiny(Eigen::AngleAxisd(1e-14, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(rotationVector(tiny).x(), 1e-14, 1e-26);
}

TEST(GaitPd, JointPdActsOnRelativeOrientationAndVelocity) {
  std::mt19937 rng(31);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Quaterniond parent = randomRot(rng), rel = randomRot(rng);
    const Eigen::Vector3d w = randomVec(rng, 2.0);
    // Child at its target relative orientation, the pair spinning together: no torque.
    EXPECT_NEAR(jointPd(300, 30, parent, parent * rel, rel, w, w).norm(), 0.0, 1e-9);
    // Rotate the whole pair rigidly: the torque rotates with it (frame-consistent).
    const Eigen::Quaterniond child = randomRot(rng), spin = randomRot(rng);
    const Eigen::Vector3d wc = randomVec(rng, 2.0);
    const Eigen::Vector3d t = jointPd(300, 30, parent, child, rel, w, wc);
    const Eigen::Vector3d t2 = jointPd(300, 30, spin * parent, spin * child, rel, spin * w, spin * wc);
    EXPECT_NEAR((t2 - spin * t).norm(), 0.0, 1e-9);
  }
}

}  // namespace
}  // namespace gaitlab::gait
