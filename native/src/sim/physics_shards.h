// The physics shards: the crowd's physics split over S independent Bullet worlds, fixed when the
// simulation is made, and the props (loose boxes) that move between them.
//
// Characters never collide with each other (physics/world.h), so a character needs only the
// ground and the props near it; a prop lives in the shard of the character nearest to it and
// moves between shards as that changes (between steps, in a fixed order). S is an input of the
// scene like the seed: the execution mode and the thread count only decide which thread steps
// which shard, never what a shard computes, which is why every mode and thread count gives the
// bit-identical state (docs/parallel.md).
#pragma once
#include <memory>
#include <utility>
#include <vector>

#include "body/morphology.h"
#include "physics/terrain.h"
#include "physics/world.h"
#include "sim/agent.h"

namespace gaitlab::sim {

// How many shards a crowd's physics is split over (docs/parallel.md, "How many shards"): 16,
// whatever the thread count, for the benchmark's crowds (fewer only when a crowd has fewer than
// 16 characters: one each) and for the demo, whose crowd grows at run time (each character
// added goes to the least populated shard). One world's cost grows faster than its crowd; at 16
// shards the measured crowds (up to 1000 bipeds, 350 quadrupeds) cost within a few per cent of
// what more shards cost, and 16 divides evenly over 1, 2, 4, 8 and 16 threads. Sixteen worlds
// pool as many contact manifolds as one (the pool is split), so they cost no more memory.
constexpr int kCrowdShards = 16;

class PhysicsShards {
 public:
  using Agents = std::vector<std::unique_ptr<Agent>>;

  // `shards` >= 1 worlds, on flat ground drawn from `seed`.
  PhysicsShards(int shards, uint32_t seed);

  int count() const { return static_cast<int>(worlds_.size()); }
  physics::World& world(int shard) { return *worlds_[shard]; }
  const physics::World& world(int shard) const { return *worlds_[shard]; }

  // ---- Characters ---------------------------------------------------------------------------
  // The shard a character spawned on its own goes to: the least populated (the first of equals).
  int leastPopulated() const;
  // Characters of each shard in spawn order, for the shard's contact and fall updates.
  void addAgent(Agent* agent) { shardAgents_[agent->shard].push_back(agent); }
  void removeAgent(const Agent* agent);
  void replaceAgent(Agent* old, Agent* fresh);  // same place in its shard's order
  // Height at which a character placed at (x, z) facing `heading` stands with its rest pose's
  // soles on the ground: the highest ground under any sole touches it, so no foot starts inside
  // uneven ground (on flat ground: the ground height, as always).
  double standingHeight(int shard, const body::Morphology& m, double x, double z,
                        double heading) const;

  // ---- Props --------------------------------------------------------------------------------
  // The shard of the character nearest to (x, z) in the ground plane, or `fallback` if there is
  // no character.
  int nearestShard(const Agents& agents, double x, double z, int fallback) const;
  // A prop box in the shard of the character nearest to `at` (rehomeProps keeps it there).
  btRigidBody* addProp(const Agents& agents, const Eigen::Vector3d& half, double mass,
                       const Eigen::Vector3d& at, const Eigen::Quaterniond& orientation);
  void removeProp(btRigidBody* body);
  // Moves each prop into the shard of its nearest character (between steps).
  void rehomeProps(const Agents& agents);

  // ---- Stepping -----------------------------------------------------------------------------
  // One shard's part of a fixed step: its Bullet step, its characters' foot contacts and fall
  // test. Touches only this shard, so shards can be stepped concurrently.
  void step(int shard);

  // ---- Ground -------------------------------------------------------------------------------
  const physics::Terrain& terrain() const { return *terrain_; }
  // The same ground in every shard. Characters are the simulation's to re-place on it.
  void setTerrain(std::shared_ptr<const physics::Terrain> terrain);
  // Lifts each prop so that its lowest point clears the highest ground under it.
  void liftPropsOutOfGround();

  // ---- Solver -------------------------------------------------------------------------------
  void setFastSolver(bool on) {
    for (auto& w : worlds_) w->setFastSolver(on);
  }
  void setFastJointRows(bool on) {
    for (auto& w : worlds_) w->setFastJointRows(on);
  }
  std::pair<long, long> solverBatches() const;

 private:
  // A loose body (a dropped or thrown box) and the shard it lives in.
  struct Prop {
    btRigidBody* body;
    int shard;
  };
  // Each shard is a complete Bullet world with its own ground, dispatcher and solver, so shards
  // can be stepped concurrently without sharing state.
  std::vector<std::unique_ptr<physics::World>> worlds_;
  std::shared_ptr<const physics::Terrain> terrain_;  // shared by every shard
  std::vector<std::vector<Agent*>> shardAgents_;
  std::vector<Prop> props_;
};

}  // namespace gaitlab::sim
