#include "physics/terrain.h"

#include <BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>
#include <LinearMath/btTransform.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics/collision_algorithm.h"
#include "physics/fnv1a.h"

namespace gaitlab::physics {

namespace {

// Quintic smoothstep (Perlin's fade): 0 → 1 on [0, 1] with zero first and second derivatives at
// both ends, so joined pieces are C² and the ends are extrema.
double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Ridge-and-valley profile in units of run length: rises 1:1 from 0 at z = 0 to +run/2 at
// z = run/2, falls to −run/2 at z = 3·run/2, period 2·run.
double triangle(double z, double run) {
  const double period = 2 * run, u = z + 0.5 * run;
  const double m = u - period * std::floor(u / period);  // in [0, period)
  return 0.5 * run - std::fabs(m - run);
}

// Height in [0, 1) of lattice point (i, j) for `seed`: a 32-bit integer hash (MurmurHash3's
// finaliser over the mixed coordinates), the same on every platform.
double latticeRandom(int64_t i, int64_t j, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B1u;
  h ^= static_cast<uint32_t>(i) * 0x85EBCA77u;
  h = (h << 13) | (h >> 19);
  h ^= static_cast<uint32_t>(j) * 0xC2B2AE3Du;
  h ^= h >> 16;
  h *= 0x85EBCA6Bu;
  h ^= h >> 13;
  h *= 0xC2B2AE35u;
  h ^= h >> 16;
  return (h >> 8) * (1.0 / 16777216.0);
}

}  // namespace

const char* terrainName(TerrainKind kind) {
  switch (kind) {
    case TerrainKind::Flat: return "flat";
    case TerrainKind::Slope: return "slope";
    case TerrainKind::Bumps: return "bumps";
  }
  return "?";
}

bool parseTerrain(const std::string& name, TerrainKind* out) {
  for (TerrainKind k : {TerrainKind::Flat, TerrainKind::Slope, TerrainKind::Bumps}) {
    if (name == terrainName(k)) {
      *out = k;
      return true;
    }
  }
  return false;
}

Terrain::Terrain(TerrainKind kind, uint32_t seed, double scale) : kind_(kind), seed_(seed), scale_(scale) {
  if (kind_ == TerrainKind::Flat) return;
  spacing_ = kind_ == TerrainKind::Slope ? kSlopeSpacing : kBumpSpacing;
  // The relief's lowest point, from the formula: the plane lies kPlaneClearance below it, so
  // inside the grid only the heightfield is ever touched.
  const double lowest = kind_ == TerrainKind::Slope ? -0.5 * kSlopeRun * kSlopeGrade : -kBumpMax;
  planeHeight_ = std::fabs(scale_) * lowest - kPlaneClearance;
  columns_ = rows_ = static_cast<int>(std::lround(2 * kHalfSize / spacing_)) + 1;
  heights_.resize(static_cast<size_t>(columns_) * rows_);
  const double x0 = originX(), z0 = originZ();
  for (int r = 0; r < rows_; ++r) {
    const double z = z0 + r * spacing_;
    for (int c = 0; c < columns_; ++c) {
      heights_[static_cast<size_t>(r) * columns_ + c] = static_cast<float>(sampleHeight(x0 + c * spacing_, z));
    }
  }
  const auto [lo, hi] = std::minmax_element(heights_.begin(), heights_.end());
  minHeight_ = *lo;
  maxHeight_ = *hi;
}

double Terrain::relief(double x, double z) const {
  switch (kind_) {
    case TerrainKind::Flat:
      return 0.0;
    case TerrainKind::Slope:
      return kSlopeGrade * triangle(z, kSlopeRun);
    case TerrainKind::Bumps: {
      const double u = x / kBumpLattice, v = z / kBumpLattice;
      const double fi = std::floor(u), fj = std::floor(v);
      const auto i = static_cast<int64_t>(fi), j = static_cast<int64_t>(fj);
      // Lattice point (i, j) is a bump when i + j is even, a hollow when odd.
      const auto at = [&](int64_t a, int64_t b) {
        const double height = kBumpMin + (kBumpMax - kBumpMin) * latticeRandom(a, b, seed_);
        return ((a + b) & 1) ? -height : height;
      };
      const double sx = fade(u - fi), sz = fade(v - fj);
      const double near = at(i, j) + (at(i + 1, j) - at(i, j)) * sx;
      const double far = at(i, j + 1) + (at(i + 1, j + 1) - at(i, j + 1)) * sx;
      return near + (far - near) * sz;
    }
  }
  return 0.0;
}

double Terrain::sampleHeight(double x, double z) const {
  // Blend weight: 1 inside, easing to 0 over the outer kBlend metres of the grid.
  const auto weight = [](double a) {
    const double t = (kHalfSize - std::fabs(a)) / kBlend;
    return t >= 1 ? 1.0 : t <= 0 ? 0.0 : fade(t);
  };
  const double w = weight(x) * weight(z);
  const double r = scale_ * relief(x, z);
  return w == 1.0 ? r : planeHeight_ + w * (r - planeHeight_);
}

double Terrain::height(double x, double z) const { return surface(x, z).height; }

Terrain::Surface Terrain::surface(double x, double z) const {
  const double u = (x - originX()) / spacing_, v = (z - originZ()) / spacing_;
  if (flat() || !(u >= 0 && v >= 0 && u <= columns_ - 1 && v <= rows_ - 1))
    return {planeHeight_, {0, 1, 0}, false};
  const int c = std::min(static_cast<int>(u), columns_ - 2), r = std::min(static_cast<int>(v), rows_ - 2);
  const double fx = u - c, fz = v - r;
  const double h00 = sample(c, r), h10 = sample(c + 1, r), h01 = sample(c, r + 1),
               h11 = sample(c + 1, r + 1);
  // btHeightfieldTerrainShape (no flipped or diamond subdivision) splits cell (c, r) into the
  // triangles (c, r) (c, r+1) (c+1, r) and (c+1, r) (c, r+1) (c+1, r+1).
  double height, dx, dz;  // and the gradient, per cell
  if (fx + fz <= 1) {
    height = h00 + fx * (h10 - h00) + fz * (h01 - h00);
    dx = h10 - h00;
    dz = h01 - h00;
  } else {
    height = h11 + (1 - fx) * (h01 - h11) + (1 - fz) * (h10 - h11);
    dx = h11 - h01;
    dz = h11 - h10;
  }
  dx /= spacing_;
  dz /= spacing_;
  const double norm = std::sqrt(dx * dx + 1 + dz * dz);
  return {height, {-dx / norm, 1 / norm, -dz / norm}, true};
}

std::string Terrain::hash() const {
  Fnv1a h;
  const int kind = static_cast<int>(kind_);
  h.bytes(&kind, sizeof(kind));
  h.bytes(&columns_, sizeof(columns_));
  h.bytes(&rows_, sizeof(rows_));
  h.bytes(&spacing_, sizeof(spacing_));
  h.bytes(&planeHeight_, sizeof(planeHeight_));
  if (!heights_.empty()) h.bytes(heights_.data(), heights_.size() * sizeof(float));
  char out[17];
  std::snprintf(out, sizeof(out), "%016llx", static_cast<unsigned long long>(h.h));
  return out;
}

std::unique_ptr<btCollisionShape> makeHeightfieldShape(const Terrain& t, btTransform* where) {
  if (t.flat()) return nullptr;
  auto shape = std::make_unique<btHeightfieldTerrainShape>(
      t.columns(), t.rows(), t.heights().data(), t.minHeight(), t.maxHeight(), 1, false);
  // The box–terrain algorithm (registerTerrainCollision) reads the terrain through this.
  shape->setUserPointer(const_cast<Terrain*>(&t));
  shape->setLocalScaling(btVector3(static_cast<btScalar>(t.spacing()), 1, static_cast<btScalar>(t.spacing())));
  // Bullet centres the grid on the shape's origin horizontally and puts the middle of
  // [minHeight, maxHeight] there vertically: the grid is centred on the world's origin already.
  *where = btTransform::getIdentity();
  where->setOrigin(btVector3(0, 0.5f * (t.minHeight() + t.maxHeight()), 0));
  return shape;
}

}  // namespace gaitlab::physics

