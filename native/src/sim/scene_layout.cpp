#include "sim/scene_layout.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::sim {

namespace {
int squareColumns(int n) { return std::max(1, static_cast<int>(std::ceil(std::sqrt(n)))); }
}  // namespace

Character crowdKind(Crowd crowd, int i) {
  switch (crowd) {
    case Crowd::Bipeds: return Character::Biped;
    case Crowd::Quadrupeds: return Character::Quadruped;
    case Crowd::Hexapods: return Character::Hexapod;
    case Crowd::Octopods: return Character::Octopod;
    case Crowd::Mixed: break;
  }
  return i % 2 == 0 ? Character::Biped : Character::Quadruped;
}

Place benchmarkPlace(int i, int characters, double spacing) {
  const int columns = squareColumns(characters);
  return {(i % columns - (columns - 1) / 2.0) * spacing, (i / columns - (columns - 1) / 2.0) * spacing,
          0.0};
}

void SceneLayout::plan(int characters) {
  if (planned()) return;
  columns_ = squareColumns(characters);
  rows_ = std::max(1, static_cast<int>(std::ceil(static_cast<double>(characters) / columns_)));
}

Place SceneLayout::next() {
  plan(0);
  const int slot = used_++;
  // Centred on the origin across; rows count towards −z from the front row of the first group,
  // so rows beyond it continue behind it.
  return {(slot % columns_ - (columns_ - 1) / 2.0) * kSpacingX,
          ((rows_ - 1) / 2.0 - slot / columns_) * kSpacingZ, 0.0};
}

Place SceneLayout::apart() const {
  const int columns = std::max(1, columns_);
  return {-((columns - 1) / 2.0) * kSpacingX - kApartGap, 0.0, 0.0};
}

}  // namespace gaitlab::sim
