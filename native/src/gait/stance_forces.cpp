#include "gait/stance_forces.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::gait {

using Eigen::Vector3d;

namespace {

Eigen::Matrix3d cross(const Vector3d& r) {  // [r]×, so that [r]× f = r × f
  Eigen::Matrix3d m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

}  // namespace

bool distributeStanceForces(const Vector3d& com, const Vector3d& force, const Vector3d& torque,
                            const Vector3d* points, int count, const StanceForceSettings& settings,
                            Vector3d* out) {
  if (count < 1 || count > kMaxStanceFeet) return false;
  // Fixed maximum sizes: Eigen keeps these on the stack.
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 3 * kMaxStanceFeet>;
  using Normal = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3 * kMaxStanceFeet,
                               3 * kMaxStanceFeet>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3 * kMaxStanceFeet, 1>;
  const int n = 3 * count;
  Matrix a(6, n);
  for (int i = 0; i < count; ++i) {
    a.block<3, 3>(0, 3 * i).setIdentity();
    a.block<3, 3>(3, 3 * i) = settings.torqueWeight * cross(points[i] - com);
  }
  Eigen::Matrix<double, 6, 1> w;
  w << force, settings.torqueWeight * torque;
  // Normal equations (AᵀA + λI) f = Aᵀw: at most 12 × 12, symmetric positive definite.
  Normal lhs = a.transpose() * a;
  lhs.diagonal().array() += settings.regularisation;
  const Vector f = lhs.ldlt().solve(a.transpose() * w);
  for (int i = 0; i < count; ++i) {
    Vector3d fi = f.segment<3>(3 * i);
    fi.y() = std::max(fi.y(), settings.minNormal);
    const double horizontal = std::hypot(fi.x(), fi.z());
    const double limit = settings.friction * fi.y();
    if (horizontal > limit) {
      fi.x() *= limit / horizontal;
      fi.z() *= limit / horizontal;
    }
    out[i] = fi;
  }
  return true;
}

}  // namespace gaitlab::gait
