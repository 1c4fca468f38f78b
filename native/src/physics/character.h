// An articulated character in a physics::World, built from a body::Morphology: one box rigid
// body per segment, one constraint per joint (btHingeConstraint for 1 DOF, a
// physics::Joint, a btGeneric6DofSpring2Constraint with locked translation whose limit rows
// exist only near a limit, for 2 and 3 DOF).
#pragma once
#include <Eigen/Dense>
#include <vector>

#include "body/morphology.h"
#include "gait/controller.h"
#include "physics/world.h"

class btRigidBody;
class btTypedConstraint;

namespace gaitlab::physics {

// World-frame state of one segment: the controller's own BodyState.
using SegmentState = gait::BodyState;

class Character {
 public:
  // Places the rest pose with its feet on the ground at (x, groundY, z), turned by `heading`.
  Character(World& world, const body::Morphology& morphology, const Eigen::Vector3d& origin,
            double heading);
  ~Character();
  Character(const Character&) = delete;
  Character& operator=(const Character&) = delete;

  const body::Morphology& morphology() const { return morphology_; }
  int segmentCount() const { return static_cast<int>(bodies_.size()); }
  btRigidBody* body(int segment) const { return bodies_[segment]; }

  SegmentState segmentState(int segment) const;

  // The controller's view of the character (gait::CharacterState::segments), morphology order.
  void readState(gait::BodyState* out) const;

  // torques[segment]: torque of the joint between the segment and its parent, world frame.
  // Applied as an equal and opposite pair: +τ on the segment, −τ on its parent (the original
  // applied it to the child only, creating angular momentum from nothing: defect 3 of the original implementation, docs/original-implementation.md).
  void applyJointTorques(const Eigen::Vector3d* torques);

  // Marks foot `leg`'s body so that contact detection can find its flag (World::updateContacts).
  void setFootContactFlag(int leg, bool* flag);

  // Planted feet hold their place (a character standing still, gait::Controller::standing):
  // Bullet's friction anchors keep a foot's contact points while their friction stays inside
  // the friction cone and pull them back to where they touched (positional friction,
  // btContactSolverInfo::m_frictionERP). Without them a foot under a steady load creeps: a
  // standing biped slid 5 cm/s with its friction far inside the cone (docs/controller-notes.md,
  // "Standing on planted feet"). Walking leaves them off, as every gait was tuned.
  void holdFeet(bool hold);

  // The gait's forward stop at each hip (gait::GaitParams::hipForwardStop): the
  // thigh's forward swing limited to `stop` rad, or to the body's own range if that is smaller.
  // A limit row of the solver, as the body's own limit is: a stop as stiff as the joint's end,
  // which an explicit spring at 120 Hz could not give (docs/controller-notes.md §78).
  void setHipForwardStop(double stop);

 private:
  World& world_;
  const body::Morphology& morphology_;
  std::vector<btRigidBody*> bodies_;
  std::vector<btTypedConstraint*> joints_;  // per segment, its joint to its parent (the root's: none)
};

}  // namespace gaitlab::physics
