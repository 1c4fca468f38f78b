// Interaction: everything a user does to a running scene from the demo page (goals, the
// pointer's drag, thrown boxes, reset, remove, the automatic reset of fallen characters). The
// sim worker applies these between fixed steps (it queues the page's commands and applies them
// at the start of the next step), so each acts at a known step index and a run can be replayed
// from (seed, scene, command log).
//
// The state those commands leave behind lives here; the commands themselves are Simulation's
// (interaction.cpp), as they add, replace and remove characters and props in every part of it.
#pragma once
#include <Eigen/Core>
#include <deque>

class btRigidBody;

namespace gaitlab::physics {
class Character;
}

namespace gaitlab::sim {

// The pointer holding a character: a spring pulling point `local` (body frame of segment
// `segment`, metres) towards `target` (world), every step until the drag ends.
struct Drag {
  int id = -1;  // character; -1 = no drag
  int segment = 0;
  Eigen::Vector3d local = Eigen::Vector3d::Zero(), target = Eigen::Vector3d::Zero();
};

// Applies one fixed step's worth of the drag spring to character `c`.
void applyDragSpring(physics::Character& c, const Drag& drag);

// A box the user threw, and its id.
struct ThrownBox {
  btRigidBody* body;
  int id;
};

struct Interaction {
  Drag drag;
  std::deque<ThrownBox> thrown;  // oldest first
  double autoResetSeconds = 0;   // 0 = off
};

}  // namespace gaitlab::sim
