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

namespace gaitlab::gait {
namespace {

// A serial chain of 1-DOF rotations: before DOF i the frame moves by `offset[i]` (in the current
// local frame), then rotates about `localAxis[i]` (local) by angle[i]. Multi-DOF joints are
// consecutive DOFs with zero offset between them.
struct SerialChain {
  Eigen::Vector3d basePos = Eigen::Vector3d::Zero();
  Eigen::Quaterniond baseRot = Eigen::Quaterniond::Identity();
  std::vector<Eigen::Vector3d> offset;
  std::vector<Eigen::Vector3d> localAxis;

  int size() const { return static_cast<int>(offset.size()); }

  // World transform of the frame after DOF `upTo` − 1 (upTo = 0: the base).
  Eigen::Isometry3d frameAfter(const std::vector<double>& angle, int upTo) const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translate(basePos);
    t.rotate(baseRot);
    for (int i = 0; i < upTo; ++i) {
      t.translate(offset[i]);
      t.rotate(Eigen::AngleAxisd(angle[i], localAxis[i]));
    }
    return t;
  }

  // A point fixed in the frame after DOF upTo − 1, in world coordinates.
  Eigen::Vector3d point(const std::vector<double>& angle, int upTo,
                        const Eigen::Vector3d& local) const {
    return frameAfter(angle, upTo) * local;
  }

  // The chain's DOFs in world axes for the gait module (axis and pivot of each DOF).
  DofChain dofChain(const std::vector<double>& angle) const {
    DofChain c;
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translate(basePos);
    t.rotate(baseRot);
    for (int i = 0; i < size(); ++i) {
      t.translate(offset[i]);
      c.push(t.linear() * localAxis[i], t.translation(), i);
      t.rotate(Eigen::AngleAxisd(angle[i], localAxis[i]));
    }
    return c;
  }
};

inline Eigen::Vector3d randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(n(rng), n(rng), n(rng));
  } while (v.norm() < 1e-3);
  return v.normalized();
}

inline Eigen::Vector3d randomVec(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Eigen::Vector3d(u(rng), u(rng), u(rng));
}

inline Eigen::Quaterniond randomRot(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q;
}

// A leg like the thesis's (REFERENCE.md): 3 leg-frame DOFs at the leg frame's centre, hip
// (1 DOF, offset to the hip corner), knee (1 DOF, down the thigh), ankle (2 DOF, down the shin).
// Lengths and axes are randomised a little so no test passes by symmetry.
inline SerialChain randomLeg(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SerialChain c;
  c.basePos = randomVec(rng, 5.0);
  c.baseRot = randomRot(rng);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  // Leg frame: three DOFs about x, y, z at its centre.
  c.offset = {zero, zero, zero};
  c.localAxis = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  // Hip at a lower corner of the pelvis, sagittal axis perturbed.
  c.offset.push_back(Eigen::Vector3d(0.4 + 0.1 * u(rng), -0.48 + 0.1 * u(rng), 0.1 * u(rng)));
  c.localAxis.push_back((Eigen::Vector3d::UnitX() + 0.2 * randomVec(rng, 1.0)).normalized());
  // Knee: down the thigh.
  c.offset.push_back(Eigen::Vector3d(0.05 * u(rng), -0.9 + 0.1 * u(rng), 0.05 * u(rng)));
  c.localAxis.push_back((Eigen::Vector3d::UnitX() + 0.2 * randomVec(rng, 1.0)).normalized());
  // Ankle: two DOFs at the end of the shin.
  c.offset.push_back(Eigen::Vector3d(0.05 * u(rng), -0.9 + 0.1 * u(rng), 0.05 * u(rng)));
  c.localAxis.push_back((Eigen::Vector3d::UnitX() + 0.2 * randomVec(rng, 1.0)).normalized());
  c.offset.push_back(zero);
  c.localAxis.push_back((Eigen::Vector3d::UnitZ() + 0.2 * randomVec(rng, 1.0)).normalized());
  return c;
}

inline std::vector<double> randomAngles(std::mt19937& rng, int n, double range = 1.2) {
  std::uniform_real_distribution<double> u(-range, range);
  std::vector<double> a(n);
  for (double& x : a) x = u(rng);
  return a;
}

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

// The biped leg of REFERENCE.md: leg frame 10 kg (moved by the 3 leg-frame DOFs), upper leg
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
  // Four links evenly spaced between leg frames 2 m apart (REFERENCE.md quadruped): the link
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
