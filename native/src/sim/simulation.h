// The crowd simulation: the public face of the sim, a thin owner of its parts, each its own
// concept and file (as Box2D v3 splits its world into body, contact, solver, island...):
//
//   agent.h            a character: its bodies, its controller and the controller's buffers;
//   ids.h              stable generational ids naming characters and props;
//   scene_layout.h     where characters stand: the demo page's layout, the benchmark's grid;
//   physics_shards.h   the Bullet world(s), and props moving between them;
//   stepping.h         the fixed step (thesis §3.2: 120 Hz), execution modes, timing;
//   render_publisher.h the render buffer shared with the browser (render_buffer.h);
//   state_hash.h       the bit-exact state hash;
//   interaction.h      the demo page's commands: goals, drag, thrown boxes, reset, remove.
//
// Characters are named two ways: by id (stable for the character's life, never reused: what
// the page and the C ABI use) and by index 0..characterCount()-1 (their order in the controller
// loop and in gl_sim_character_info, which shifts when a character is removed: what loops over
// the crowd use). indexOf and idOf convert.
#pragma once
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "body/morphology.h"
#include "gait/controller.h"
#include "physics/character.h"
#include "physics/world.h"
#include "sim/agent.h"
#include "sim/ids.h"
#include "sim/interaction.h"
#include "sim/intercept.h"
#include "sim/physics_shards.h"
#include "sim/render_buffer.h"
#include "sim/render_publisher.h"
#include "sim/scene_layout.h"
#include "sim/stepping.h"
#include "sim/thread_pool.h"
#include "sim/wander.h"

namespace gaitlab::sim {

class Simulation {
 public:
  static constexpr int kRenderCapacity = RenderPublisher::kCapacity;  // bodies

  // `shards` >= 1 independent Bullet worlds (physics_shards.h); 1 is a single world.
  Simulation(int threads, uint32_t seed, int shards = 1);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // ---- Scenes ---------------------------------------------------------------------------------
  // Spawns a character standing at (x, z), or a box (a prop, 0.3 m, 4 kg) dropped from 1.5 m
  // there. Returns its id, or -1 if the render buffer has no room left.
  int spawn(Character kind, double x, double z, double heading);
  // The body characters of `kind` spawned from now on are built with: a creature file's
  // (body/creature.h, `gaitlab walk --creature`) instead of the shipped one. It must have the
  // kind's leg frames (gait::characterOf).
  void setBody(Character kind, const body::Morphology& morphology);
  // Spawns a character with a creature file's body (body/creature.h) standing at (x, z): one or
  // two leg frames walk the biped's or the quadruped's preset, more the gait derived from the
  // body (gait/derived_gait.h). It starts without a goal. Returns its id, or -1 if there is no
  // room for its bodies (creatureRoom).
  int spawnCreature(const body::Morphology& morphology, double x, double z, double heading);
  // How many more characters of this body the simulation can take now (as characterRoom).
  int creatureRoom(const body::Morphology& morphology) const;
  int spawnBox(double x, double z, double heading);
  // `count` characters (Crowd::Mixed: biped and quadruped in turn, a biped first) in the next
  // free places of the demo page's layout (SceneLayout), each walking forward at its type's
  // cruise speed. The first call sizes the layout's grid for its `count`. Returns how many it
  // added (fewer than `count` once the render buffer is full); they are the last characters.
  int addCharacters(Crowd crowd, int count);
  // One character at the layout's place apart (left of the grid), as spawn() places it: where
  // the optimize panel's learner walks alone. Returns its id, or -1.
  int addApart(Character kind);
  // A creature (spawnCreature) at the layout's place apart.
  int addApartCreature(const body::Morphology& morphology);
  // The demo page's scene: `characters` figures of a mixed crowd in the page's layout
  // (addCharacters(Crowd::Mixed, characters) on a new simulation), plus a few boxes dropped at
  // places drawn from the seed, props for the tests to push against.
  void demoScene(int characters);
  // The thesis experiment's crowd (§4.1, Figures 4.5, 4.6): `characters` bipeds, quadrupeds or
  // both (alternating) on a square grid `spacing` metres apart, centred on the origin, all facing
  // +z; no props. Shard s gets the s-th contiguous chunk of the grid (rows), so neighbours share
  // a world. Every character walks forward at its type's cruise speed (the benchmark measures
  // characters that walk), and the crowd starts out of step: character i at gait phase
  // frac(i / golden ratio), as a crowd would be, rather than 100 characters whose feet all strike
  // on the same step (docs/parallel.md, the p99).
  void crowdScene(Crowd crowd, int characters, double spacing);
  // The same crowd of creature files' bodies (body/creature.h, `gaitlab bench --creature A,B`),
  // the i-th character of body i mod bodies.size(), each walking at its kind's cruise speed with
  // the gait spawnCreature gives it.
  void creatureScene(const std::vector<body::Morphology>& bodies, int characters, double spacing);
  // The speed each type's preset is tuned and benchmarked for (bench/walking.mjs; also the demo's
  // start goals): a 0.49 m dog walks slower than a 1.8 m human.
  static double cruiseSpeed(Character kind) { return kind == Character::Biped ? 1.0 : 0.4; }

