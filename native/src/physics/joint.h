// The joint of a segment with 2 or 3 rotational degrees of freedom (ball joints, universals):
// Bullet's btGeneric6DofSpring2Constraint, whose angular limit rows exist only near a limit.
//
// Why. For an angular axis with a range (lower < upper), btGeneric6DofSpring2Constraint emits a
// lower and an upper limit row at every step, wherever the joint is in its range. Such a row is an
// inequality: it acts only when the joint would cross its limit within the step. Far inside the
// range both rows are idle, yet the solver sets them up and sweeps them every iteration: 53 % of
// the quadruped's joint rows (docs/parallel.md, "Where the physics time goes"). Bullet's own
// btHingeConstraint already emits its limit row only at its limit; this does the same for the
// 6-DOF joint, with a test that keeps the rows whenever they might act.
//
// When a pair of rows is dropped. A limit row with error e (distance into the range, rad) asks
// the relative angular velocity along its axis towards the limit to stay below fps·erp·e
// (get_limit_motor_info2: the row's target velocity), so it applies no impulse while the joint
// approaches slower than that. The pair of an axis is dropped when the nearer limit is more than
// kMinDistance away and the joint's present speed along the axis, times kSpeedHeadroom, is below
// fps·erp·e. Otherwise both rows stay, exactly as Bullet builds them. The headroom is there
// because the solve itself changes the velocities: the sweep's intermediate velocities can catch
// a limit row for an iteration or two. With a headroom of 2 (or a distance of 0.1 rad and a
// headroom of 4) the quadruped standing on four feet with the gains of controller-notes §10
// tipped over within 7 s, which it does not with Bullet's rows
// (BodyStance.TheQuadrupedStandsOnFourFeet); with 8 it stands, and still 55 of the walking
// quadruped's 70 limit rows and 15 of the biped's 20 are dropped (docs/parallel.md).
#pragma once
#include <BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h>

namespace gaitlab::physics {

class Joint final : public btGeneric6DofSpring2Constraint {
 public:
  // `subStep`: the Bullet sub-step (s), for the rows' fps; `erp`: the solver's error reduction
  // parameter for joints (btContactSolverInfo::m_erp).
  Joint(btRigidBody& parent, btRigidBody& child, const btTransform& inParent,
        const btTransform& inChild, btScalar subStep, btScalar erp);

  void getInfo1(btConstraintInfo1* info) override;

  static constexpr btScalar kMinDistance = 0.05;  // rad
  static constexpr btScalar kSpeedHeadroom = 8;

  // Angular axes (0..2) whose limit rows the last getInfo1 dropped, as bits.
  int droppedAxes() const { return dropped_; }

 private:
  btScalar rowSpeedPerRadian_;  // fps·erp: the speed towards a limit a row allows per rad of range
  int dropped_ = 0;
};

}  // namespace gaitlab::physics
