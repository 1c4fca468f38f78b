// The ground's relief (walking criteria on uneven ground; the demo's ground choice): flat, a ±5° slope, or 3 cm bumps.
//
// A terrain is a square grid of height samples centred on the origin, joined by the triangles of
// Bullet's btHeightfieldTerrainShape, and an infinite flat plane at planeHeight() beyond it. The
// samples are the one definition of the ground: the physics collides with them (World::setTerrain),
// the controller's ground height is a ray cast against them (World::terrainHeight), and the web page
// builds its ground mesh from the same array (gl_sim_terrain_*), so nothing re-implements the
// formulas below.
//
// Kinds (every length in metres):
//   flat   the plane y = 0 alone, no samples (the ground gaitlab always had).
//   slope  ridges and valleys across the walking direction of a character facing +z (heading 0):
//          y = tan(5°)·tri(z), where tri rises 1:1 for 5 m and falls for 5 m, with tri(0) = 0
//          rising: ridges at z = 2.5 + 10k, valleys at z = −2.5 + 10k, peak to trough 0.437 m.
//          A character spawned at the origin facing +z stands on a 5° up-grade, crests after 2.5 m
//          and then goes down 5° for 5 m, up 5 m... Constant along x. Samples every 0.5 m, which
//          includes every ridge and valley line, so the sampled ground is the profile exactly.
//   bumps  smooth random bumps, an egg crate with random heights: a lattice every 0.5 m whose
//          points alternate bump (+a) and hollow (−a), each a drawn uniformly in [1.0, 1.5] cm from
//          the seed, joined by quintic smoothstep interpolation (C², and every lattice point is an
//          extremum). So the ground stays within ±1.5 cm (peak to trough at most 3.0 cm), every
//          bump is 2.0–3.0 cm above its neighbouring hollows (2.5 cm on average), bumps are 0.71 m
//          apart diagonally and 1 m along the axes (a step of the biped is 0.3–0.5 m), and the
//          steepest grade is 6.4°. Samples every 0.125 m (every lattice point is a sample);
//          between samples the heightfield's triangles differ from the smooth formula by < 3 mm.
//
// Extent: the grid covers |x|, |z| ≤ 120 m: a crowd as large as the demo allows (256 characters,
// ±19 m × ±23 m) walking for 60 s at 1.5 m/s in any heading stays within 113 m of the origin. In the
// outer 10 m the relief blends smoothly (quintic) into the plane, which lies 2 cm below the
// lowest point of the relief, so a character that walks further steps down onto flat ground
// rather than off an edge. Memory: 1921² floats (14.8 MB) for bumps, 481² (0.9 MB) for slope,
// shared by every physics shard of a simulation.
//
// Deterministic: the heights are computed from the seed with integer arithmetic, + − × ÷ and
// polynomials only (no libm), so the same seed gives bit-identical samples natively and in WASM.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class btCollisionDispatcher;
class btCollisionShape;
class btTransform;

namespace gaitlab::physics {

enum class TerrainKind { Flat = 0, Slope = 1, Bumps = 2 };
const char* terrainName(TerrainKind kind);
// "flat", "slope", "bumps"; false for anything else.
bool parseTerrain(const std::string& name, TerrainKind* out);

class Terrain {
 public:
  static constexpr double kHalfSize = 120.0;  // the grid covers [−kHalfSize, kHalfSize]²
  static constexpr double kBlend = 10.0;      // outer band blending into the plane
  static constexpr double kPlaneClearance = 0.02;  // plane below the relief's lowest point
  // Slope: tan(5°), and the length of each up or down run.
  static constexpr double kSlopeGrade = 0.087488663525924;
  static constexpr double kSlopeRun = 5.0;
  static constexpr double kSlopeSpacing = 0.5;
  // Bumps: lattice spacing, the range of each bump's height (half its peak-to-trough), sampling.
  static constexpr double kBumpLattice = 0.5;
  static constexpr double kBumpMin = 0.010, kBumpMax = 0.015;
  static constexpr double kBumpSpacing = 0.125;

  // `scale` multiplies the relief (1: as specified above). Tests use 0: a heightfield that is
  // flat, to compare its contacts with the plane's.
  Terrain(TerrainKind kind, uint32_t seed, double scale = 1.0);

  TerrainKind kind() const { return kind_; }
  const char* name() const { return terrainName(kind_); }
  uint32_t seed() const { return seed_; }
  bool flat() const { return kind_ == TerrainKind::Flat; }

  // The grid: columns along +x, rows along +z; sample (c, r) lies at
  // (originX() + c·spacing(), sample(c, r), originZ() + r·spacing()). Empty when flat.
  int columns() const { return columns_; }
  int rows() const { return rows_; }
  double spacing() const { return spacing_; }
  double originX() const { return -0.5 * (columns_ - 1) * spacing_; }
  double originZ() const { return -0.5 * (rows_ - 1) * spacing_; }
  // Row-major: heights()[r * columns() + c]. Bullet reads this array in place.
  const std::vector<float>& heights() const { return heights_; }
  float sample(int column, int row) const { return heights_[static_cast<size_t>(row) * columns_ + column]; }
  float minHeight() const { return minHeight_; }
  float maxHeight() const { return maxHeight_; }
  // Height of the flat ground beyond the grid (and everywhere when flat).
  double planeHeight() const { return planeHeight_; }

  // The kind's formula before sampling and blending (see the top of this file): what the
  // samples are taken from. Zero when flat.
  double relief(double x, double z) const;
  // The ground as the physics has it: inside the grid the samples joined by Bullet's triangles
  // (each cell split along the diagonal from (c+1, r) to (c, r+1)), the plane outside.
  double height(double x, double z) const;
  // The same, with the upward unit normal of the triangle (or plane) under (x, z). `inside` says
  // whether (x, z) lies on the grid.
  struct Surface {
    double height;
    double normal[3];
    bool inside;
  };
  Surface surface(double x, double z) const;

  // 16 hex digits of a 64-bit FNV-1a hash of the kind, grid and samples' exact bits.
  std::string hash() const;

 private:
  double sampleHeight(double x, double z) const;  // relief blended into the plane
  TerrainKind kind_;
  uint32_t seed_;
  double scale_;
  int columns_ = 0, rows_ = 0;
  double spacing_ = 1.0;
  double planeHeight_ = 0.0;
  float minHeight_ = 0, maxHeight_ = 0;
  std::vector<float> heights_;
};

// Bullet's view of a terrain with samples: a btHeightfieldTerrainShape reading terrain.heights()
// in place (the terrain must outlive it), and the transform that puts its samples where
// Terrain::height says they are. nullptr for flat terrain.
std::unique_ptr<btCollisionShape> makeHeightfieldShape(const Terrain& terrain, btTransform* where);

// Box–terrain contacts for `dispatcher`, in place of Bullet's generic convex–triangle-mesh
// algorithm (GJK against every triangle under the box). Measured: with that, a biped whose
// preset walks 60 s on the plane fell within 1.3-3.6 s on a heightfield of zeros (the same flat
// ground): GJK against single triangles gives a box corner near a shared edge the edge's
// normal, tilted up to 45° off the surface, and one point per triangle per step. This one does
// for a terrain what btConvexPlaneCollisionAlgorithm does for the plane: every box corner
// against the triangle under it (its normal, its height), plus every terrain sample inside the
// box (a bump's top or a ridge under the middle of a sole) against the box face that faces down.
// Other shapes keep Bullet's algorithm. Safe to call more than once.
void registerTerrainCollision(btCollisionDispatcher& dispatcher);

}  // namespace gaitlab::physics
