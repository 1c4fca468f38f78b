// Gravity compensation (thesis §3.1.5) against independent mathematics: the torques that hold a
// chain still against gravity are the gradient of its potential energy, τ_i = +∂V/∂θ_i with
// V = Σ m_k g h_k, taken here by central finite differences of forward kinematics.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "gait/gravity.h"

#include "random_chain.h"

namespace gaitlab::gait {
namespace {
constexpr double kG = 9.81;

struct Body {
  double mass;
  int frame;  // fixed in the frame after DOF frame − 1 (so moved by DOFs [0, frame))
  Eigen::Vector3d localCom;
};

double potential(const SerialChain& c, const std::vector<double>& angle,
                 const std::vector<Body>& bodies, const std::vector<double>& weight) {
  double v = 0.0;
  for (size_t k = 0; k < bodies.size(); ++k) {
    v += weight[k] * bodies[k].mass * kG * c.point(angle, bodies[k].frame, bodies[k].localCom).y();
  }
  return v;
}

// The original implementation's biped leg (docs/original-implementation.md): leg frame 10 kg (moved by the 3 leg-frame DOFs), upper leg
// 5 kg (after the hip), lower leg 4 kg (after the knee), foot 1 kg (after both ankle DOFs).
std::vector<Body> legBodies() {
  return {{10.0, 3, Eigen::Vector3d(0.0, 0.0, 0.0)},
          {5.0, 4, Eigen::Vector3d(0.0, -0.45, 0.0)},
          {4.0, 5, Eigen::Vector3d(0.0, -0.45, 0.0)},
          {1.0, 7, Eigen::Vector3d(0.0, -0.05, 0.1)}};
}

TEST(GaitGravity, CompensationIsTheGradientOfPotentialEnergy) {
  std::mt19937 rng(2024);
  const Eigen::Vector3d gravity(0.0, -kG, 0.0);
  for (int trial = 0; trial < 50; ++trial) {
    const SerialChain leg = randomLeg(rng);
    const std::vector<double> angle = randomAngles(rng, leg.size());
    const std::vector<Body> bodies = legBodies();
    std::uniform_real_distribution<double> uw(0.2, 1.0);
    std::vector<double> weight(bodies.size(), 1.0);
    if (trial % 2) {
      for (double& w : weight) w = uw(rng);  // partial shares, as the spine uses
    }

    SegmentLoad loads[4];
    for (size_t k = 0; k < bodies.size(); ++k) {
      loads[k].mass = bodies[k].mass;
      loads[k].com = leg.point(angle, bodies[k].frame, bodies[k].localCom);
      loads[k].dofCount = bodies[k].frame;
      loads[k].weight = weight[k];
    }
    double tau[DofChain::kMaxDofs];
    gravityCompensationTorques(leg.dofChain(angle), loads, 4, gravity, tau);

    const double h = 1e-6;
    for (int i = 0; i < leg.size(); ++i) {
      std::vector<double> a = angle, b = angle;
      a[i] += h;
      b[i] -= h;
      const double dV = (potential(leg, a, bodies, weight) - potential(leg, b, bodies, weight)) /
                        (2.0 * h);
      EXPECT_NEAR(tau[i], dV, 1e-6 * (1.0 + std::fabs(dV))) << "trial " << trial << " dof " << i;
    }
  }
}

TEST(GaitGravity, HoldingAHorizontalLinkTakesMgl) {
  // A 2 kg link with its COM 0.5 m out along +x from a hinge about +z: the hinge must exert
  // +m g l about +z (counter-clockwise, lifting the link).
  DofChain chain;
  chain.push(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero(), 0);
  SegmentLoad link;
  link.mass = 2.0;
  link.com = Eigen::Vector3d(0.5, 0.0, 0.0);
  link.dofCount = 1;
  double tau[1];
  gravityCompensationTorques(chain, &link, 1, Eigen::Vector3d(0, -kG, 0), tau);
  EXPECT_NEAR(tau[0], 2.0 * kG * 0.5, 1e-12);
}

TEST(GaitGravity, JointAccumulationMatchesPerDofTorques) {
  std::mt19937 rng(3);
  const SerialChain leg = randomLeg(rng);
  const std::vector<double> angle = randomAngles(rng, leg.size());
  const DofChain chain = leg.dofChain(angle);  // joint id = DOF index
  const std::vector<Body> bodies = legBodies();
  SegmentLoad loads[4];
  for (size_t k = 0; k < bodies.size(); ++k) {
    loads[k].mass = bodies[k].mass;
    loads[k].com = leg.point(angle, bodies[k].frame, bodies[k].localCom);
    loads[k].dofCount = bodies[k].frame;
  }
  const Eigen::Vector3d gravity(0, -kG, 0);
  double tau[DofChain::kMaxDofs];
  gravityCompensationTorques(chain, loads, 4, gravity, tau);
  Eigen::Vector3d joints[DofChain::kMaxDofs];
  for (auto& j : joints) j.setZero();
  accumulateGravityCompensation(chain, loads, 4, gravity, joints, chain.count);
  for (int i = 0; i < chain.count; ++i) {
    EXPECT_NEAR((joints[i] - chain.dofs[i].axis * tau[i]).norm(), 0.0, 1e-9);
  }
}

TEST(GaitGravity, SpineWeightsSumToOne) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d back = randomVec(rng, 3.0), front = randomVec(rng, 3.0);
    const Eigen::Vector3d link = randomVec(rng, 3.0);
    const SpineWeights w = spineGravityWeights(back, front, link);
    EXPECT_NEAR(w.back + w.front, 1.0, 1e-15);
    EXPECT_GE(w.back, 0.0);
    EXPECT_GE(w.front, 0.0);
  }
  // Four links evenly spaced between leg frames 2 m apart (the original implementation's quadruped): the link
  // nearest the back leg frame is held mostly from the back, and the weights mirror.
  const Eigen::Vector3d back(0, 1, -1), front(0, 1, 1);
  double prevBack = 2.0;
  for (int j = 0; j < 4; ++j) {
    const Eigen::Vector3d c(0, 1, -1 + 2.0 * (j + 1) / 5.0);
    const SpineWeights w = spineGravityWeights(back, front, c);
    EXPECT_NEAR(w.back, 1.0 - (j + 1) / 5.0, 1e-12);
    EXPECT_NEAR(w.back + w.front, 1.0, 1e-15);
    EXPECT_LT(w.back, prevBack);
    prevBack = w.back;
  }
  const SpineWeights mid = spineGravityWeights(1.0, 1.0);
  EXPECT_DOUBLE_EQ(mid.back, 0.5);
  const SpineWeights atBack = spineGravityWeights(0.0, 2.0);
  EXPECT_DOUBLE_EQ(atBack.back, 1.0);
  EXPECT_DOUBLE_EQ(atBack.front, 0.0);
  const SpineWeights degenerate = spineGravityWeights(0.0, 0.0);
  EXPECT_DOUBLE_EQ(degenerate.back + degenerate.front, 1.0);
}

