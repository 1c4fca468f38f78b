// The peer benchmark's reference scene: a scene any rigid-body engine can build, so that
// gaitlab's physics can be timed side by side with another engine (Jolt Physics, Rouwé 2022) on
// the same work — the comparison Larsson 2015 §7.5 asks for ("the overall impact of the
// locomotion algorithm combined with the physics solver ... for several available physics
// solvers").
//
// The scene: `characters` copies of one of gaitlab's morphologies (body/morphology.h: boxes,
// hinge / universal / ball joints with limits) on the crowd benchmark's square grid, each a
// passive ragdoll whose joints hold the rest (standing) pose with motors, on flat ground;
// characters collide with the ground only (neither with themselves nor with each other, as in
// gaitlab's simulation: physics/world.h). Time advances in fixed steps of 1/120 s, each two
// sub-steps of 1/240 s (physics/world.h). No controller runs: this is the physics alone plus the
// motors' torques, which every engine computes its own way (here explicit PD torques, applied
// once per fixed step as gaitlab's controller applies its own; Jolt uses its constraints'
// position motors).
//
// The motors are PD springs with fixed joint gains (hip, knee, stance ankle, spine: the gains
// gaitlab's presets held a stance with when the benchmark was first measured, pinned in
// reference_scene.cpp so that tuning a gait does not move the comparison); the other engine gets the
// same stiffness and damping for its position motors through gl_morphology_json.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "body/morphology.h"
#include "gait/schema.h"
#include "physics/character.h"
#include "physics/world.h"
#include "sim/thread_pool.h"

namespace gaitlab::peers {

// The most ragdolls a scene holds: the peer benchmark goes to 400. 400 quadrupeds take about
// 100 MB of the WebAssembly build's fixed 256 MB heap (a walking one 244 KiB, README "Limits").
constexpr int kMaxCharacters = 400;

// A joint's motor: torque = kp·(rotation to the rest pose) − kd·(relative angular velocity).
struct Motor {
  double kp = 0, kd = 0;  // N·m/rad, N·m·s/rad
};
// The motor of each segment's joint to its parent (the root's is zero): the preset's gains.
std::vector<Motor> holdingMotors(gait::Character character);

class ReferenceScene {
 public:
  // `characters` ragdolls of `character`, `spacing` metres apart on the crowd benchmark's grid,
  // split into `shards` physics worlds (contiguous rows; 0: one per thread) that `threads`
  // threads step, each world on one thread at a time. The result depends on the shards, never on
  // the threads.
  ReferenceScene(gait::Character character, int characters, int threads, int shards = 0,
                 double spacing = 2.5);
  ~ReferenceScene();
  ReferenceScene(const ReferenceScene&) = delete;
  ReferenceScene& operator=(const ReferenceScene&) = delete;

  // `steps` fixed steps: per character the motor torques, then its world's two sub-steps.
  void step(int steps);
  int characters() const { return static_cast<int>(ragdolls_.size()); }
  // Mean height of the characters' root segments above the ground, m: whether they still stand.
  double meanRootHeight() const;
  // The largest angle any joint of any ragdoll is turned away from the rest pose, radians.
  double largestPoseError() const;
  // FNV-1a over every body's transform and velocities: runs compared bit for bit.
  uint64_t hash() const;

 private:
  struct Ragdoll {
    std::unique_ptr<physics::Character> body;
    int world;
  };
  void holdPose(const Ragdoll& r, std::vector<gait::BodyState>* state,
                std::vector<Eigen::Vector3d>* torques) const;

  body::Morphology morphology_;
  std::vector<Motor> motors_;  // per segment (its joint to the parent); the root's unused
  std::vector<std::unique_ptr<physics::World>> worlds_;
  std::vector<Ragdoll> ragdolls_;
  std::vector<std::vector<int>> byWorld_;  // ragdoll indices per world
  sim::ThreadPool pool_;
};

}  // namespace gaitlab::peers
