// The demo page's scene layout (sim/scene_layout.h) and replaying a page run natively: a scene
// built through the layout plus a command log (the sim worker's: commands applied at given step
// indices) gives the same state every time, and the same through the C ABI the worker calls as
// through the C++ API.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "api/c_api.h"
#include "sim/scene_layout.h"
#include "sim/simulation.h"

using gaitlab::sim::Crowd;
using gaitlab::gait::Character;
using gaitlab::sim::Mode;
using gaitlab::sim::Place;
using gaitlab::sim::SceneLayout;
using gaitlab::sim::Simulation;

TEST(SceneLayout, AGridSizedByTheFirstGroupAndContinuedBehindIt) {
  SceneLayout layout;
  layout.plan(5);  // 3 columns, 2 rows
  layout.plan(100);  // sized once: later groups continue the grid
  std::vector<Place> places;
  for (int i = 0; i < 7; ++i) places.push_back(layout.next());
  // Columns 2.5 m apart centred on x = 0; rows 3 m apart, the first group's centred on z = 0,
  // later ones behind (−z).
  const double expected[7][2] = {{-2.5, 1.5}, {0, 1.5}, {2.5, 1.5}, {-2.5, -1.5},
                                 {0, -1.5},   {2.5, -1.5}, {-2.5, -4.5}};
  for (int i = 0; i < 7; ++i) {
    EXPECT_DOUBLE_EQ(places[i].x, expected[i][0]) << "place " << i;
    EXPECT_DOUBLE_EQ(places[i].z, expected[i][1]) << "place " << i;
    EXPECT_EQ(places[i].heading, 0.0);
  }
  EXPECT_EQ(layout.used(), 7);
  EXPECT_DOUBLE_EQ(layout.apart().x, -7.5) << "5 m left of the first column";
  EXPECT_DOUBLE_EQ(layout.apart().z, 0.0);
}

TEST(SceneLayout, AddCharactersIsSpawningAtTheLayoutsPlacesWithTheCruiseGoal) {
  // What the page's sim worker did itself before the layout moved into C++: its positions
  // (grid columns from the first crowd, 2.5 m by 3 m), spawn, then each type's cruise goal.
  void* byHand = gl_sim_create(1, 9);
  const int first = 5, later = 3;
  const int columns = static_cast<int>(std::ceil(std::sqrt(first)));
  const int rows = static_cast<int>(std::ceil(static_cast<double>(first) / columns));
  for (int slot = 0; slot < first + later; ++slot) {
    const int kind = slot < first ? slot % 2 : GL_KIND_QUADRUPED;
    const double x = ((slot % columns) - (columns - 1) / 2.0) * 2.5;
    const double z = ((rows - 1) / 2.0 - slot / columns) * 3.0;
    const int id = gl_sim_spawn(byHand, kind, x, z, 0);
    ASSERT_EQ(id, slot);
    gl_sim_set_goal(byHand, id, gl_cruise_speed(kind), 0.0);
  }
  void* layout = gl_sim_create(1, 9);
  EXPECT_EQ(gl_sim_add_characters(layout, GL_LAYOUT_ALTERNATING, first), first);
  EXPECT_EQ(gl_sim_add_characters(layout, GL_KIND_QUADRUPED, later), later);
  gl_sim_step(byHand, 60);
  gl_sim_step(layout, 60);
  EXPECT_EQ(std::string(gl_sim_state_hash(layout)), gl_sim_state_hash(byHand));
  // The place apart: as the page's learner was placed.
  const int apart = gl_sim_add_apart(layout, GL_KIND_BIPED);
  const int learner = gl_sim_spawn(byHand, GL_KIND_BIPED, -((columns - 1) / 2.0) * 2.5 - 5, 0, 0);
  EXPECT_EQ(apart, learner);
  gl_sim_step(byHand, 10);
  gl_sim_step(layout, 10);
  EXPECT_EQ(std::string(gl_sim_state_hash(layout)), gl_sim_state_hash(byHand));
  gl_sim_destroy(byHand);
  gl_sim_destroy(layout);
}

