// Foot placement (thesis §3.1.6) and the stance forces F_v, F_D (eq. 3.6–3.8), checked against
// formulas computed here with Eigen rotations, and the motion graph and heading helpers they use.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "gait/foot_placement.h"
#include "gait/graph.h"
#include "gait/heading.h"

namespace gaitlab::gait {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix3d yawMatrix(double yaw) {
  return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

TEST(GaitGraph, KnotsInterpolationAndClamp) {
  const MotionGraph g = MotionGraph::of(1.0, 4.0, -2.0, 0.5);
  EXPECT_DOUBLE_EQ(g.eval(0.0), 1.0);
  EXPECT_NEAR(g.eval(1.0 / 3.0), 4.0, 1e-12);
  EXPECT_NEAR(g.eval(2.0 / 3.0), -2.0, 1e-12);
  EXPECT_DOUBLE_EQ(g.eval(1.0), 0.5);
  EXPECT_NEAR(g.eval(1.0 / 6.0), 2.5, 1e-12);
  EXPECT_NEAR(g.eval(0.5), 1.0, 1e-12);
  EXPECT_NEAR(g.eval(5.0 / 6.0), -0.75, 1e-12);
  EXPECT_DOUBLE_EQ(g.eval(-0.5), 1.0);
  EXPECT_DOUBLE_EQ(g.eval(7.0), 0.5);
  EXPECT_DOUBLE_EQ(g.eval(std::numeric_limits<double>::quiet_NaN()), 1.0);
  EXPECT_NEAR(g.eval(std::nextafter(1.0, 0.0)), 0.5, 1e-12);  // just below the last knot
  // Continuous at the interior knots.
  for (double k : {1.0 / 3.0, 2.0 / 3.0}) {
    EXPECT_NEAR(g.eval(k - 1e-12), g.eval(k + 1e-12), 1e-9);
  }
  EXPECT_DOUBLE_EQ(MotionGraph::constant(3.0).eval(0.37), 3.0);
}

TEST(GaitHeading, YawOfYawPitchRollIsTheYaw) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> uy(-kPi, kPi), up(-1.4, 1.4), ur(-kPi, kPi);
  for (int trial = 0; trial < 200; ++trial) {
    const double yaw = uy(rng);
    const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(up(rng), Eigen::Vector3d::UnitX()) *
                                 Eigen::AngleAxisd(ur(rng), Eigen::Vector3d::UnitZ());
    EXPECT_NEAR(wrapAngle(headingOf(q) - yaw), 0.0, 1e-9);
    EXPECT_NEAR(wrapAngle(headingOf(yawOnly(q)) - yaw), 0.0, 1e-9);
    EXPECT_NEAR(yawOnly(q).angularDistance(Eigen::Quaterniond(
                    Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()))),
                0.0, 1e-9);
  }
  // Forward axis vertical: still finite.
  const Eigen::Quaterniond up90(Eigen::AngleAxisd(-kPi / 2, Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(std::isfinite(headingOf(up90)));
}

TEST(GaitHeading, FrameConversions) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int trial = 0; trial < 100; ++trial) {
    const double yaw = u(rng);
    const Eigen::Vector3d v(u(rng), u(rng), u(rng)), o(u(rng), u(rng), u(rng));
    EXPECT_NEAR((headingToWorld(yaw, v) - yawMatrix(yaw) * v).norm(), 0.0, 1e-9);
    EXPECT_NEAR((worldToHeading(yaw, headingToWorld(yaw, v)) - v).norm(), 0.0, 1e-9);
    EXPECT_NEAR((worldPointToHeading(yaw, o, headingPointToWorld(yaw, o, v)) - v).norm(), 0.0,
                1e-9);
    EXPECT_NEAR((headingForward(yaw) - headingToWorld(yaw, Eigen::Vector3d::UnitZ())).norm(), 0.0,
                1e-12);
    EXPECT_NEAR((headingLeft(yaw) - headingToWorld(yaw, Eigen::Vector3d::UnitX())).norm(), 0.0,
                1e-12);
    const double w = wrapAngle(yaw);
    EXPECT_GT(w, -kPi);
    EXPECT_LE(w, kPi);
    EXPECT_NEAR(std::remainder(w - yaw, 2 * kPi), 0.0, 1e-9);
  }
  EXPECT_NEAR((headingForward(0) - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
  // Left of a character facing +z with y up is +x (right-handed: forward × up = right = −x).
  EXPECT_NEAR((headingLeft(0) - Eigen::Vector3d::UnitX()).norm(), 0.0, 1e-15);
}

TEST(GaitFootPlacement, DesiredVelocityRampIsBoundedAndReachesTheGoal) {
  const double maxAccel = 1.5, dt = 1.0 / 120.0;
  const Eigen::Vector3d goal(0.8, 0.0, 2.0);
  Eigen::Vector3d vd(0.0, 0.0, -0.5);
  bool reached = false;
  int steps = 0;
  for (; steps < 1000; ++steps) {
    const Eigen::Vector3d next = rampDesiredVelocity(vd, goal, maxAccel, dt);
    EXPECT_LE((next - vd).norm(), maxAccel * dt * (1.0 + 1e-12));
    // Straight towards the goal, never past it.
    EXPECT_LE((goal - next).norm(), (goal - vd).norm());
    vd = next;
    if (vd == goal) {
      reached = true;
      break;
    }
  }
  ASSERT_TRUE(reached);
  const int expected = static_cast<int>(
      std::ceil((goal - Eigen::Vector3d(0, 0, -0.5)).norm() / (maxAccel * dt)));
  EXPECT_EQ(steps + 1, expected);
  EXPECT_EQ(rampDesiredVelocity(goal, goal, maxAccel, dt), goal);  // stays
  // Decelerating works the same way.
  const Eigen::Vector3d slower = rampDesiredVelocity(goal, Eigen::Vector3d::Zero(), maxAccel, dt);
  EXPECT_NEAR((goal - slower).norm(), maxAccel * dt, 1e-12);
}

TEST(GaitFootPlacement, PlacementTargetFormula) {
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int trial = 0; trial < 100; ++trial) {
    const double yaw = u(rng) * 2.0, s = 0.1 + std::fabs(u(rng)) * 0.2, ground = u(rng);
    const Eigen::Vector3d lf(u(rng), 1.5 + u(rng), u(rng));
    const Eigen::Vector3d nominal = nominalFootOffset(trial % 2 ? 1.0 : -1.0, 0.3, 0.1);
    const Eigen::Vector3d v(u(rng), u(rng), u(rng)), vd(u(rng), 0.0, u(rng));
    const Eigen::Vector3d p1 = footPlacementTarget(lf, yaw, nominal, v, vd, s, ground);
    // P1 = P_legframe + (v − v_d)·s with P_legframe = leg frame + nominal (heading frame),
    // everything horizontal, on the ground.
    Eigen::Vector3d offset = nominal + (v - vd) * s;
    offset.y() = 0.0;
    Eigen::Vector3d expected = lf + yawMatrix(yaw) * offset;
    expected.y() = ground;
    EXPECT_NEAR((p1 - expected).norm(), 0.0, 1e-12);
  }
  // Going faster than desired places the foot further ahead (brakes).
  const Eigen::Vector3d a =
      footPlacementTarget(Eigen::Vector3d(0, 1, 0), 0.0, nominalFootOffset(1, 0.3, 0.0),
                          Eigen::Vector3d(0, 0, 1.5), Eigen::Vector3d(0, 0, 1.0), 0.2, 0.0);
  EXPECT_NEAR((a - Eigen::Vector3d(0.3, 0.0, 0.1)).norm(), 0.0, 1e-12);
}

TEST(GaitFootPlacement, SwingTrajectoryRunsFromP0ToP1AlongTheGraphs) {
  const MotionGraph tSw = MotionGraph::of(0.0, 0.15, 0.7, 1.0);   // ease in
  const MotionGraph hSw = MotionGraph::of(0.0, 0.25, 0.2, 0.0);   // step height
  const Eigen::Vector3d p0(0.3, 0.05, -0.4), p1(0.35, 0.15, 0.6);  // onto a step up
  EXPECT_NEAR((swingFootTarget(p0, p1, 0.0, tSw, hSw) - p0).norm(), 0.0, 1e-15);
  EXPECT_NEAR((swingFootTarget(p0, p1, 1.0, tSw, hSw) - p1).norm(), 0.0, 1e-15);
  double peak = -1.0, peakPhi = -1.0;
  for (int i = 0; i <= 300; ++i) {
    const double phi = i / 300.0;
    const Eigen::Vector3d p = swingFootTarget(p0, p1, phi, tSw, hSw);
    const double f = tSw.eval(phi);
    // Horizontal: the fraction t_sw(ϕ) of the way.
    EXPECT_NEAR(p.x(), p0.x() + f * (p1.x() - p0.x()), 1e-12);
    EXPECT_NEAR(p.z(), p0.z() + f * (p1.z() - p0.z()), 1e-12);
    // Vertical: above the ground line by h_sw(ϕ).
    const double height = p.y() - (p0.y() + f * (p1.y() - p0.y()));
    EXPECT_NEAR(height, hSw.eval(phi), 1e-12);
    if (height > peak) {
      peak = height;
      peakPhi = phi;
    }
  }
  EXPECT_NEAR(peak, 0.25, 1e-12);
  EXPECT_NEAR(peakPhi, 1.0 / 3.0, 1.0 / 300.0);
  // Late strike: the held end point sinks by the offset.
  const Eigen::Vector3d late = swingFootTarget(p0, p1, 1.0, tSw, hSw, 0.03);
  EXPECT_NEAR((late - (p1 - Eigen::Vector3d(0, 0.03, 0))).norm(), 0.0, 1e-15);
  // Re-evaluated with a new P1 each step, the target moves with it (not frozen at lift-off).
  const Eigen::Vector3d moved = swingFootTarget(p0, p1 + Eigen::Vector3d(0, 0, 0.2), 0.5, tSw, hSw);
  EXPECT_GT(moved.z(), swingFootTarget(p0, p1, 0.5, tSw, hSw).z());
}

TEST(GaitFootPlacement, StanceForces) {
  // Eq. 3.6, horizontal.
  const Eigen::Vector3d fv =
      velocityForce(100.0, Eigen::Vector3d(0, 0, 1.0), Eigen::Vector3d(0.2, -0.5, 0.6));
  EXPECT_NEAR((fv - Eigen::Vector3d(-20.0, 0.0, 40.0)).norm(), 0.0, 1e-12);
  // Eq. 3.7: forward-signed progress of the foot relative to the leg frame.
  const double yaw = 0.7;
  const Eigen::Vector3d lf(1.0, 1.8, 2.0);
  const Eigen::Vector3d ahead = lf + yawMatrix(yaw) * Eigen::Vector3d(0.3, -1.7, 0.4);
  const Eigen::Vector3d behind = lf + yawMatrix(yaw) * Eigen::Vector3d(-0.3, -1.8, -0.25);
  EXPECT_NEAR(footProgress(lf, ahead, yaw), 0.4, 1e-12);
  EXPECT_NEAR(footProgress(lf, behind, yaw), -0.25, 1e-12);
  // Eq. 3.8: vertical c0 + c1·D, horizontal c2 + c3·D along the heading's forward axis.
  PhaseForceCoefficients c;
  c.c0 = 10;
  c.c1 = -4;
  c.c2 = 3;
  c.c3 = 20;
  const Eigen::Vector3d fd = phaseForce(c, 0.4, yaw);
  const Eigen::Vector3d expected =
      yawMatrix(yaw) * Eigen::Vector3d(0, 10 - 4 * 0.4, 3 + 20 * 0.4);
  EXPECT_NEAR((fd - expected).norm(), 0.0, 1e-12);
  // F_sw: PD towards the target with Kd = 0.1·k_ft (defect 2: never zero away from the target).
  const Eigen::Vector3d fsw = swingFootForce(50.0, Eigen::Vector3d(0, 0.2, 0),
                                             Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0.3, 0.5));
  EXPECT_NEAR((fsw - Eigen::Vector3d(0, 5.0, 25.0 - 5.0)).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace gaitlab::gait
