// The crowd simulation: the characters, loose props, the Bullet world(s) they live in, the
// fixed-step loop (thesis §3.2: 120 Hz), the thread pool and the execution mode, per-step timing,
// the state hash, and the render buffer shared with the browser (render_buffer.h).
//
// Physics shards. The crowd's physics may be split over S independent Bullet worlds ("shards"),
// fixed when the simulation is made. Characters never collide with each other (physics/world.h),
// so a character needs only the ground and the props near it; a prop lives in the shard of the
// character nearest to it and moves between shards as that changes (between steps, in a fixed
// order). S is an input of the scene like the seed: the execution mode and the thread count only
// decide which thread steps which shard, never what a shard computes, which is why every mode and
// thread count gives the bit-identical state (docs/parallel.md).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "body/morphology.h"
#include "gait/controller.h"
#include "physics/character.h"
#include "physics/world.h"
#include "sim/render_buffer.h"
#include "sim/thread_pool.h"

namespace gaitlab::sim {

enum class Kind { Biped = 0, Quadruped = 1, Box = 2 };

// Who makes up a benchmark crowd (crowdScene): thesis §4.1 measured bipeds and quadrupeds apart.
enum class Crowd { Bipeds, Quadrupeds, Mixed };

// How a fixed step uses the thread pool (chosen at run time; docs/parallel.md):
//   Serial      everything on the calling thread;
//   Controller  the thesis's mode (§3.1, §4.1): the controller loop is a parallel-for over the
//               characters in T contiguous chunks, the first N mod T one larger (§4.3); physics
//               is serial;
//   Full        the controller loop as above, then the physics shards in parallel, each shard
//               taken by the next free thread (ThreadPool::forEach).
enum class Mode { Serial = 0, Controller = 1, Full = 2 };
const char* modeName(Mode mode);
bool parseMode(const std::string& name, Mode* out);

// Wall-clock seconds of one fixed step. `controller` is the thesis's measure (§4.1: "from before
// the start of the first thread until all threads have finished"), `physics` the same for the
// Bullet step and contact update, `step` the whole fixed step (both, plus moving props between
// shards), render publishing excluded as the thesis excluded rendering.
struct StepTiming {
  double controller = 0, physics = 0, step = 0;
};

class Simulation {
 public:
  static constexpr int kRenderCapacity = 16384;  // bodies

  // `shards` >= 1 independent Bullet worlds (see above); 1 is a single world.
  Simulation(int threads, uint32_t seed, int shards = 1);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Spawns a character standing at (x, z) or a box dropped from 1.5 m there. Returns its id,
  // or -1 if the render buffer has no room left.
  int spawn(Kind kind, double x, double z, double heading);
  // `characters` figures on a grid, alternating biped and quadruped, plus a few boxes.
  void demoScene(int characters);
  // The thesis experiment's crowd (§4.1, Figures 4.5, 4.6): `characters` bipeds, quadrupeds or
  // both (alternating) on a square grid `spacing` metres apart, centred on the origin, all facing
  // +z; no props. Shard s gets the s-th contiguous chunk of the grid (rows), so neighbours share
  // a world. Every character walks forward at its type's cruise speed (the benchmark measures
  // characters that walk), and the crowd starts out of step: character i at gait phase
  // frac(i / golden ratio), as a crowd would be, rather than 100 characters whose feet all strike
  // on the same step (docs/parallel.md, the p99).
  void crowdScene(Crowd crowd, int characters, double spacing);
  // The speed each type's preset is tuned and benchmarked for (bench/walking.mjs; also the demo's
  // start goals, through gl_cruise_speed): a 0.49 m dog walks slower than a 1.8 m human.
  static double cruiseSpeed(Kind kind) { return kind == Kind::Biped ? 1.0 : 0.4; }

  void setMode(Mode mode) { mode_ = mode; }
  // Bullet's own constraint sweep instead of the faster one that computes the same
  // (physics/solver.h), in every shard: for tests and measurements.
  void setFastSolver(bool on) {
    for (auto& w : worlds_) w->setFastSolver(on);
  }
  // Solver batches so far over every shard, and how many the fast sweep solved.
  std::pair<long, long> solverBatches() const {
    std::pair<long, long> n{0, 0};
    for (const auto& w : worlds_) {
      const auto b = w->solverBatches();
      n.first += b.first;
      n.second += b.second;
    }
    return n;
  }
  Mode mode() const { return mode_; }
  int shards() const { return static_cast<int>(worlds_.size()); }
  // The shard character i lives in, and that shard's physics world.
  int shardOf(int i) const { return agents_[i]->shard; }
  const physics::World& world(int shard) const { return *worlds_[shard]; }
  // Timing of the last fixed step.
  const StepTiming& lastStep() const { return lastStep_; }
  // How many times the controller has run for character i (each step must run it exactly once).
  uint64_t controllerUpdates(int i) const { return agents_[i]->updates; }
  void step(int steps);

