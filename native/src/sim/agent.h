// A character of the simulation: its bodies in a physics shard, its controller, and the buffers
// the controller reads and writes, allocated once so that the per-step loop allocates nothing
// (defect 10 of the original implementation, docs/original-implementation.md).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "body/morphology.h"
#include "gait/controller.h"
#include "physics/character.h"
#include "physics/world.h"
#include "sim/scene_layout.h"

namespace gaitlab::sim {

struct Agent {
  Agent(physics::World& world, const body::Morphology& m, const Eigen::Vector3d& origin,
        double heading);

  // Algorithm 1 of the thesis (§3.1) for this character: read its state, compute the joint
  // torques, hand them to the physics. Touches only this character, so the controller loop can
  // run characters on any threads.
  void control();

  std::unique_ptr<physics::Character> body;
  gait::Controller controller;
  std::vector<gait::BodyState> state;
  std::vector<Eigen::Vector3d> torques;
  bool footContact[gait::kMaxLegs] = {false, false, false, false};
  const physics::World* world;
  int id = -1;  // its IdPool id
  Character kind = Character::Biped;
  bool down = false;        // hasFallen after the last step (set in its shard's task)
  double fallenSince = -1;  // simulated time it was first seen fallen; -1 = standing
  int shard = 0;
  // A state that stopped being finite (a physics blow-up; scene commands are checked for
  // finiteness where they enter): set in its shard's task, after which the character is down,
  // its controller no longer runs and its bodies are parked out of the simulation
  // (Simulation::isolateBroken) until a reset rebuilds it at `lastGood`.
  bool broken = false;
  bool feetHeld = false;  // the body's feet hold their place: the controller stands (holdFeet)
  double hipStop = 0;     // the forward stop set on the body's hips (setHipForwardStop)
  bool parked = false;
  Eigen::Vector3d lastGood;    // the root leg frame's last finite position
  double lastGoodHeading = 0;  // and heading
  uint64_t updates = 0;  // controller runs: each fixed step must run it exactly once
};

}  // namespace gaitlab::sim
