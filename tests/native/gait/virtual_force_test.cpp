// Virtual forces (thesis §3.1.2, eq. 3.1–3.3) against independent mathematics: the Jacobian
// transpose τ_i = (∂p/∂α_i)·F, with ∂p/∂α_i taken by central finite differences of a
// forward-kinematics function written here with Eigen transforms.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "gait/virtual_force.h"

#include "random_chain.h"

namespace gaitlab::gait {
namespace {
// τ_i = (∂p/∂θ_i)·F by central differences; p is a point fixed in the last frame.
std::vector<double> numericTorques(const SerialChain& c, const std::vector<double>& angle,
                                   const Eigen::Vector3d& endLocal, const Eigen::Vector3d& force) {
  const double h = 1e-6;
  std::vector<double> tau(angle.size());
  for (size_t i = 0; i < angle.size(); ++i) {
    std::vector<double> a = angle, b = angle;
    a[i] += h;
    b[i] -= h;
    const Eigen::Vector3d dp =
        (c.point(a, c.size(), endLocal) - c.point(b, c.size(), endLocal)) / (2.0 * h);
    tau[i] = dp.dot(force);
  }
  return tau;
}

TEST(GaitVirtualForce, JacobianTransposeMatchesFiniteDifferencesOnRandomLegs) {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 50; ++trial) {
    const SerialChain leg = randomLeg(rng);
    ASSERT_EQ(leg.size(), 7);  // 3 leg-frame DOFs + hip + knee + 2 ankle (docs/original-implementation.md)
    const std::vector<double> angle = randomAngles(rng, leg.size());
    const Eigen::Vector3d toeLocal(0.02, -0.05, 0.3);  // a point on the foot
    const Eigen::Vector3d p = leg.point(angle, leg.size(), toeLocal);
    const Eigen::Vector3d force = randomVec(rng, 300.0);

    const DofChain chain = leg.dofChain(angle);
    double tau[DofChain::kMaxDofs];
    jacobianTransposeTorques(chain, p, force, tau);
    const std::vector<double> expected = numericTorques(leg, angle, toeLocal, force);
    for (int i = 0; i < leg.size(); ++i) {
      EXPECT_NEAR(tau[i], expected[i], 1e-6 * (1.0 + std::fabs(expected[i])))
          << "trial " << trial << " dof " << i;
    }
  }
}

TEST(GaitVirtualForce, PartialChainOnlyTouchesItsDofs) {
  std::mt19937 rng(7);
  const SerialChain leg = randomLeg(rng);
  const std::vector<double> angle = randomAngles(rng, leg.size());
  // A point fixed after the knee (the shin's centre): only the first 5 DOFs move it.
  const Eigen::Vector3d shinLocal(0.0, -0.45, 0.0);
  const Eigen::Vector3d p = leg.point(angle, 5, shinLocal);
  const Eigen::Vector3d force = randomVec(rng, 100.0);
  const DofChain chain = leg.dofChain(angle);

  double tau[DofChain::kMaxDofs];
  for (double& t : tau) t = 12345.0;  // sentinel: must survive past dofCount
  jacobianTransposeTorques(chain, p, force, tau, 5);
  const double h = 1e-6;
  for (int i = 0; i < 5; ++i) {
    std::vector<double> a = angle, b = angle;
    a[i] += h;
    b[i] -= h;
    const double expected =
        ((leg.point(a, 5, shinLocal) - leg.point(b, 5, shinLocal)) / (2.0 * h)).dot(force);
    EXPECT_NEAR(tau[i], expected, 1e-6 * (1.0 + std::fabs(expected)));
  }
  EXPECT_EQ(tau[5], 12345.0);
  EXPECT_EQ(tau[6], 12345.0);
}

TEST(GaitVirtualForce, VirtualWorkBalances) {
  // Power balance of the Jacobian transpose: Σ τ_i θ̇_i = F · ṗ for any joint rates.
  std::mt19937 rng(99);
  for (int trial = 0; trial < 20; ++trial) {
    const SerialChain leg = randomLeg(rng);
    const std::vector<double> angle = randomAngles(rng, leg.size());
    const std::vector<double> rate = randomAngles(rng, leg.size(), 3.0);
    const Eigen::Vector3d endLocal(0.0, -0.05, 0.2);
    const Eigen::Vector3d force = randomVec(rng, 50.0);
    const double h = 1e-6;
    std::vector<double> a = angle, b = angle;
    for (int i = 0; i < leg.size(); ++i) {
      a[i] += h * rate[i];
      b[i] -= h * rate[i];
    }
    const Eigen::Vector3d pdot =
        (leg.point(a, leg.size(), endLocal) - leg.point(b, leg.size(), endLocal)) / (2.0 * h);
    double tau[DofChain::kMaxDofs];
    jacobianTransposeTorques(leg.dofChain(angle), leg.point(angle, leg.size(), endLocal), force,
                             tau);
    double power = 0.0;
    for (int i = 0; i < leg.size(); ++i) power += tau[i] * rate[i];
    EXPECT_NEAR(power, force.dot(pdot), 1e-6 * (1.0 + std::fabs(power)));
  }
}

TEST(GaitVirtualForce, TorqueVectorsAreAxisTimesScalar) {
  std::mt19937 rng(5);
  const SerialChain leg = randomLeg(rng);
  const std::vector<double> angle = randomAngles(rng, leg.size());
  const DofChain chain = leg.dofChain(angle);
  const Eigen::Vector3d p = randomVec(rng, 3.0), force = randomVec(rng, 10.0);
  double tau[DofChain::kMaxDofs];
  Eigen::Vector3d vec[DofChain::kMaxDofs];
  jacobianTransposeTorques(chain, p, force, tau);
  jointTorqueVectors(chain, p, force, vec);
  for (int i = 0; i < chain.count; ++i) {
    EXPECT_NEAR((vec[i] - chain.dofs[i].axis * tau[i]).norm(), 0.0, 1e-12);
  }
}

TEST(GaitVirtualForce, BallJointAccumulatesTheFullMoment) {
  // Three orthonormal DOFs at one pivot, all mapped to one joint: their torque vectors sum to
  // the whole moment (p − b) × F. Marked reversed, the joint's child gets the opposite.
  std::mt19937 rng(11);
  const Eigen::Quaterniond r = randomRot(rng);
  const Eigen::Vector3d b = randomVec(rng, 2.0), p = randomVec(rng, 2.0);
  const Eigen::Vector3d force = randomVec(rng, 20.0);
  for (bool reversed : {false, true}) {
    DofChain chain;
    for (int k = 0; k < 3; ++k) {
      ASSERT_TRUE(chain.push(r * Eigen::Vector3d::Unit(k), b, 2, reversed));
    }
    Eigen::Vector3d joints[4];
    for (auto& j : joints) j.setZero();
    accumulateJointTorques(chain, p, force, joints, 4);
    const Eigen::Vector3d moment = (p - b).cross(force);
    EXPECT_NEAR((joints[2] - (reversed ? -moment : moment)).norm(), 0.0, 1e-10);
    EXPECT_EQ(joints[0].norm() + joints[1].norm() + joints[3].norm(), 0.0);
  }
}

TEST(GaitVirtualForce, AccumulateSkipsNonJointsAndOutOfRange) {
  DofChain chain;
  chain.push(Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero(), -1);  // free base row
  chain.push(Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero(), 7);   // beyond jointCount
  chain.push(Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero(), 1);
  Eigen::Vector3d joints[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  accumulateJointTorques(chain, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, -10, 0), joints, 2);
  // α × (p − b) = x × z = −y; · (0, −10, 0) = 10.
  EXPECT_NEAR((joints[1] - Eigen::Vector3d(10, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(joints[0].norm(), 0.0);
}

TEST(GaitVirtualForce, ChainCapacityIsFixed) {
  DofChain chain;
  for (int i = 0; i < DofChain::kMaxDofs; ++i) {
    EXPECT_TRUE(chain.push(Eigen::Vector3d::UnitY(), Eigen::Vector3d::Zero()));
  }
  EXPECT_FALSE(chain.push(Eigen::Vector3d::UnitY(), Eigen::Vector3d::Zero()));
  EXPECT_EQ(chain.count, DofChain::kMaxDofs);
}

}  // namespace
}  // namespace gaitlab::gait