  double time() const { return stepIndex_ * physics::kFixedStep; }
  uint32_t stepIndex() const { return stepIndex_; }
  int bodyCount() const { return static_cast<int>(renderBodies_.size()); }
  int threads() const { return pool_.size(); }
  // The simulation's thread pool (the Bullet-multithreading probe runs Bullet's tasks on it).
  ThreadPool& pool() { return pool_; }
  int characterCount() const { return static_cast<int>(agents_.size()); }
  // The index (0..characterCount()-1) of the character spawn() returned `id` for, or -1 when
  // `id` names no character (a box, or nothing spawned).
  int characterIndex(int id) const { return indexOf(id); }
  int characterId(int index) const { return agents_[index]->id; }
  const physics::Character& character(int i) const { return *agents_[i]->body; }
  physics::Character& character(int i) { return *agents_[i]->body; }
  double groundHeight(double x, double z) const { return worlds_[0]->terrainHeight(x, z); }

  // The ground (physics/terrain.h): flat (the default), slope or bumps, the same in every
  // physics shard; the bumps are drawn from the simulation's seed. Characters already in the
  // scene are re-placed standing on the new ground where their leg frames are (resetCharacter:
  // same gait and goal), props are lifted out of it if the new ground is higher.
  void setTerrain(physics::TerrainKind kind);
  // The same with a terrain made elsewhere (tests: a heightfield with its relief scaled to 0).
  void setTerrain(std::shared_ptr<const physics::Terrain> terrain);
  const physics::Terrain& terrain() const { return *terrain_; }
  // Wall-clock seconds spent so far in the controller loop (thesis timing: from before the
  // first thread starts until the last is done) and in the physics step.
  double controllerSeconds() const { return controllerSeconds_; }
  double physicsSeconds() const { return physicsSeconds_; }
  gait::Controller& controller(int i) { return agents_[i]->controller; }
  const gait::Controller& controller(int i) const { return agents_[i]->controller; }
  // The joint torques the controller wrote in the last step (controller.h convention).
  const std::vector<Eigen::Vector3d>& lastTorques(int i) const { return agents_[i]->torques; }
  // Steering (beyond the thesis): one character, or all with i = -1.
  void setGoal(int i, const gait::Goal& goal);

  // 64-bit FNV-1a over the exact bits of every body's transform and velocities, as 16 hex digits.
  std::string stateHash() const;

  const RenderHeader* renderBuffer() const { return header_; }

  // ---- Interaction (the demo page, issue 5) --------------------------------------------------
  // Everything a user does to a running scene. The sim worker applies these between fixed steps
  // (it queues its commands and applies them at the start of the next step), so each one acts at
  // a known step index and a run can be replayed from (seed, scene, command log).

  // Index in 0..characterCount()-1 of the character with id `id`, or -1.
  int indexOf(int id) const;
  int idOf(int index) const { return agents_[index]->id; }
  Kind kindOf(int index) const { return agents_[index]->kind; }
  // Fallen now (walk_trial.h's hasFallen, evaluated after every step), and for how long.
  bool fallen(int index) const { return agents_[index]->fallenSince >= 0; }
  double fallenSeconds(int index) const {
    return fallen(index) ? time() - agents_[index]->fallenSince : 0.0;
  }

  // A box of half size `half` thrown from `from` with velocity `velocity` (m/s). It collides
  // with the ground, props and characters. At most kMaxThrown thrown boxes exist: the oldest
  // goes when another is thrown, so a user who keeps clicking does not slow the scene down.
  static constexpr int kMaxThrown = 32;
  int throwBox(const Eigen::Vector3d& from, const Eigen::Vector3d& velocity, double half);

