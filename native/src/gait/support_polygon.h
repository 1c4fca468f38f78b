// The support polygon of the feet on the ground, and how far a point lies inside it (beyond
// the thesis). A body standing on planted feet stays balanced while its capture point, the
// point x + v·√(h/g) over which the inverted pendulum of its centre of mass would come to
// rest (Pratt et al. 2006; the low-speed placement of Coros et al. 2010), lies inside the
// support polygon; once it leaves, only a step can catch the body. The standing controller
// (gait/standing.cpp) uses this to decide when a standing character must step.
//
// Horizontal plane (x, z). Physics-free; fixed-size storage (no heap).
#pragma once
#include <Eigen/Dense>

namespace gaitlab::gait {

constexpr int kMaxSupportPoints = 32;  // e.g. 8 feet × the 4 corners of each sole

struct SupportPolygon {
  Eigen::Vector2d vertices[kMaxSupportPoints];  // convex hull, counter-clockwise, (x, z)
  int count = 0;

  // The convex hull of `count` points (x, z); more than kMaxSupportPoints are ignored.
  static SupportPolygon hullOf(const Eigen::Vector2d* points, int count);

  // Signed distance from `p` to the polygon's boundary, positive inside (m). A polygon of
  // fewer than three vertices (a line or a point: no area to stand on) gives minus the
  // distance to it.
  double inside(const Eigen::Vector2d& p) const;
  Eigen::Vector2d centroid() const;  // of the vertices (the centre of the feet)
};

}  // namespace gaitlab::gait
