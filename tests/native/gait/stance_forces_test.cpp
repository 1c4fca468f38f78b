// Ground forces for the whole-body stance (gait/stance_forces.h), checked against plain statics:
// the forces' resultant and their moment about the centre of mass, summed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "gait/stance_forces.h"

using Eigen::Vector3d;
using gaitlab::gait::distributeStanceForces;
using gaitlab::gait::StanceForceSettings;

namespace {

struct Wrench {
  Vector3d force = Vector3d::Zero(), torque = Vector3d::Zero();
};

Wrench resultant(const Vector3d& com, const Vector3d* points, const Vector3d* forces, int n) {
  Wrench w;
  for (int i = 0; i < n; ++i) {
    w.force += forces[i];
    w.torque += (points[i] - com).cross(forces[i]);
  }
  return w;
}

// A dog-sized stance: feet 0.8 m apart front to back, 0.18 m side to side, the centre of mass
// 0.45 m up and a little ahead of the middle.
const Vector3d kCom(0.0, 0.45, 0.03);
const Vector3d kFeet[4] = {{0.09, 0, 0.4}, {-0.09, 0, 0.4}, {0.09, 0, -0.4}, {-0.09, 0, -0.4}};

}  // namespace

TEST(StanceForces, FourFeetGiveAnyModestWrenchExactly) {
  StanceForceSettings settings;
  settings.regularisation = 1e-9;
  const Vector3d force(8, 330, -15), torque(6, -3, 4);
  Vector3d out[4];
  ASSERT_TRUE(distributeStanceForces(kCom, force, torque, kFeet, 4, settings, out));
  const Wrench w = resultant(kCom, kFeet, out, 4);
  EXPECT_LT((w.force - force).norm(), 1e-3);
  EXPECT_LT((w.torque - torque).norm(), 1e-3);
  for (const Vector3d& f : out) {
    EXPECT_GT(f.y(), 0) << "a foot pulls on the ground";
    EXPECT_LE(std::hypot(f.x(), f.z()), settings.friction * f.y() + 1e-9);
  }
}

TEST(StanceForces, WeightAloneIsSharedByTheLevers) {
  // Only the weight, centre of mass 3 cm ahead of the middle: the front feet carry more, by the
  // lever rule (0.43 / 0.8 of it), left and right alike.
  Vector3d out[4];
  ASSERT_TRUE(distributeStanceForces(kCom, Vector3d(0, 320, 0), Vector3d::Zero(), kFeet, 4,
                                     StanceForceSettings{}, out));
  EXPECT_NEAR(out[0].y() + out[1].y(), 320 * 0.43 / 0.8, 0.5);
  EXPECT_NEAR(out[2].y() + out[3].y(), 320 * 0.37 / 0.8, 0.5);
  EXPECT_NEAR(out[0].y(), out[1].y(), 1e-6);
  for (const Vector3d& f : out) EXPECT_NEAR(std::hypot(f.x(), f.z()), 0, 1e-3);
}

TEST(StanceForces, ADiagonalPairGivesWhatTwoPointFeetCan) {
  // A trot's diagonal: front left and back right. Any wrench two point feet can exert is given
  // exactly; point feet on a line exert no moment about that line, so whatever is asked, the
  // forces found have none about it (the rest is foot placement's job).
  const Vector3d pair[2] = {kFeet[0], kFeet[3]};
  StanceForceSettings settings;
  settings.regularisation = 1e-9;
  const Vector3d made[2] = {Vector3d(3, 150, 8), Vector3d(-2, 170, 4)};
  const Wrench reachable = resultant(kCom, pair, made, 2);
  Vector3d out[2];
  ASSERT_TRUE(distributeStanceForces(kCom, reachable.force, reachable.torque, pair, 2, settings, out));
  const Wrench w = resultant(kCom, pair, out, 2);
  EXPECT_LT((w.force - reachable.force).norm(), 1e-3);
  EXPECT_LT((w.torque - reachable.torque).norm(), 1e-3);

  const Vector3d line = (pair[0] - pair[1]).normalized();
  ASSERT_TRUE(distributeStanceForces(kCom, Vector3d(0, 320, 10), Vector3d(5, 2, 1) + 20 * line, pair,
                                     2, settings, out));
  const Wrench aboutFoot = resultant(pair[1], pair, out, 2);
  EXPECT_NEAR(aboutFoot.torque.dot(line), 0, 1e-6) << "no moment about the feet's own line";
}

TEST(StanceForces, FeetPushButNeverPullAndStayInsideTheFrictionCone) {
  // Asked to lift the body's left side hard and shove it sideways: the left feet would have to
  // pull and the sideways force exceeds friction. Every force stays a push within the cone.
  StanceForceSettings settings;
  Vector3d out[4];
  ASSERT_TRUE(distributeStanceForces(kCom, Vector3d(400, 100, 0), Vector3d(0, 0, -200), kFeet, 4,
                                     settings, out));
  for (const Vector3d& f : out) {
    EXPECT_GE(f.y(), settings.minNormal - 1e-12);
    EXPECT_LE(std::hypot(f.x(), f.z()), settings.friction * f.y() + 1e-9);
  }
}

TEST(StanceForces, RefusesACountOutOfRange) {
  Vector3d out[1] = {Vector3d(7, 7, 7)};
  EXPECT_FALSE(distributeStanceForces(kCom, Vector3d::UnitY(), Vector3d::Zero(), kFeet, 0,
                                      StanceForceSettings{}, out));
  EXPECT_FALSE(distributeStanceForces(kCom, Vector3d::UnitY(), Vector3d::Zero(), kFeet, gaitlab::gait::kMaxStanceFeet + 1,
                                      StanceForceSettings{}, out));
  EXPECT_EQ(out[0], Vector3d(7, 7, 7));
}
