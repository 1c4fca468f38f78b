// Footfall patterns by name (gait/footfall.h): the walk and the run by duty factor (Alexander
// 1984), a quadruped's running gaits by the feet that lift off together (Hildebrand 1965, 1977),
// on made-up schedules and on the gait files the walking benchmark measures.
#include <gtest/gtest.h>

#include <string>

#include "body/morphology.h"
#include "gait/footfall.h"
#include "gait/params_io.h"

using namespace gaitlab;
using namespace gaitlab::gait;

namespace {

// Step triggers front left, front right, back left, back right; one duty factor for all four.
Footfall quadruped(double fl, double fr, double bl, double br, double duty = 0.4) {
  static const body::Morphology m = body::makeQuadruped();
  const LegSchedule legs[4] = {{fl, duty}, {fr, duty}, {bl, duty}, {br, duty}};
  return classifyFootfall(m, legs);
}

// The footfall of each key of a gait file, in key order.
std::vector<std::string> keysOf(const std::string& file, Character c) {
  GaitFile f;
  const auto error = loadGaitFile(std::string(GAITLAB_SOURCE_DIR) + "/" + file, c, &f);
  EXPECT_FALSE(error) << file << ": " << (error ? error->describe() : "");
  const body::Morphology m = c == Character::Biped ? body::makeBiped() : body::makeQuadruped();
  std::vector<std::string> names;
  for (const SpeedKey& k : f.gait.keys) {
    LegSchedule legs[GaitPlayer::kMaxLegs];
    for (size_t l = 0; l < m.legs.size(); ++l) legs[l] = {k.params.legs[l].stepTrigger, k.params.legs[l].dutyFactor};
    names.push_back(footfallName(classifyFootfall(m, legs)));
  }
  return names;
}

}  // namespace

TEST(Footfall, AQuadrupedsRunningGaitsAreNamedByTheFeetThatLiftOffTogether) {
  EXPECT_EQ(quadruped(0.0, 0.5, 0.5, 0.0), Footfall::Trot);
  EXPECT_EQ(quadruped(0.0, 0.5, 0.0, 0.5), Footfall::Pace);
  EXPECT_EQ(quadruped(0.0, 0.0, 0.5, 0.5), Footfall::Bound);
  EXPECT_EQ(quadruped(0.3, 0.3, 0.3, 0.3), Footfall::Pronk);
  // Each leg frame's feet half a cycle apart, no pair together: a running walk.
  EXPECT_EQ(quadruped(0.25, 0.75, 0.0, 0.5), Footfall::Amble);
  // Asymmetric: one diagonal pair together (three beats), or none (four).
  EXPECT_EQ(quadruped(0.155, 0.405, 0.905, 0.155), Footfall::Canter);
  EXPECT_EQ(quadruped(0.0, 0.2, 0.55, 0.7), Footfall::Gallop);
  // "Together" tolerates 0.15 of a cycle, across the wrap as well.
  EXPECT_EQ(quadruped(0.95, 0.45, 0.52, 0.05), Footfall::Trot);
  EXPECT_EQ(quadruped(0.0, 0.5, 0.5, 0.2), Footfall::Canter);
}

TEST(Footfall, EveryFootDownMoreThanHalfTheCycleIsAWalk) {
  EXPECT_EQ(quadruped(0.25, 0.75, 0.0, 0.5, 0.65), Footfall::Walk);
  // The duty factors decide, whatever the triggers: a trot's with every foot down longer is a walk.
  EXPECT_EQ(quadruped(0.0, 0.5, 0.5, 0.0, 0.6), Footfall::Walk);
  const body::Morphology biped = body::makeBiped();
  const LegSchedule walk[2] = {{0.0, 0.62}, {0.5, 0.62}}, run[2] = {{0.0, 0.41}, {0.5, 0.36}};
  EXPECT_EQ(classifyFootfall(biped, walk), Footfall::Walk);
  EXPECT_EQ(classifyFootfall(biped, run), Footfall::Run);
  // One leg short of half the cycle is not a walk.
  const LegSchedule limp[2] = {{0.0, 0.62}, {0.5, 0.45}};
  EXPECT_EQ(classifyFootfall(biped, limp), Footfall::Run);
  EXPECT_STREQ(footfallName(Footfall::Canter), "canter");
  EXPECT_STREQ(footfallName(Footfall::Unknown), "unknown");
}

// The gait files: the quadruped's walk, trot (every key, the 2.7 m/s key's uneven rhythm
// included) and pace, the canter keys of the research gaits, and the biped's two gaits: the preset,
// a walk with double support, and the jog it replaced, a run by duty factor (0.41 / 0.36) at
// every speed (docs/controller-notes.md).
TEST(Footfall, TheGaitFilesAreTheGaitsTheyAreNamedFor) {
  using V = std::vector<std::string>;
  EXPECT_EQ(keysOf("public/presets/quadruped-walk.json", Character::Quadruped), V{"walk"});
  EXPECT_EQ(keysOf("public/presets/quadruped-trot.json", Character::Quadruped), V(4, "trot"));
  EXPECT_EQ(keysOf("public/presets/quadruped-pace.json", Character::Quadruped), V{"pace"});
  // The preset by speed (0, 0.01, 0.15, 0.45, 0.8, 1.6, 2.1, 2.7, 2.8, 3.0, 3.2, 3.5 m/s): the
  // standing and quick-step keys trot on the spot, the walk at 0.15 m/s, the trot from 0.45 (its
  // bridge at 2.8 included), the canter from 3.0. The research canters have two canter keys (the
  // top one at 4.0 m/s in the one whose top key does not yet sit at the speed it runs).
  const V trotBelow{"trot", "trot", "walk", "trot", "trot", "trot", "trot", "trot", "trot"};
  V canter = trotBelow;
  canter.insert(canter.end(), {"canter", "canter", "canter"});
  EXPECT_EQ(keysOf("public/presets/quadruped.json", Character::Quadruped), canter);
  V research = trotBelow;
  research.insert(research.end(), {"canter", "canter"});
  EXPECT_EQ(keysOf("bench/gaits/quadruped-canter-trim.json", Character::Quadruped), research);
  EXPECT_EQ(keysOf("bench/gaits/quadruped-canter.json", Character::Quadruped), research);
  // The preset (0, 0.15, 0.5, 1.4, 1.8, 2.5 m/s): the standing key, the walk, the run at 2.5.
  EXPECT_EQ(keysOf("public/presets/biped.json", Character::Biped), (V{"run", "walk", "walk", "walk", "walk", "run"}));
  EXPECT_EQ(keysOf("bench/gaits/biped-jog.json", Character::Biped), (V{"run", "run"}));
}
