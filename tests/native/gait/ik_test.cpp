// Two-link IK (thesis §3.1.4, law of cosines) checked by forward kinematics: the solved hip and
// knee angles, fed through an independent planar FK, must land on the target; in 3D the link
// lengths and the interior angle must be what the solver claims.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "gait/ik.h"

namespace gaitlab::gait {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool allFinite(const TwoLinkIk& r) {
  return r.knee.allFinite() && r.foot.allFinite() && r.thighDir.allFinite() &&
         r.shinDir.allFinite() && std::isfinite(r.kneeAngle) && std::isfinite(r.kneeFlexion);
}

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

TEST(GaitIk, PlanarForwardKinematicsOfSolvedAnglesReachesTarget) {
  // Sagittal plane (y up, z forward), knee bending forward (biped). Hip pitch a is measured from
  // straight down towards +z; with the knee forward the shin is rotated back by the flexion f.
  std::mt19937 rng(42);
  // Targets below the hip (within 80° of straight down): the knee side "towards +z" is then a
  // fixed rotational sense in the plane, the one this FK assumes.
  std::uniform_real_distribution<double> ul(0.3, 1.2), ua(-1.4, 1.4), uf(0.0, 1.0);
  int solved = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const double l1 = ul(rng), l2 = ul(rng);
    const double reachMin = std::fabs(l1 - l2), reachMax = l1 + l2;
    const double d = reachMin + (reachMax - reachMin) * (0.001 + 0.998 * uf(rng));
    const double dir = ua(rng);
    const Eigen::Vector3d hip(0.0, 1.7, 0.3);
    const Eigen::Vector3d target = hip + d * Eigen::Vector3d(0.0, -std::cos(dir), std::sin(dir));
    const TwoLinkIk r = solveTwoLinkIk(hip, target, l1, l2, Eigen::Vector3d::UnitZ());
    ASSERT_TRUE(r.reachable);
    const double a = std::atan2(r.thighDir.z(), -r.thighDir.y());
    const double f = r.kneeFlexion;
    const Eigen::Vector3d fk = hip + l1 * Eigen::Vector3d(0.0, -std::cos(a), std::sin(a)) +
                               l2 * Eigen::Vector3d(0.0, -std::cos(a - f), std::sin(a - f));
    EXPECT_NEAR((fk - target).norm(), 0.0, 1e-9) << "trial " << trial;
    EXPECT_NEAR(r.thighDir.x(), 0.0, 1e-12);  // stays in the sagittal plane
    ++solved;
  }
  EXPECT_EQ(solved, 500);
}

TEST(GaitIk, ThreeDimensionalSolutionsHaveTheRightShape) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ul(0.2, 1.5), uf(0.0, 1.0), uc(-3.0, 3.0);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const double l1 = ul(rng), l2 = ul(rng);
    const Eigen::Vector3d hip(uc(rng), uc(rng), uc(rng));
    Eigen::Vector3d dir(n(rng), n(rng), n(rng));
    dir.normalize();
    const double reachMin = std::fabs(l1 - l2), reachMax = l1 + l2;
    const double d = reachMin + (reachMax - reachMin) * (0.001 + 0.998 * uf(rng));
    const Eigen::Vector3d target = hip + d * dir;
    const Eigen::Vector3d bend(n(rng), n(rng), n(rng));
    const TwoLinkIk r = solveTwoLinkIk(hip, target, l1, l2, bend);
    ASSERT_TRUE(r.reachable);
    EXPECT_NEAR((r.foot - target).norm(), 0.0, 1e-9);
    EXPECT_NEAR((r.knee - hip).norm(), l1, 1e-9);
    EXPECT_NEAR((r.foot - r.knee).norm(), l2, 1e-9);
    EXPECT_NEAR((r.knee + l2 * r.shinDir - target).norm(), 0.0, 1e-9);
    EXPECT_NEAR(angleBetween(hip - r.knee, target - r.knee), r.kneeAngle, 1e-7);
    EXPECT_NEAR(r.kneeAngle + r.kneeFlexion, kPi, 1e-12);
    // The knee lies on the bend side of the hip→target line, in the plane of that line and bend.
    const Eigen::Vector3d bendPerp = bend - dir * bend.dot(dir);
    EXPECT_GE((r.knee - hip).dot(bendPerp), -1e-9);
    EXPECT_NEAR((r.knee - hip).dot(dir.cross(bendPerp).normalized()), 0.0, 1e-9);
  }
}

