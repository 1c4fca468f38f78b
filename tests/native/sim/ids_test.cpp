// Stable generational ids (sim/ids.h): a removed thing's id is never given to another, a stale
// id is refused everywhere a character is named, and a character keeps its id for its life
// (through resets and the removal of others) while its index shifts.
#include <gtest/gtest.h>

#include <set>

#include "api/c_api.h"
#include "api/handles.h"
#include "sim/ids.h"
#include "sim/simulation.h"

using gaitlab::sim::IdPool;
using gaitlab::gait::Character;
using gaitlab::sim::Simulation;

TEST(IdPool, FreshIdsCountUpAndAFreedSlotComesBackWithANewGeneration) {
  IdPool ids;
  EXPECT_EQ(ids.create(10), 0);
  EXPECT_EQ(ids.create(11), 1);
  EXPECT_EQ(ids.create(12), 2);
  ids.destroy(1);
  EXPECT_FALSE(ids.live(1));
  EXPECT_EQ(ids.value(1), -1);
  const int again = ids.create(13);
  EXPECT_NE(again, 1);
  EXPECT_EQ(IdPool::slotOf(again), 1) << "the freed slot is reused";
  EXPECT_EQ(IdPool::generationOf(again), 1);
  EXPECT_EQ(ids.value(again), 13);
  EXPECT_EQ(ids.value(1), -1) << "the old id still names nothing";
  EXPECT_EQ(ids.value(2), 12);
  EXPECT_FALSE(ids.live(-1));
  EXPECT_FALSE(ids.live(7)) << "a slot never handed out";
}

TEST(IdPool, NoIdIsEverGivenTwiceEvenWhenASlotsGenerationsRunOut) {
  IdPool ids;
  std::set<int> seen;
  // Every generation of slot 0, and then some: the slot retires and a new one takes over.
  int last = -1;
  for (int i = 0; i < IdPool::kGenerations + 10; ++i) {
    last = ids.create(i);
    ASSERT_GE(last, 0);
    ASSERT_TRUE(seen.insert(last).second) << "id " << last << " given twice";
    ids.destroy(last);
  }
  EXPECT_EQ(IdPool::slotOf(last), 1) << "slot 0 retired after its last generation";
  EXPECT_EQ(IdPool::generationOf(last), 9);
}

TEST(CharacterIds, RemovingAndAddingNeverGivesAnOldIdToANewCharacter) {
  Simulation sim(1, 3);
  ASSERT_EQ(sim.addCharacters(gaitlab::sim::Crowd::Mixed, 4), 4);
  std::set<int> given;
  for (int i = 0; i < sim.characterCount(); ++i) {
    EXPECT_EQ(sim.idOf(i), i) << "a fresh scene's characters are 0, 1, 2...";
    given.insert(sim.idOf(i));
  }
  // Remove and add over and over, thrown boxes in between (they take ids too).
  for (int round = 0; round < 20; ++round) {
    const int victim = sim.idOf(round % sim.characterCount());
    ASSERT_TRUE(sim.removeCharacter(victim));
    EXPECT_EQ(sim.indexOf(victim), -1);
    const int box = sim.throwBox({0, 2, 0}, {0, 0, 1}, 0.1);
    ASSERT_GE(box, 0);
    EXPECT_TRUE(given.insert(box).second) << "box id " << box << " given before";
    const int fresh = sim.spawn(round % 2 ? Character::Biped : Character::Quadruped, 10.0 + round, 0, 0);
    ASSERT_GE(fresh, 0);
    EXPECT_TRUE(given.insert(fresh).second) << "character id " << fresh << " given before";
    EXPECT_EQ(sim.idOf(sim.indexOf(fresh)), fresh);
    if (round % 5 == 4) sim.step(1);
  }
  EXPECT_EQ(sim.characterCount(), 4);
}

TEST(CharacterIds, AStaleIdIsRefusedByEveryCommand) {
  void* s = gl_sim_create(1, 1);
  ASSERT_EQ(gl_sim_add_characters(s, GL_LAYOUT_ALTERNATING, 3), 3);
  ASSERT_EQ(gl_sim_remove_character(s, 1), 0);
  ASSERT_EQ(gl_sim_add_characters(s, GL_KIND_BIPED, 1), 1);
  const int fresh = gaitlab::api::simulationOf(s).idOf(2);  // the characters added last come last
  EXPECT_NE(fresh, 1);
  EXPECT_EQ(IdPool::slotOf(fresh), 1) << "the new character took the freed slot, a generation on";
  // Id 1 named the removed character; the new one in its slot must not answer to it.
  const gl_drag_settings staleDrag{1, 0, {0, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(gl_sim_set_goal(s, 1, 1.0, 0.0), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_drag(s, &staleDrag), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_reset_character(s, 1), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_remove_character(s, 1), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_get_params(s, 1), nullptr);
  EXPECT_EQ(gl_sim_character_count(s), 3);
  // Ids that never named anything, and a prop's id, name no character either.
  EXPECT_EQ(gl_sim_set_goal(s, 12345, 1.0, 0.0), GL_ERR_NO_CHARACTER);
  const int box = gl_sim_spawn(s, GL_KIND_BOX, 0, 5, 0);
  ASSERT_GE(box, 0);
  EXPECT_EQ(gl_sim_reset_character(s, box), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_set_goal(s, fresh, 0.5, 0.0), 0);
  gl_sim_destroy(s);
}

TEST(CharacterIds, ACharacterKeepsItsIdThroughResetsAndOthersRemovals) {
  Simulation sim(1, 5);
  ASSERT_EQ(sim.addCharacters(gaitlab::sim::Crowd::Mixed, 5), 5);
  sim.step(30);
  ASSERT_TRUE(sim.resetCharacter(3));
  EXPECT_EQ(sim.indexOf(3), 3);
  ASSERT_TRUE(sim.removeCharacter(0));
  ASSERT_TRUE(sim.removeCharacter(2));
  // Indices shift down; ids do not.
  EXPECT_EQ(sim.indexOf(1), 0);
  EXPECT_EQ(sim.indexOf(3), 1);
  EXPECT_EQ(sim.indexOf(4), 2);
  EXPECT_EQ(sim.kindOf(sim.indexOf(3)), Character::Quadruped);
  EXPECT_EQ(sim.kindOf(sim.indexOf(4)), Character::Biped);
  for (int i = 0; i < sim.characterCount(); ++i) EXPECT_EQ(sim.indexOf(sim.idOf(i)), i);
}