TEST(GaitGravity, SpineLinkIsCompensatedExactlyOnceThroughBothChains) {
  // A spine link held from both leg frames as bases (one hinge about x at each): each chain
  // carries its weight's share of m g, and the shares add up to the whole weight.
  const Eigen::Vector3d back(0, 1, -1), front(0, 1, 1), com(0.1, 1.05, -0.3);
  const SpineWeights w = spineGravityWeights(back, front, com);
  DofChain fromBack, fromFront;
  fromBack.push(Eigen::Vector3d::UnitX(), back, 0);
  fromFront.push(Eigen::Vector3d::UnitX(), front, 0, true);
  SegmentLoad l;
  l.mass = 1.0;
  l.com = com;
  l.dofCount = 1;
  const Eigen::Vector3d g(0, -kG, 0);
  l.weight = w.back;
  double tb[1], tf[1];
  gravityCompensationTorques(fromBack, &l, 1, g, tb);
  l.weight = w.front;
  gravityCompensationTorques(fromFront, &l, 1, g, tf);
  // Hinges about x at the two bases: moment arms along z are (com − base).z.
  EXPECT_NEAR(tb[0], -(com.z() - back.z()) * w.back * kG, 1e-12);
  EXPECT_NEAR(tf[0], -(com.z() - front.z()) * w.front * kG, 1e-12);
  EXPECT_NEAR(w.back + w.front, 1.0, 1e-15);
}

}  // namespace
}  // namespace gaitlab::gait