TEST(GaitIk, BendDirectionChoosesTheKneeSide) {
  const Eigen::Vector3d hip(0, 2, 0), target(0, 0.5, 0.2);
  const TwoLinkIk fwd = solveTwoLinkIk(hip, target, 0.9, 0.9, Eigen::Vector3d::UnitZ());
  const TwoLinkIk back = solveTwoLinkIk(hip, target, 0.9, 0.9, -Eigen::Vector3d::UnitZ());
  EXPECT_GT(fwd.knee.z(), 0.2);   // biped: knee points forward
  EXPECT_LT(back.knee.z(), 0.0);  // quadruped front leg: the other way
  EXPECT_NEAR(fwd.kneeAngle, back.kneeAngle, 1e-12);
}

TEST(GaitIk, OutOfReachIsStraightTowardsTarget) {
  const Eigen::Vector3d hip(1, 2, 3);
  const Eigen::Vector3d target = hip + Eigen::Vector3d(0.3, -4.0, 0.5);
  const TwoLinkIk r = solveTwoLinkIk(hip, target, 0.9, 0.9, Eigen::Vector3d::UnitZ());
  EXPECT_FALSE(r.reachable);
  const Eigen::Vector3d e = (target - hip).normalized();
  EXPECT_NEAR(r.kneeAngle, kPi, 1e-7);
  EXPECT_NEAR(r.kneeFlexion, 0.0, 1e-7);
  EXPECT_NEAR((r.thighDir - e).norm(), 0.0, 1e-7);
  EXPECT_NEAR((r.shinDir - e).norm(), 0.0, 1e-7);
  EXPECT_NEAR((r.foot - (hip + 1.8 * e)).norm(), 0.0, 1e-12);
  EXPECT_TRUE(allFinite(r));
}

TEST(GaitIk, TooCloseIsFullyFolded) {
  const Eigen::Vector3d hip(0, 2, 0);
  const Eigen::Vector3d target = hip + Eigen::Vector3d(0, -0.1, 0);
  const TwoLinkIk r = solveTwoLinkIk(hip, target, 0.9, 0.5, Eigen::Vector3d::UnitZ());
  EXPECT_FALSE(r.reachable);
  EXPECT_NEAR(r.kneeAngle, 0.0, 1e-7);
  EXPECT_NEAR((r.foot - (hip + Eigen::Vector3d(0, -0.4, 0))).norm(), 0.0, 1e-12);
  EXPECT_NEAR((r.knee - hip).norm(), 0.9, 1e-12);
  EXPECT_NEAR((r.foot - r.knee).norm(), 0.5, 1e-9);
  EXPECT_TRUE(allFinite(r));
}