  // ---- Stepping -------------------------------------------------------------------------------
  void step(int steps);
  void setMode(Mode mode) { stepping_.setMode(mode); }
  Mode mode() const { return stepping_.mode(); }
  double time() const { return stepping_.time(); }
  uint32_t stepIndex() const { return stepping_.stepIndex(); }
  int threads() const { return stepping_.threads(); }
  // The simulation's thread pool (the Bullet-multithreading probe runs Bullet's tasks on it).
  ThreadPool& pool() { return stepping_.pool(); }
  // Timing of the last fixed step.
  const StepTiming& lastStep() const { return stepping_.lastStep(); }
  // Wall-clock seconds spent so far in the controller loop (thesis timing: from before the
  // first thread starts until the last is done) and in the physics step.
  double controllerSeconds() const { return stepping_.controllerSeconds(); }
  double physicsSeconds() const { return stepping_.physicsSeconds(); }
  // How many times the controller has run for character i (each step must run it exactly once).
  uint64_t controllerUpdates(int i) const { return agents_[i]->updates; }

  // ---- Physics shards -------------------------------------------------------------------------
  int shards() const { return shards_.count(); }
  // The shard character i lives in, and that shard's physics world.
  int shardOf(int i) const { return agents_[i]->shard; }
  const physics::World& world(int shard) const { return shards_.world(shard); }
  // Bullet's own constraint sweep instead of the faster one that computes the same
  // (physics/solver.h), in every shard: for tests and measurements.
  void setFastSolver(bool on) { shards_.setFastSolver(on); }
  // Bullet's own setup of the joints' rows instead of the faster one that computes the same
  // (physics/joint_rows.h): for tests and measurements.
  void setFastJointRows(bool on) { shards_.setFastJointRows(on); }
  // Solver batches so far over every shard, and how many the fast sweep solved.
  std::pair<long, long> solverBatches() const { return shards_.solverBatches(); }
  double groundHeight(double x, double z) const { return shards_.world(0).terrainHeight(x, z); }
  // The ground (physics/terrain.h): flat (the default), slope or bumps, the same in every
  // physics shard; the bumps are drawn from the simulation's seed. Characters already in the
  // scene are re-placed standing on the new ground where their leg frames are (resetCharacter:
  // same gait and goal), props are lifted out of it if the new ground is higher.
  void setTerrain(physics::TerrainKind kind);
  // The same with a terrain made elsewhere (tests: a heightfield with its relief scaled to 0).
  void setTerrain(std::shared_ptr<const physics::Terrain> terrain);
  const physics::Terrain& terrain() const { return shards_.terrain(); }

