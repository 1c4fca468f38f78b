// Where characters stand when a scene is made: the two layouts of gaitlab's scenes, as geometry
// only (the simulation spawns what they place).
//
//  - The crowd benchmark's grid (Larsson 2015 §4.1, Figures 4.5 and 4.6): N characters on a
//    square grid `spacing` metres apart, centred on the origin, all facing +z.
//  - The demo page's layout (SceneLayout): the page's crowd on a grid 2.5 m apart across and 3 m
//    deep, facing +z; characters added later take the next free places, in rows behind the first
//    crowd (−z), away from where the crowd walks; and one place apart, left of the grid, where
//    the optimize panel's learner walks alone. The page asks the simulation for places
//    (gl_sim_add_characters) rather than computing them, so a page run can be replayed natively
//    from its seed, this layout and its command log.
#pragma once
#include "gait/schema.h"

namespace gaitlab::sim {

// A character's type is the gait schema's: one enum (gait::Character) from the schema through
// the simulation to the C ABI's GL_KIND_* numbers. Boxes are props, not a type of character.
using gait::Character;

// Who makes up a crowd: thesis §4.1 measured bipeds and quadrupeds apart; the demo page mixes
// them, alternating so that each type spreads over the whole grid.
enum class Crowd { Bipeds, Quadrupeds, Mixed, Hexapods, Octopods };
// The type of the i-th character of a crowd (Mixed: a biped first, then in turn).
Character crowdKind(Crowd crowd, int i);

// A place to stand: ground-plane position (metres) and heading (radians about +y, 0 = +z).
struct Place {
  double x = 0, z = 0, heading = 0;
};

// The i-th of `characters` places of the crowd benchmark's grid, `spacing` metres apart.
Place benchmarkPlace(int i, int characters, double spacing);

// The demo page's layout. The first group placed sizes the grid (ceil(sqrt(n)) columns, the
// rows that n needs), even a group of none; every place after that continues it.
class SceneLayout {
 public:
  static constexpr double kSpacingX = 2.5;  // across, m: wider than a quadruped is long
  static constexpr double kSpacingZ = 3.0;  // deep, m: a biped's stride or two between rows
  static constexpr double kApartGap = 5.0;  // m left (−x) of the grid's first column

  // Sizes the grid for a first group of `characters`, unless it is sized already.
  void plan(int characters);
  bool planned() const { return columns_ > 0; }
  // The next free place (plan() first); taking it moves on.
  Place next();
  // The place apart, left of the grid, level with its middle row.
  Place apart() const;
  // Places handed out so far.
  int used() const { return used_; }

 private:
  int columns_ = 0, rows_ = 0;
  int used_ = 0;
};

}  // namespace gaitlab::sim