TEST(GaitIk, DegenerateInputsStayFinite) {
  const Eigen::Vector3d hip(0.5, 1.0, -0.5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    Eigen::Vector3d target;
    double l1, l2;
    Eigen::Vector3d bend;
  };
  const Case cases[] = {
      {hip, 0.9, 0.9, Eigen::Vector3d::UnitZ()},          // target at the hip, equal links
      {hip, 0.9, 0.5, Eigen::Vector3d::UnitZ()},          // target at the hip, unequal links
      {hip, 0.9, 0.9, Eigen::Vector3d::Zero()},           // and no bend direction
      {hip, 0.9, 0.9, Eigen::Vector3d::UnitY()},          // bend along the default leg line
      {hip + Eigen::Vector3d(0, -1, 0), 0.9, 0.9, Eigen::Vector3d::UnitY()},  // bend ∥ line
      {hip + Eigen::Vector3d(0, -1, 0), 0.0, 0.0, Eigen::Vector3d::UnitZ()},  // no leg
      {hip + Eigen::Vector3d(0, -1, 0), 0.9, 0.0, Eigen::Vector3d::UnitZ()},  // no shin
      {hip + Eigen::Vector3d(0, -1, 0), -1.0, nan, Eigen::Vector3d::UnitZ()},
      {Eigen::Vector3d(nan, 0, 0), 0.9, 0.9, Eigen::Vector3d::UnitZ()},
      {Eigen::Vector3d(inf, 0, 0), 0.9, 0.9, Eigen::Vector3d(nan, 0, 0)},
      {hip + Eigen::Vector3d(0, -1e-300, 0), 0.9, 0.9, Eigen::Vector3d::UnitZ()},
  };
  for (const Case& c : cases) {
    const TwoLinkIk r = solveTwoLinkIk(hip, c.target, c.l1, c.l2, c.bend);
    EXPECT_TRUE(allFinite(r)) << c.target.transpose() << " " << c.l1 << " " << c.l2;
  }
  // Target at the hip with equal links: folded shut, foot back at the hip.
  const TwoLinkIk r = solveTwoLinkIk(hip, hip, 0.9, 0.9, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(r.kneeAngle, 0.0, 1e-7);
  EXPECT_NEAR((r.foot - hip).norm(), 0.0, 1e-12);
  EXPECT_NEAR((r.knee - hip).norm(), 0.9, 1e-12);
  EXPECT_GT(r.knee.z() - hip.z(), 0.0);  // towards the bend side
}

}  // namespace
}  // namespace gaitlab::gait

namespace gaitlab::gait {
namespace {

// A leg of three segments as a pantograph (solveLegIk): the tarsus parallel to the thigh, the
// chain hip → knee → hock → ankle reaching every reachable target, the knee on the bend side and
// the hock on the other; without a tarsus, the two-link solution to the last bit.
TEST(GaitIk, ALegOfThreeSegmentsReachesItsTargetAsAPantograph) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d hip(0.1, 0.9, 0.2), forward = Eigen::Vector3d::UnitZ();
  const double thigh = 0.3, shin = 0.36, tarsus = 0.18;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d target = hip + Eigen::Vector3d(0.3 * u(rng), -0.45 - 0.3 * std::abs(u(rng)), 0.3 * u(rng));
    const LegIk ik = solveLegIk(hip, target, thigh, shin, tarsus, forward);
    ASSERT_TRUE(ik.reachable) << i;
    const Eigen::Vector3d knee = hip + thigh * ik.thighDir;
    const Eigen::Vector3d hock = knee + shin * ik.shinDir;
    const Eigen::Vector3d ankle = hock + tarsus * ik.ankleLimb;
    EXPECT_LT((ankle - target).norm(), 1e-9) << i;
    EXPECT_LT((ik.ankleLimb - ik.thighDir).norm(), 1e-15) << "the tarsus is parallel to the thigh";
    // The knee lies ahead of the hip–ankle line (the bend side), the hock behind it.
    const Eigen::Vector3d line = (target - hip).normalized();
    const auto side = [&](const Eigen::Vector3d& p) {
      const Eigen::Vector3d off = (p - hip) - (p - hip).dot(line) * line;
      return off.dot(forward - forward.dot(line) * line);
    };
    EXPECT_GT(side(knee), 0.0) << i;
    EXPECT_LT(side(hock), 0.0) << i;
    // Knee and hock bend by the same angle, the knee's flexion.
    EXPECT_NEAR(angleBetween(ik.thighDir, ik.shinDir), ik.kneeFlexion, 1e-9);
    EXPECT_NEAR(angleBetween(ik.shinDir, ik.ankleLimb), ik.kneeFlexion, 1e-9);
  }
  const Eigen::Vector3d target = hip + Eigen::Vector3d(0.05, -0.6, 0.1);
  const LegIk two = solveLegIk(hip, target, 0.42, 0.42, 0.0, forward);
  const TwoLinkIk plain = solveTwoLinkIk(hip, target, 0.42, 0.42, forward);
  EXPECT_EQ(two.thighDir, plain.thighDir);
  EXPECT_EQ(two.ankleLimb, plain.shinDir);
  EXPECT_EQ(two.kneeFlexion, plain.kneeFlexion);
}

}  // namespace
}  // namespace gaitlab::gait
