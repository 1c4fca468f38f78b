// The demo page's commands through the C ABI (c_api.h, "Interaction"): thrown boxes hit
// characters, the drag spring pulls a body towards the pointer, reset puts a character back on
// its feet where it was, remove and add keep the render buffer consistent, fallen characters are
// detected and reset automatically when asked.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "api/c_api.h"
#include "sim/render_buffer.h"

namespace {

struct Info {
  double v[GL_INFO_FIELDS];
  double operator[](int f) const { return v[f]; }
};

std::vector<Info> infos(void* sim) {
  std::vector<Info> out(gl_sim_character_count(sim));
  gl_sim_character_info(sim, out.empty() ? nullptr : out[0].v, static_cast<int>(out.size()));
  return out;
}

const gaitlab::BodyInfo* bodyInfo(void* sim) {
  const auto* h = static_cast<const gaitlab::RenderHeader*>(gl_sim_render_buffer(sim));
  return reinterpret_cast<const gaitlab::BodyInfo*>(reinterpret_cast<const unsigned char*>(h) + h->info);
}

// gl_sim_throw_box and gl_sim_drag with their settings structs filled from positional values.
int throwBox(void* sim, double x, double y, double z, double vx, double vy, double vz, double half) {
  const gl_throw_settings t{{x, y, z}, {vx, vy, vz}, half};
  return gl_sim_throw_box(sim, &t);
}

int drag(void* sim, int id, int segment, double lx, double ly, double lz, double tx, double ty, double tz) {
  const gl_drag_settings d{id, segment, {lx, ly, lz}, {tx, ty, tz}};
  return gl_sim_drag(sim, &d);
}

}  // namespace

TEST(Interaction, CharacterInfoDescribesEachCharacter) {
  void* sim = gl_sim_create(1, 1);
  const int a = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  const int b = gl_sim_spawn(sim, GL_KIND_QUADRUPED, 5, 0, 1.0);
  gl_sim_step(sim, 1);
  const auto info = infos(sim);
  ASSERT_EQ(info.size(), 2u);
  EXPECT_EQ(info[0][GL_INFO_ID], a);
  EXPECT_EQ(info[1][GL_INFO_ID], b);
  EXPECT_EQ(info[0][GL_INFO_KIND], GL_KIND_BIPED);
  EXPECT_EQ(info[1][GL_INFO_KIND], GL_KIND_QUADRUPED);
  EXPECT_NEAR(info[0][GL_INFO_X], 0, 0.2);
  EXPECT_GT(info[0][GL_INFO_Y], 0.5);  // a standing biped's pelvis
  EXPECT_NEAR(info[1][GL_INFO_HEADING], 1.0, 0.05);
  EXPECT_EQ(info[0][GL_INFO_FALLEN], 0);
  // A smaller capacity writes fewer records but still tells the count.
  Info one;
  EXPECT_EQ(gl_sim_character_info(sim, one.v, 1), 2);
  gl_sim_destroy(sim);
}

TEST(Interaction, GoalsReachOneOrAllCharacters) {
  void* sim = gl_sim_create(1, 1);
  const int a = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  gl_sim_spawn(sim, GL_KIND_QUADRUPED, 5, 0, 0);
  EXPECT_EQ(gl_sim_set_goal(sim, -1, 0.7, 0.1), 0);
  EXPECT_EQ(gl_sim_set_goal(sim, a, 1.2, -0.2), 0);
  EXPECT_EQ(gl_sim_set_goal(sim, 999, 1, 0), GL_ERR_NO_CHARACTER);
  const auto info = infos(sim);
  EXPECT_EQ(info[0][GL_INFO_GOAL_SPEED], 1.2);
  EXPECT_EQ(info[0][GL_INFO_GOAL_TURN], -0.2);
  EXPECT_EQ(info[1][GL_INFO_GOAL_SPEED], 0.7);
  gl_sim_destroy(sim);
}

TEST(Interaction, ThrownBoxHitsACharacter) {
  // Two identical runs but for a box thrown at the character's chest in one of them.
  const auto run = [](bool hit) {
    void* sim = gl_sim_create(1, 1);
    gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
    gl_sim_step(sim, 1);
    const double y = infos(sim)[0][GL_INFO_Y];
    if (hit) EXPECT_GE(throwBox(sim, -3, y + 0.3, 0, 15, 0, 0, 0.12), 0);
    gl_sim_step(sim, 30);  // 0.25 s: the box crosses 3 m in 0.2 s
    const Info after = infos(sim)[0];
    gl_sim_destroy(sim);
    return after;
  };
  const Info quiet = run(false), hit = run(true);
  EXPECT_GT(hit[GL_INFO_X] - quiet[GL_INFO_X], 0.05) << "the box pushed the character along +x";
}

TEST(Interaction, ThrownBoxesAreCappedAndLeaveTheRenderBuffer) {
  void* sim = gl_sim_create(1, 1);
  gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  const int before = gl_sim_body_count(sim);
  for (int i = 0; i < 40; ++i) throwBox(sim, i, 1, 5, 0, 0, 0, 0.1);
  EXPECT_EQ(gl_sim_body_count(sim), before + 32);
  gl_sim_step(sim, 1);
  // The character's bodies are still first and still its own.
  for (int i = 0; i < before; ++i) EXPECT_EQ(bodyInfo(sim)[i].owner, 0);
  for (int i = before; i < before + 32; ++i) EXPECT_EQ(bodyInfo(sim)[i].owner, -1);
  gl_sim_destroy(sim);
}