// ---- Box–terrain contacts -----------------------------------------------------------------------

namespace gaitlab::physics {

namespace {

class BoxTerrainAlgorithm : public btCollisionAlgorithm {
 public:
  BoxTerrainAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* a,
                      const btCollisionObjectWrapper* b, bool swapped)
      : btCollisionAlgorithm(ci), swapped_(swapped) {
    const btCollisionObject* box = (swapped ? b : a)->getCollisionObject();
    const btCollisionObject* ground = (swapped ? a : b)->getCollisionObject();
    // The manifold is (box, terrain): contact normals point from the terrain to the box.
    if (m_dispatcher->needsCollision(box, ground)) manifold_ = m_dispatcher->getNewManifold(box, ground);
  }
  ~BoxTerrainAlgorithm() override {
    if (manifold_) m_dispatcher->releaseManifold(manifold_);
  }

  void processCollision(const btCollisionObjectWrapper* a, const btCollisionObjectWrapper* b,
                        const btDispatcherInfo&, btManifoldResult* out) override {
    if (!manifold_) return;
    const btCollisionObjectWrapper* boxWrap = swapped_ ? b : a;
    const btCollisionObjectWrapper* groundWrap = swapped_ ? a : b;
    const auto* box = static_cast<const btBoxShape*>(boxWrap->getCollisionShape());
    const auto* terrain = static_cast<const Terrain*>(groundWrap->getCollisionShape()->getUserPointer());
    out->setPersistentManifold(manifold_);
    const btTransform& t = boxWrap->getWorldTransform();
    const btVector3 half = box->getHalfExtentsWithMargin();
    const double threshold = manifold_->getContactBreakingThreshold();
    btVector3 lo, hi;
    box->getAabb(t, lo, hi);
    if (lo.y() <= terrain->maxHeight() + threshold) {
      // Each corner against the triangle under it, as the plane algorithm takes the deepest
      // vertex against the plane: distance along the triangle's normal.
      for (int i = 0; i < 8; ++i) {
        const btVector3 p = t(btVector3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(),
                                        i & 4 ? half.z() : -half.z()));
        const Terrain::Surface s = terrain->surface(p.x(), p.z());
        if (!s.inside) continue;  // beyond the grid the plane takes over
        const double d = (p.y() - s.height) * s.normal[1];
        if (d >= threshold) continue;
        const btVector3 n(static_cast<btScalar>(s.normal[0]), static_cast<btScalar>(s.normal[1]),
                          static_cast<btScalar>(s.normal[2]));
        out->addContactPoint(n, p - n * static_cast<btScalar>(d), static_cast<btScalar>(d));
      }
      // Terrain samples inside the box (a bump's top or a ridge under the middle of a sole),
      // pushed out through the face that faces the ground most, the one whose outward normal is
      // closest to straight down: a sample comes up into a sole from below, not sideways into a
      // toe, which the nearest face would often say.
      const btVector3 down = t.getBasis().transpose() * btVector3(0, -1, 0);  // in the box frame
      int k = 0;
      for (int a = 1; a < 3; ++a)
        if (btFabs(down[a]) > btFabs(down[k])) k = a;
      btVector3 face(0, 0, 0);
      face[k] = down[k] < 0 ? -1 : 1;
      const btVector3 n = -(t.getBasis() * face);  // out of the terrain, into the box
      const double sp = terrain->spacing();
      const int c0 = std::max(0, static_cast<int>(std::ceil((lo.x() - terrain->originX()) / sp)));
      const int c1 = std::min(terrain->columns() - 1, static_cast<int>(std::floor((hi.x() - terrain->originX()) / sp)));
      const int r0 = std::max(0, static_cast<int>(std::ceil((lo.z() - terrain->originZ()) / sp)));
      const int r1 = std::min(terrain->rows() - 1, static_cast<int>(std::floor((hi.z() - terrain->originZ()) / sp)));
      for (int r = r0; r <= r1; ++r) {
        for (int c = c0; c <= c1; ++c) {
          const btVector3 v(static_cast<btScalar>(terrain->originX() + c * sp), terrain->sample(c, r),
                            static_cast<btScalar>(terrain->originZ() + r * sp));
          if (v.y() < lo.y()) continue;
          const btVector3 l = t.invXform(v);
          if (btFabs(l.x()) >= half.x() || btFabs(l.y()) >= half.y() || btFabs(l.z()) >= half.z()) continue;
          const btScalar depth = half[k] - face[k] * l[k];  // from the sample out to that face
          out->addContactPoint(n, v, -depth);
        }
      }
    }
    if (manifold_->getNumContacts()) out->refreshContactPoints();
  }

  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;  // no continuous collision detection, as for the plane
  }

  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (manifold_) manifolds.push_back(manifold_);
  }

 private:
  btPersistentManifold* manifold_ = nullptr;
  bool swapped_;
};

}  // namespace

void registerTerrainCollision(btCollisionDispatcher& dispatcher) {
  registerCollisionAlgorithm<BoxTerrainAlgorithm>(dispatcher, BOX_SHAPE_PROXYTYPE, TERRAIN_SHAPE_PROXYTYPE);
}

}  // namespace gaitlab::physics