TEST(SceneLayout, AddCharactersRefusesWhatItCannotPlace) {
  void* s = gl_sim_create(1, 1);
  EXPECT_EQ(gl_sim_add_characters(s, GL_KIND_BOX, 2), GL_ERR_ARGUMENT);
  EXPECT_EQ(gl_sim_add_characters(s, 99, 2), GL_ERR_ARGUMENT);
  EXPECT_EQ(gl_sim_add_characters(s, GL_KIND_BIPED, -1), GL_ERR_ARGUMENT);
  EXPECT_EQ(gl_sim_add_apart(s, GL_KIND_BOX), GL_ERR_ARGUMENT);
  EXPECT_EQ(gl_sim_character_count(s), 0);
  gl_sim_destroy(s);
}

TEST(SceneLayout, TheDemoSceneIsThePagesCrowdPlusBoxes) {
  Simulation demo(1, 4), page(1, 4);
  demo.demoScene(6);
  page.addCharacters(Crowd::Mixed, 6);
  ASSERT_EQ(demo.characterCount(), 6);
  EXPECT_GT(demo.bodyCount(), page.bodyCount()) << "and a few boxes";
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(demo.idOf(i), page.idOf(i));
    EXPECT_EQ(demo.kindOf(i), page.kindOf(i));
    EXPECT_EQ(demo.controller(i).goal().speed, page.controller(i).goal().speed);
    const auto a = demo.character(i).segmentState(0).position, b = page.character(i).segmentState(0).position;
    EXPECT_EQ(a, b) << "character " << i << " stands in the same place";
  }
}

// ---- Replaying a page run -----------------------------------------------------------------------