  // A spring pulling point `local` (body frame of the character's segment `segment`, metres)
  // towards `target` (world), applied every step until endDrag(). One drag at a time: a pointer.
  // Returns false if the character or segment does not exist.
  bool drag(int id, int segment, const Eigen::Vector3d& local, const Eigen::Vector3d& target);
  void endDrag() { drag_.id = -1; }

  // Replaces character `id` by a new one standing where its leg frame is now (on the ground,
  // facing its current heading), with the same gait parameters and goal. Returns false if no
  // such character exists.
  bool resetCharacter(int id);
  // Removes character `id` (its bodies leave the world and the render buffer).
  bool removeCharacter(int id);
  // Characters fallen for at least `seconds` are reset automatically; 0 turns this off.
  void setAutoReset(double seconds) { autoResetSeconds_ = seconds; }
  double autoReset() const { return autoResetSeconds_; }

 private:
  struct RenderBody {
    btRigidBody* body;
    BodyInfo info;
  };
  void addRenderBody(btRigidBody* body, const BodyInfo& info);
  void publish();  // writes transforms into the back buffer and flips it to the front
  int spawnCharacter(Kind kind, double x, double z, double heading, int shard);
  void stepShard(int shard);  // Bullet step and foot contacts of one shard
  void rehomeProps();         // moves each prop into the shard of its nearest character
  int nearestShard(double x, double z, int fallback) const;  // shard of the nearest character
  // Height at which a character placed at (x, z) facing `heading` stands with its rest pose's
  // soles on the ground: the highest ground under any sole touches it, so no foot starts inside
  // uneven ground (on flat ground: the ground height, as always).
  double standingHeight(const physics::World& world, const body::Morphology& m, double x,
                        double z, double heading) const;

  // The physics shards; one unless asked otherwise. Each is a complete Bullet world with its own
  // ground, dispatcher and solver, so shards can be stepped concurrently without sharing state.
  std::vector<std::unique_ptr<physics::World>> worlds_;
  std::shared_ptr<const physics::Terrain> terrain_;  // shared by every shard
  body::Morphology biped_, quadruped_;
  // A character: its bodies in the world, its controller, and the buffers the controller reads
  // and writes, allocated once so the per-step loop allocates nothing (defect 10).
  struct Agent {
    Agent(physics::World& world, const body::Morphology& m, const Eigen::Vector3d& origin,
          double heading);
    std::unique_ptr<physics::Character> body;
    gait::Controller controller;
    std::vector<gait::BodyState> state;
    std::vector<Eigen::Vector3d> torques;
    bool footContact[gait::kMaxLegs] = {false, false, false, false};
    const physics::World* world;
    int id = -1;
    Kind kind = Kind::Biped;
    bool down = false;        // hasFallen after the last step (set in its shard's task)
    double fallenSince = -1;  // simulated time it was first seen fallen; -1 = standing
    int shard = 0;
    uint64_t updates = 0;
  };
  // A loose body (a dropped or thrown box) and the shard it lives in.
  struct Prop {
    btRigidBody* body;
    int shard;
  };
  void control(Agent& agent);
  std::vector<std::unique_ptr<Agent>> agents_;
  std::vector<RenderBody> renderBodies_;
  std::vector<Prop> props_;
  // Agents of each shard in spawn order, for the per-shard contact update.
  std::vector<std::vector<Agent*>> shardAgents_;
  ThreadPool pool_;
  Mode mode_ = Mode::Controller;
  StepTiming lastStep_;
  uint32_t seed_;

  // Interaction state (see the section above).
  struct Drag {
    int id = -1;  // character; -1 = no drag
    int segment = 0;
    Eigen::Vector3d local = Eigen::Vector3d::Zero(), target = Eigen::Vector3d::Zero();
  };
  Drag drag_;
  std::vector<btRigidBody*> thrown_;  // oldest first
  double autoResetSeconds_ = 0;
  void applyDrag();
  void updateFallen();
  // Drops the render entries of `bodies` and packs the rest (ids and order kept).
  void removeRenderBodies(const std::vector<btRigidBody*>& bodies);
  uint32_t stepIndex_ = 0;
  double controllerSeconds_ = 0, physicsSeconds_ = 0;
  int nextId_ = 0;

  std::vector<unsigned char> renderMemory_;  // header + 2 matrix buffers + body info
  RenderHeader* header_ = nullptr;
  float* matrices_[2] = {nullptr, nullptr};
  BodyInfo* info_ = nullptr;
};

}  // namespace gaitlab::sim
