// The support polygon of the feet (gait/support_polygon.h): its convex hull, and the signed
// distance of a point (the capture point) from its edge, which decides when a standing character
// has to step.
#include <gtest/gtest.h>

#include "gait/support_polygon.h"

namespace gaitlab::gait {
namespace {

using Eigen::Vector2d;

TEST(SupportPolygon, TheHullOfTwoFeetIsTheirOutlineAndInsideIsTheDistanceToItsEdge) {
  // Two soles 0.1 × 0.2 m, side by side 0.2 m apart (centres at x = ±0.1), as a biped stands.
  Vector2d corners[8];
  int n = 0;
  for (double cx : {-0.1, 0.1})
    for (double dx : {-0.05, 0.05})
      for (double dz : {-0.1, 0.1}) corners[n++] = Vector2d(cx + dx, dz);
  const SupportPolygon p = SupportPolygon::hullOf(corners, n);
  EXPECT_EQ(p.count, 4);  // the outer corners: a 0.3 × 0.2 m rectangle
  EXPECT_NEAR(p.centroid().x(), 0.0, 1e-12);
  EXPECT_NEAR(p.centroid().y(), 0.0, 1e-12);
  EXPECT_NEAR(p.inside(Vector2d(0, 0)), 0.1, 1e-12);       // nearest edge: the toes and heels
  EXPECT_NEAR(p.inside(Vector2d(0.12, 0)), 0.03, 1e-12);   // 3 cm from the outer side
  EXPECT_NEAR(p.inside(Vector2d(0.25, 0)), -0.1, 1e-12);   // 10 cm outside
  EXPECT_NEAR(p.inside(Vector2d(0.15, 0.1)), 0.0, 1e-12);  // on a corner
  EXPECT_NEAR(p.inside(Vector2d(0.18, 0.14)), -0.05, 1e-12);
}

TEST(SupportPolygon, FewerThanThreePointsHaveNoInside) {
  const Vector2d two[2] = {Vector2d(0, 0), Vector2d(1, 0)};
  const SupportPolygon line = SupportPolygon::hullOf(two, 2);
  EXPECT_NEAR(line.inside(Vector2d(0.5, 0)), 0.0, 1e-12);
  EXPECT_NEAR(line.inside(Vector2d(0.5, 0.2)), -0.2, 1e-12);
  EXPECT_LT(SupportPolygon::hullOf(two, 0).inside(Vector2d(0, 0)), -1e300);
  // Repeated and collinear points are dropped from the hull; non-finite ones ignored.
  const Vector2d many[6] = {Vector2d(0, 0), Vector2d(1, 0), Vector2d(0.5, 0), Vector2d(1, 1),
                            Vector2d(0, 1), Vector2d(NAN, 0)};
  EXPECT_EQ(SupportPolygon::hullOf(many, 6).count, 4);
}

}  // namespace
}  // namespace gaitlab::gait
