#include "gait/support_polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gaitlab::gait {

namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace

SupportPolygon SupportPolygon::hullOf(const Eigen::Vector2d* points, int count) {
  // Andrew's monotone chain: sort by x then z, build the lower and upper chains.
  Eigen::Vector2d p[kMaxSupportPoints];
  int n = 0;
  for (int i = 0; i < count && n < kMaxSupportPoints; ++i)
    if (points[i].allFinite()) p[n++] = points[i];
  std::sort(p, p + n, [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  SupportPolygon hull;
  if (n < 3) {
    for (int i = 0; i < n; ++i) hull.vertices[hull.count++] = p[i];
    return hull;
  }
  Eigen::Vector2d h[2 * kMaxSupportPoints];
  int k = 0;
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  hull.count = std::min(k - 1, kMaxSupportPoints);  // the last point repeats the first
  for (int i = 0; i < hull.count; ++i) hull.vertices[i] = h[i];
  return hull;
}

double SupportPolygon::inside(const Eigen::Vector2d& p) const {
  if (count == 0) return -std::numeric_limits<double>::infinity();
  double nearest = std::numeric_limits<double>::infinity();
  bool in = count >= 3;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d& a = vertices[i];
    const Eigen::Vector2d& b = vertices[(i + 1) % count];
    nearest = std::min(nearest, distanceToSegment(p, a, b));
    if (count >= 3 && cross(a, b, p) < 0) in = false;  // right of a counter-clockwise edge
  }
  return in ? nearest : -nearest;
}

Eigen::Vector2d SupportPolygon::centroid() const {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (int i = 0; i < count; ++i) c += vertices[i];
  return count > 0 ? Eigen::Vector2d(c / count) : c;
}

}  // namespace gaitlab::gait