namespace {

// One entry of the sim worker's command log: a scene command and the step index it preceded.
struct Command {
  enum Type { Goal, Throw, Drag, EndDrag, Reset, Remove, Add, AutoReset } type;
  int step;
  int id = -1;      // Goal (-1 = all), Drag, Reset, Remove
  double a = 0, b = 0;  // Goal: speed, turn; Add: kind, count; AutoReset: seconds
};

const std::vector<Command>& commandLog() {
  static const std::vector<Command> log = {
      {Command::AutoReset, 0, -1, 1.5},
      {Command::Goal, 0, -1, 1.2, 0.0},
      {Command::Goal, 30, 2, 0.6, 0.4},
      {Command::Throw, 45},
      {Command::Drag, 60, 1},
      {Command::EndDrag, 90},
      {Command::Remove, 100, 3},
      {Command::Add, 100, -1, GL_KIND_QUADRUPED, 2},
      {Command::Throw, 130},
      {Command::Reset, 150, 0},
      // Ids so far: 0-5 the crowd, 6 the first box; the two added took 3's slot a generation on
      // (65539) and slot 7; the second box 8.
      {Command::Goal, 150, 7, 0.3, -0.2},
      {Command::Remove, 170, 1},
      {Command::Add, 170, -1, GL_LAYOUT_ALTERNATING, 1},
      {Command::Goal, 200, -1, 3.0, 0.0},  // too fast: some fall, and the auto-reset acts
  };
  return log;
}

constexpr int kSteps = 720;  // 6 s: some fall after the fast goal and are reset 1.5 s later

// The run through the C ABI, as the sim worker drives it: its scene, its commands, and what it
// does after adding characters (each type's last goal given to all: the added ones get it too).
std::string replayThroughTheCAbi(int threads, uint32_t seed) {
  void* s = gl_sim_create(threads, seed);
  double lastGoal[2][2] = {{gl_cruise_speed(GL_KIND_BIPED), 0}, {gl_cruise_speed(GL_KIND_QUADRUPED), 0}};
  const auto add = [&](int kind, int count) {
    const int added = gl_sim_add_characters(s, kind, count);
    std::vector<double> info(GL_INFO_FIELDS * gl_sim_character_count(s));
    const int n = gl_sim_character_info(s, info.data(), gl_sim_character_count(s));
    for (int i = n - added; i < n; ++i) {
      const double* o = &info[GL_INFO_FIELDS * i];
      const int k = static_cast<int>(o[GL_INFO_KIND]);
      gl_sim_set_goal(s, static_cast<int>(o[GL_INFO_ID]), lastGoal[k][0], lastGoal[k][1]);
    }
  };
  add(GL_LAYOUT_ALTERNATING, 6);
  size_t next = 0;
  for (int step = 0; step < kSteps; ++step) {
    for (; next < commandLog().size() && commandLog()[next].step == step; ++next) {
      const Command& c = commandLog()[next];
      switch (c.type) {
        case Command::Goal:
          gl_sim_set_goal(s, c.id, c.a, c.b);
          if (c.id == -1) lastGoal[0][0] = lastGoal[1][0] = c.a, lastGoal[0][1] = lastGoal[1][1] = c.b;
          break;
        case Command::Throw: {
          const gl_throw_settings t{{-3, 1.2, 2}, {9, 1, -1}, 0.12};
          gl_sim_throw_box(s, &t);
          break;
        }
        case Command::Drag: {
          const gl_drag_settings d{c.id, 0, {0, 0.1, 0}, {1, 2.5, 1}};
          gl_sim_drag(s, &d);
          break;
        }
        case Command::EndDrag: gl_sim_end_drag(s); break;
        case Command::Reset: gl_sim_reset_character(s, c.id); break;
        case Command::Remove: gl_sim_remove_character(s, c.id); break;
        case Command::Add: add(static_cast<int>(c.a), static_cast<int>(c.b)); break;
        case Command::AutoReset: gl_sim_set_auto_reset(s, c.a); break;
      }
    }
    gl_sim_step(s, 1);
  }
  std::string hash = gl_sim_state_hash(s);
  gl_sim_destroy(s);
  return hash;
}

// The same run through the C++ API, stepped in whole stretches between commands.
std::string replayThroughTheCppApi(int threads, uint32_t seed, Mode mode) {
  Simulation sim(threads, seed, gaitlab::sim::kCrowdShards);  // as the C ABI makes the demo's
  sim.setMode(mode);
  gaitlab::gait::Goal lastGoal[2] = {{Simulation::cruiseSpeed(Character::Biped), 0},
                                     {Simulation::cruiseSpeed(Character::Quadruped), 0}};
  const auto add = [&](Crowd crowd, int count) {
    const int added = sim.addCharacters(crowd, count);
    for (int i = sim.characterCount() - added; i < sim.characterCount(); ++i)
      sim.setGoal(i, lastGoal[static_cast<int>(sim.kindOf(i))]);
  };
  add(Crowd::Mixed, 6);
  int at = 0;
  for (const Command& c : commandLog()) {
    sim.step(c.step - at);
    at = c.step;
    switch (c.type) {
      case Command::Goal:
        if (c.id < 0 || sim.indexOf(c.id) >= 0) sim.setGoal(c.id < 0 ? -1 : sim.indexOf(c.id), {c.a, c.b});
        if (c.id < 0) lastGoal[0] = lastGoal[1] = {c.a, c.b};
        break;
      case Command::Throw: sim.throwBox({-3, 1.2, 2}, {9, 1, -1}, 0.12); break;
      case Command::Drag: sim.drag(c.id, 0, {0, 0.1, 0}, {1, 2.5, 1}); break;
      case Command::EndDrag: sim.endDrag(); break;
      case Command::Reset: sim.resetCharacter(c.id); break;
      case Command::Remove: sim.removeCharacter(c.id); break;
      case Command::Add:
        add(c.a == GL_LAYOUT_ALTERNATING ? Crowd::Mixed
            : c.a == GL_KIND_BIPED      ? Crowd::Bipeds
                                        : Crowd::Quadrupeds,
            static_cast<int>(c.b));
        break;
      case Command::AutoReset: sim.setAutoReset(c.a); break;
    }
  }
  sim.step(kSteps - at);
  EXPECT_EQ(sim.characterCount(), 7);
  EXPECT_EQ(sim.indexOf(3), -1) << "removed";
  EXPECT_GE(sim.indexOf(3 | 1 << gaitlab::sim::IdPool::kSlotBits), 0) << "added in 3's slot";
  EXPECT_GE(sim.indexOf(7), 0) << "added";
  EXPECT_EQ(sim.indexOf(6), -1) << "a box, not a character";
  return sim.stateHash();
}

}  // namespace

TEST(Replay, APageRunReplaysFromSeedLayoutAndCommandLog) {
  const std::string once = replayThroughTheCAbi(1, 21);
  EXPECT_EQ(replayThroughTheCAbi(1, 21), once) << "the same run twice";
  EXPECT_EQ(replayThroughTheCAbi(2, 21), once) << "on two threads, as the page runs it";
  for (Mode mode : {Mode::Serial, Mode::Controller, Mode::Full})
    EXPECT_EQ(replayThroughTheCppApi(2, 21, mode), once)
        << "the C++ API in " << gaitlab::sim::modeName(mode) << " mode";
}
