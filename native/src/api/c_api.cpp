// The C ABI (c_api.h) over sim::Simulation.
#include "api/c_api.h"

#include <cmath>
#include <string>

#include <algorithm>

#include "gait/heading.h"
#include "sim/simulation.h"

using gaitlab::sim::Kind;
using gaitlab::sim::Simulation;

namespace {
Simulation* sim(void* handle) { return static_cast<Simulation*>(handle); }
thread_local std::string g_string;  // backing store for returned strings
}  // namespace

extern "C" {

const char* gl_version(void) { return GAITLAB_VERSION; }

void* gl_sim_create(int threads, uint32_t seed) {
  if (threads < 1) threads = 1;
  if (threads > GL_MAX_THREADS) threads = GL_MAX_THREADS;
  return new Simulation(threads, seed);
}

void gl_sim_destroy(void* s) { delete sim(s); }

int gl_sim_spawn(void* s, int kind, double x, double z, double heading) {
  if (kind < GL_KIND_BIPED || kind > GL_KIND_BOX) return -1;
  return sim(s)->spawn(static_cast<Kind>(kind), x, z, heading);
}

void gl_sim_demo_scene(void* s, int characters) { sim(s)->demoScene(characters); }

void gl_sim_step(void* s, int steps) { sim(s)->step(steps); }

double gl_sim_time(void* s) { return sim(s)->time(); }

uint32_t gl_sim_step_index(void* s) { return sim(s)->stepIndex(); }

int gl_sim_body_count(void* s) { return sim(s)->bodyCount(); }

int gl_sim_threads(void* s) { return sim(s)->threads(); }

const char* gl_sim_state_hash(void* s) {
  g_string = sim(s)->stateHash();
  return g_string.c_str();
}

const void* gl_sim_render_buffer(void* s) { return sim(s)->renderBuffer(); }

// ---- Interaction: the demo page's commands (issue 5) --------------------------------------------

int gl_sim_set_goal(void* s, int id, double speed, double turn_rate) {
  const gaitlab::gait::Goal goal{speed, turn_rate};
  if (id == -1) {
    sim(s)->setGoal(-1, goal);
    return 0;
  }
  const int i = sim(s)->indexOf(id);
  if (i < 0) return -1;
  sim(s)->setGoal(i, goal);
  return 0;
}

int gl_sim_throw_box(void* s, double x, double y, double z, double vx, double vy, double vz,
                     double half) {
  half = std::clamp(half, 0.03, 0.5);
  return sim(s)->throwBox({x, y, z}, {vx, vy, vz}, half);
}

int gl_sim_drag(void* s, int id, int segment, double lx, double ly, double lz, double tx,
                double ty, double tz) {
  return sim(s)->drag(id, segment, {lx, ly, lz}, {tx, ty, tz}) ? 0 : -1;
}

void gl_sim_end_drag(void* s) { sim(s)->endDrag(); }

int gl_sim_reset_character(void* s, int id) { return sim(s)->resetCharacter(id) ? 0 : -1; }

int gl_sim_remove_character(void* s, int id) { return sim(s)->removeCharacter(id) ? 0 : -1; }

void gl_sim_set_auto_reset(void* s, double seconds) {
  sim(s)->setAutoReset(std::max(0.0, seconds));
}

int gl_sim_character_count(void* s) { return sim(s)->characterCount(); }

int gl_sim_character_info(void* s, double* out, int capacity) {
  Simulation& S = *sim(s);
  const int n = S.characterCount();
  for (int i = 0; i < std::min(n, capacity); ++i) {
    const gaitlab::physics::Character& c = S.character(i);
    const auto root = c.segmentState(c.morphology().legFrames[0]);
    double* o = out + i * GL_INFO_FIELDS;
    o[GL_INFO_ID] = S.idOf(i);
    o[GL_INFO_KIND] = static_cast<int>(S.kindOf(i));
    o[GL_INFO_X] = root.position.x();
    o[GL_INFO_Y] = root.position.y();
    o[GL_INFO_Z] = root.position.z();
    o[GL_INFO_HEADING] = gaitlab::gait::headingOf(root.orientation);
    o[GL_INFO_SPEED] = std::hypot(root.linearVelocity.x(), root.linearVelocity.z());
    o[GL_INFO_FALLEN] = S.fallen(i) ? 1 : 0;
    o[GL_INFO_FALLEN_SECONDS] = S.fallenSeconds(i);
    o[GL_INFO_GOAL_SPEED] = S.controller(i).goal().speed;
    o[GL_INFO_GOAL_TURN] = S.controller(i).goal().turnRate;
    o[GL_INFO_PHASE] = S.controller(i).player().phase();
  }
  return n;
}

}  // extern "C"
