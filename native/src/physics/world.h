// The Bullet adapter's world: ground, props, stepping, ray casts. Everything Bullet-specific in
// gaitlab lives in physics/; the controller (gait/) never sees a Bullet type.
#pragma once
#include <Eigen/Dense>
#include <LinearMath/btVector3.h>
#include <utility>
#include <memory>
#include <vector>

#include "physics/terrain.h"

class btBroadphaseInterface;
class btCollisionDispatcher;
class btCollisionShape;
class btDefaultCollisionConfiguration;
class btDiscreteDynamicsWorld;
class btRigidBody;
class btConstraintSolver;

namespace gaitlab::physics {

// Collision filtering (docs/design.md, physics modelling): characters collide with the ground and
// with props, but neither with themselves nor with each other — limbs of one figure overlap at
// the joints by construction, and crowds are spaced so that characters do not meet; props
// collide with everything.
enum CollisionGroup : int { kGroundGroup = 1, kPropGroup = 2, kCharacterGroup = 4 };
constexpr int kGroundMask = kPropGroup | kCharacterGroup;
constexpr int kPropMask = kGroundGroup | kPropGroup | kCharacterGroup;
constexpr int kCharacterMask = kGroundGroup | kPropGroup;

// Sequential-impulse iterations per sub-step: Bullet's default. 40 were used at first (a trunk
// weighs 30–60 times a foot, and sequential impulses converge slowly across such mass ratios);
// 10 take about half the physics time, and both characters' presets meet every walking criterion
// with them (the quadruped's trot re-tuned by one more optimiser run; docs/parallel.md, "Trade-offs
// that change the dynamics").
constexpr int kSolverIterations = 10;

// The fixed simulation step (thesis §3.2: Bullet at 120 Hz): the controller runs once per step.
constexpr double kFixedStep = 1.0 / 120.0;

// Bullet sub-steps per fixed step. Measured: with one 1/120 s step, a biped standing on one leg
// under the controller's torques pushed its foot 6 cm into the ground within 0.1 s (whatever the
// solver iterations, ERP or split impulse), while a passive one stood still; with two 1/240 s
// sub-steps the foot stays within 1 mm. The controller still runs at 120 Hz, as in the thesis.
constexpr int kPhysicsSubsteps = 2;

class World {
 public:
  // Bullet's default collision configuration pre-allocates pools for 4096 contact manifolds and
  // collision algorithms (about 5 MB). A crowd split over several worlds (sim::Simulation's
  // physics shards) needs only a share of that per world.
  static constexpr int kDefaultContactPool = 4096;
  explicit World(int contactPool = kDefaultContactPool);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  btDiscreteDynamicsWorld& dynamics() { return *dynamics_; }
  const btDiscreteDynamicsWorld& dynamics() const { return *dynamics_; }
  // The world's gravity, m/s² (what a thrown box's flight is aimed with: sim/intercept.h).
  Eigen::Vector3d gravity() const;

  // A box rigid body (mass 0 = static), added to the world with the given collision filter.
  btRigidBody* addBox(const Eigen::Vector3d& halfExtents, double mass,
                      const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                      int group, int mask, double friction);
  void removeBody(btRigidBody* body);
  // Moves a loose body (a prop: no constraints attached) and its shape into `other`, keeping its
  // state and collision filter. Its contact manifolds stay behind and are rebuilt in `other`.
  void moveBodyTo(btRigidBody* body, World& other);

  // The solver's sweep over the constraint rows: InterleavedSolver's (the default) or Bullet's own.
  // Both compute bit for bit the same (physics/solver.h); this switch is for tests and measurements.
  void setFastSolver(bool on);
  // The setup of the joints' rows: JointRowSolver's (the default) or Bullet's own convertJoints.
  // Also bit for bit the same (physics/joint_rows.h); for tests and measurements.
  void setFastJointRows(bool on);
  // Solver batches so far, and how many the fast sweep solved (the rest fell back to Bullet's).
  std::pair<long, long> solverBatches() const;

  // Sizes the solver's working arrays for the world's contents (the worst case: see
  // ReservingSolver in world.cpp). step() does it whenever the contents have changed since, but
  // the allocation is then part of a step: for a crowd of 100 quadrupeds it made the first step
  // of a fresh simulation take twice as long as the others (docs/parallel.md, the p99). Scene
  // building calls it instead (sim::Simulation, after adding bodies). Changes no result.
  void reserve();

  // One fixed step of kFixedStep seconds, as kPhysicsSubsteps Bullet steps (no interpolation:
  // deterministic).
  void step();

  // Replaces the ground (physics/terrain.h): a heightfield over the terrain's samples, friction
  // as the plane's, with the plane moved to the terrain's plane height beyond it. Every physics
  // shard of a simulation shares one Terrain (its samples are read in place, never copied).
  // Contacts with the old ground are dropped; bodies standing on it are not moved.
  void setTerrain(std::shared_ptr<const Terrain> terrain);
  const Terrain* terrain() const { return terrain_.get(); }

  // Height of the ground below (x, z): a downward ray cast against the terrain objects alone
  // (the relief, then the plane), without the broadphase, so it is safe to call from many
  // threads at once (the controller's ground queries). Returns `fallback` if the ray misses.
  double terrainHeight(double x, double z, double fallback = 0.0) const;

  // After a step: sets *flag = true for every body whose user pointer is a bool* flag (feet,
  // Character::setFootContactFlag) and that touches the ground or a prop, counting contact points
  // within 1 cm, so a touch-down registers before the foot penetrates (defect 8). Flags of
  // bodies without contact are left alone: the caller clears them first.
  void updateContacts() const;

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> dynamics_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<btRigidBody*> bodies_;  // owned; deleted in the destructor or removeBody
  // Forces and torques applied since the last step, re-applied before each later sub-step.
  std::vector<std::pair<btVector3, btVector3>> applied_;
  btRigidBody* ground_ = nullptr;
  btRigidBody* relief_ = nullptr;  // the terrain's heightfield; nullptr while the ground is flat
  std::shared_ptr<const Terrain> terrain_;
  // The contents the solver's arrays were last sized for (World::step).
  int reservedBodies_ = -1, reservedJoints_ = -1;
};

}  // namespace gaitlab::physics