TEST(Interaction, DragPullsTheBodyTowardsTheTargetUntilReleased) {
  void* sim = gl_sim_create(1, 1);
  const int id = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  gl_sim_step(sim, 1);
  const Info start = infos(sim)[0];
  // Segment 0 is the root leg frame (the pelvis): pull it 1.5 m sideways.
  ASSERT_EQ(drag(sim, id, 0, 0, 0, 0, start[GL_INFO_X] + 1.5, start[GL_INFO_Y], start[GL_INFO_Z]), 0);
  EXPECT_EQ(drag(sim, id, 999, 0, 0, 0, 0, 0, 0), GL_ERR_ARGUMENT);
  EXPECT_EQ(drag(sim, 999, 0, 0, 0, 0, 0, 0, 0), GL_ERR_NO_CHARACTER);
  gl_sim_step(sim, 120);
  const Info pulled = infos(sim)[0];
  EXPECT_GT(pulled[GL_INFO_X] - start[GL_INFO_X], 0.7);
  EXPECT_TRUE(std::isfinite(pulled[GL_INFO_Y]));
  gl_sim_end_drag(sim);
  gl_sim_destroy(sim);
}

TEST(Interaction, FallenCharactersAreDetectedAndResetWhereTheyLie) {
  void* sim = gl_sim_create(1, 1);
  const int id = gl_sim_spawn(sim, GL_KIND_BIPED, 2, 3, 0);
  // Knock it over: a hard pull of the pelvis sideways and down.
  drag(sim, id, 0, 0, 0, 0, 4, -1, 3);
  gl_sim_step(sim, 120);
  gl_sim_end_drag(sim);
  gl_sim_step(sim, 60);
  Info down = infos(sim)[0];
  ASSERT_EQ(down[GL_INFO_FALLEN], 1) << "pulled to the ground, it counts as fallen";
  EXPECT_GT(down[GL_INFO_FALLEN_SECONDS], 0);

  const int bodies = gl_sim_body_count(sim);
  ASSERT_EQ(gl_sim_reset_character(sim, id), 0);
  EXPECT_EQ(gl_sim_reset_character(sim, 999), GL_ERR_NO_CHARACTER);
  gl_sim_step(sim, 1);
  const Info up = infos(sim)[0];
  EXPECT_EQ(up[GL_INFO_ID], id);
  EXPECT_EQ(up[GL_INFO_FALLEN], 0);
  EXPECT_GT(up[GL_INFO_Y], 0.5);
  EXPECT_NEAR(up[GL_INFO_X], down[GL_INFO_X], 0.05) << "respawned where it lay";
  EXPECT_NEAR(up[GL_INFO_Z], down[GL_INFO_Z], 0.05);
  EXPECT_EQ(gl_sim_body_count(sim), bodies);

  // Automatic reset: knocked over again, it is back up within the set time.
  gl_sim_set_auto_reset(sim, 0.5);
  drag(sim, id, 0, 0, 0, 0, up[GL_INFO_X] + 2, -1, up[GL_INFO_Z]);
  bool wasDown = false, backUp = false;
  for (int i = 0; i < 400 && !backUp; ++i) {
    gl_sim_step(sim, 1);
    const Info now = infos(sim)[0];
    if (now[GL_INFO_FALLEN] == 1) {
      wasDown = true;
      gl_sim_end_drag(sim);
    } else if (wasDown) {
      backUp = true;
    }
  }
  EXPECT_TRUE(wasDown);
  EXPECT_TRUE(backUp);
  gl_sim_destroy(sim);
}

TEST(Interaction, RemovingACharacterPacksTheRenderBuffer) {
  void* sim = gl_sim_create(1, 1);
  const int a = gl_sim_spawn(sim, GL_KIND_BIPED, 0, 0, 0);
  const int box = gl_sim_spawn(sim, GL_KIND_BOX, 3, 3, 0);
  const int b = gl_sim_spawn(sim, GL_KIND_QUADRUPED, 5, 0, 0);
  ASSERT_GE(box, 0);
  const int all = gl_sim_body_count(sim);
  int bodiesOfA = 0;
  for (int i = 0; i < all; ++i) bodiesOfA += bodyInfo(sim)[i].owner == a;
  ASSERT_EQ(gl_sim_remove_character(sim, a), 0);
  EXPECT_EQ(gl_sim_remove_character(sim, a), GL_ERR_NO_CHARACTER);
  EXPECT_EQ(gl_sim_character_count(sim), 1);
  EXPECT_EQ(gl_sim_body_count(sim), all - bodiesOfA);
  EXPECT_EQ(bodyInfo(sim)[0].owner, -1);  // the box moved up to the front
  for (int i = 1; i < gl_sim_body_count(sim); ++i) EXPECT_EQ(bodyInfo(sim)[i].owner, b);
  gl_sim_step(sim, 10);
  EXPECT_EQ(infos(sim)[0][GL_INFO_ID], b);
  // Adding after a removal gets a fresh id.
  EXPECT_GT(gl_sim_spawn(sim, GL_KIND_BIPED, -4, 0, 0), b);
  gl_sim_destroy(sim);
}
