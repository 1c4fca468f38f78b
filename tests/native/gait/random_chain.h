// A random serial chain of hinges and its forward kinematics, written independently of
// gait/virtual_force.h and gait/gravity.h so that both can be checked against finite differences.
#pragma once
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "gait/virtual_force.h"

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

// A leg like the original implementation's (docs/original-implementation.md): 3 leg-frame DOFs at the leg frame's centre, hip
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

}  // namespace
}  // namespace gaitlab::gait