  // ---- Characters -----------------------------------------------------------------------------
  int characterCount() const { return static_cast<int>(agents_.size()); }
  // The index of the character with id `id`, or -1 when `id` names no character (a prop, a
  // removed character, or nothing spawned): an array lookup (ids.h).
  int indexOf(int id) const;
  int idOf(int index) const { return agents_[index]->id; }
  // The same two under the names the gait-parameter functions of the C ABI use.
  int characterIndex(int id) const { return indexOf(id); }
  int characterId(int index) const { return idOf(index); }
  Character kindOf(int index) const { return agents_[index]->kind; }
  const physics::Character& character(int i) const { return *agents_[i]->body; }
  physics::Character& character(int i) { return *agents_[i]->body; }
  gait::Controller& controller(int i) { return agents_[i]->controller; }
  const gait::Controller& controller(int i) const { return agents_[i]->controller; }
  // The joint torques the controller wrote in the last step (controller.h convention).
  const std::vector<Eigen::Vector3d>& lastTorques(int i) const { return agents_[i]->torques; }
  // Fallen now (walk_trial.h's hasFallen, evaluated after every step), and for how long.
  bool fallen(int index) const { return agents_[index]->fallenSince >= 0; }
  double fallenSeconds(int index) const {
    return fallen(index) ? time() - agents_[index]->fallenSince : 0.0;
  }

  // Whether character i's state stopped being finite (a physics blow-up): it counts as fallen,
  // its bodies are out of the simulation, and any reset rebuilds it standing where it last
  // stood with a finite state.
  bool broken(int index) const { return agents_[index]->broken; }

  // ---- Capacity (capacity.h) ------------------------------------------------------------------
  // How many more characters of `kind`, or boxes, the simulation can take now: the least of the
  // render buffer's room, the free ids, api/limits.h's kMaxBoxes for boxes, and in the WASM build
  // the heap left (capacity.h). A spawn beyond it is refused before it allocates.
  int characterRoom(Character kind) const;
  int boxRoom() const;
  // Why the room is 0 (what is full) for a character of `kind`, or a box (nullopt), for the
  // refusal's message.
  std::string fullReason(std::optional<Character> kind) const;
  int boxCount() const { return boxes_; }

  // ---- Output ---------------------------------------------------------------------------------
  int bodyCount() const { return render_.count(); }
  const RenderHeader* renderBuffer() const { return render_.header(); }
  // 64-bit FNV-1a over the exact bits of every body's transform and velocities (state_hash.h).
  std::string stateHash() const;

  // ---- Wandering (wander.h) -------------------------------------------------------------------
  // Character `id` (or every character now in the scene with id = -1) wanders inside the arena,
  // a circle of `arenaRadius` metres about the origin (one arena for every wanderer: the last
  // radius given), keeping its goal's speed while wandering chooses its turn rate every
  // kWanderPeriodSteps steps; `arenaRadius` = 0 stops it wandering (it keeps its last goal).
  // Returns false if no character has that id. Resets keep it (ids are kept).
  bool setWander(int id, double arenaRadius);
  bool wanders(int index) const { return wander_.wanders(idOf(index)); }
  double arenaRadius() const { return wander_.arenaRadius(); }

  // ---- Interaction (interaction.h, interaction.cpp) -------------------------------------------
  // Steering (beyond the thesis): character index i, or all with i = -1.
  void setGoal(int i, const gait::Goal& goal);

