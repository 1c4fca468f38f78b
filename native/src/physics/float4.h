// Four floats in one SIMD register, the layout of btVector3 (GCC and Clang vector extension;
// SSE natively, WebAssembly SIMD in the browser), for arithmetic that must round exactly as
// Bullet's scalar btVector3 code does: a sum or product of two vectors is the same IEEE operation
// per component either way, and neither build has fused multiply-adds (docs/parallel.md). Used
// by the fast constraint sweep (physics/solver.h) and the joint row setup (physics/joint_rows.h).
#pragma once
#include <LinearMath/btVector3.h>

#include <cstring>

namespace gaitlab::physics {

typedef float Float4 __attribute__((vector_size(16)));
static_assert(sizeof(btScalar) == sizeof(float), "single precision, as the solver's rows are");
static_assert(sizeof(btVector3) == sizeof(Float4), "btVector3 is four floats (m_floats[4])");

inline Float4 load(const btVector3& v) {
  Float4 r;
  std::memcpy(&r, v.m_floats, sizeof r);
  return r;
}
inline void store(btVector3& v, Float4 r) { std::memcpy(v.m_floats, &r, sizeof r); }
inline Float4 splat(btScalar s) { return Float4{s, s, s, s}; }

// btVector3::dot without Bullet's SSE: x*x' + y*y' + z*z', left to right.
inline btScalar dot3(Float4 a, Float4 b) {
  const Float4 p = a * b;
  return (p[0] + p[1]) + p[2];
}

}  // namespace gaitlab::physics
