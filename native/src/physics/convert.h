// Conversions between Bullet's single-precision types and the controller's Eigen doubles.
#pragma once
#include <LinearMath/btQuaternion.h>
#include <LinearMath/btVector3.h>

#include <Eigen/Dense>

namespace gaitlab::physics {

inline btVector3 toBt(const Eigen::Vector3d& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}
inline btQuaternion toBt(const Eigen::Quaterniond& q) {
  return btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                      static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w()));
}
inline Eigen::Vector3d toEigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
inline Eigen::Quaterniond toEigen(const btQuaternion& q) {
  return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
}

}  // namespace gaitlab::physics