  // A box of half size `half` thrown from `from` with velocity `velocity` (m/s). It collides
  // with the ground, props and characters. At most kMaxThrown thrown boxes exist: the oldest
  // goes when another is thrown, so a user who keeps clicking does not slow the scene down.
  // Returns its id, or -1 if the render buffer is full.
  static constexpr int kMaxThrown = 32;
  int throwBox(const Eigen::Vector3d& from, const Eigen::Vector3d& velocity, double half);
  // The throw from `from` at character index i (the page's shift-click on a character), aimed
  // in the simulation from the character's state now: at where point `local` (body frame of its
  // segment `segment`, metres) will be when a box covering the distance at `speed` m/s arrives
  // (intercept.h: carried by the centre of mass's velocity, turning at the goal's turn rate; a
  // ballistic flight as Bullet integrates it). throwBox(from, aim.velocity, half) throws it.
  Intercept aimAt(int i, int segment, const Eigen::Vector3d& local, const Eigen::Vector3d& from,
                  double speed) const;

  // A spring pulling point `local` (body frame of the character's segment `segment`, metres)
  // towards `target` (world), applied every step until endDrag(). One drag at a time: a pointer.
  // Returns false if the character or segment does not exist.
  bool drag(int id, int segment, const Eigen::Vector3d& local, const Eigen::Vector3d& target);
  void endDrag() { interaction_.drag.id = -1; }

  // Replaces character `id` by a new one standing where its leg frame is now (on the ground,
  // facing its current heading), with the same gait parameters, goal and id. Returns false if
  // no such character exists.
  bool resetCharacter(int id);
  // Removes character `id` (its bodies leave the world and the render buffer; its id names
  // nothing from now on and is never given to another).
  bool removeCharacter(int id);
  // Characters fallen for at least `seconds` are reset automatically; 0 turns this off.
  void setAutoReset(double seconds) { interaction_.autoResetSeconds = seconds; }
  double autoReset() const { return interaction_.autoResetSeconds; }

 private:
  int spawnCharacter(Character kind, double x, double z, double heading, int shard);
  // A character of body `m` (which must outlive it) and `kind` in `shard`: spawnCharacter's and
  // spawnCreature's common part; a body of more than two leg frames gets the gait derived from it
  // (gait/derived_gait.h), the others their kind's preset. -1 if no id is free.
  int spawnBody(const body::Morphology& m, Character kind, double x, double z, double heading, int shard);
  int roomFor(const body::Morphology& m, int64_t bytes) const;
  // The crowd benchmark's grid (crowdScene, creatureScene): spawnAt(i, place, shard) spawns the
  // i-th character (its id, or < 0 when there is no room, which ends the crowd), which then gets
  // its kind's cruise speed and the i-th phase of an evenly spread sequence.
  void benchmarkCrowd(int characters, double spacing, const std::function<int(int, const Place&, int)>& spawnAt);
  void publish() { render_.publish(stepIndex(), time()); }
  void applyDrag();     // interaction.cpp: the drag spring, before the physics of a step
  void updateFallen();  // interaction.cpp: fall times and the automatic reset, after it
  void runSteps(int steps);
  void steerWanderers();  // wander.h: the wanderers' turn rates, between fixed steps
  void isolate(Agent& a);  // interaction.cpp: parks a character whose state is not finite
  void removeOldestThrown();  // interaction.cpp: the oldest thrown box leaves the scene

  uint32_t seed_;
  // The body each kind of character is spawned with (gait::shippedBody unless setBody).
  std::array<body::Morphology, gait::kCharacterCount> bodies_;
  // The bodies of creatures spawned (spawnCreature), one per spawn: a deque, so that the agents'
  // references to them stay valid as more are added.
  std::deque<body::Morphology> creatures_;
  PhysicsShards shards_;
  // Declared after the shards: characters leave the worlds before the worlds are destroyed.
  std::vector<std::unique_ptr<Agent>> agents_;  // in spawn order: the controller loop's order
  IdPool ids_;  // id -> index into agents_ for a character, -1 for a prop
  SceneLayout layout_;
  RenderPublisher render_;
  Stepping stepping_;
  Interaction interaction_;
  Wander wander_;
  int boxes_ = 0;  // props alive: spawned and thrown boxes
};

}  // namespace gaitlab::sim
