#include "physics/character.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cassert>

#include "physics/convert.h"
#include "physics/joint.h"

namespace gaitlab::physics {

namespace {

// Index (0, 1, 2) of the character-frame axis a DOF turns about; the morphologies use
// axis-aligned DOFs only, which is what the 6-DOF constraint's limits are expressed in.
int axisIndex(const Eigen::Vector3d& axis) {
  int i;
  axis.cwiseAbs().maxCoeff(&i);
  return i;
}

}  // namespace

Character::Character(World& world, const body::Morphology& morphology,
                     const Eigen::Vector3d& origin, double heading)
    : world_(world), morphology_(morphology) {
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY()));
  const auto place = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return origin + yaw * p; };

  bodies_.reserve(morphology.segments.size());
  for (const body::Segment& s : morphology.segments) {
    // Feet get more friction than the rest: they are what the controller pushes with.
    const bool isFoot = s.name.size() > 5 && s.name.compare(s.name.size() - 5, 5, ".foot") == 0;
    btRigidBody* b = world.addBox(s.halfExtents, s.mass, place(s.center), yaw, kCharacterGroup,
                                  kCharacterMask, isFoot ? 1.0 : 0.6);
    // Joint armature (body/morphology.h): raise each principal moment to at least `armature`.
    const btVector3 inv = b->getInvInertiaDiagLocal();
    btVector3 inertia;
    for (int a = 0; a < 3; ++a)
      inertia[a] = std::max(static_cast<btScalar>(morphology.armature), btScalar(1) / inv[a]);
    b->setMassProps(static_cast<btScalar>(s.mass), inertia);
    b->updateInertiaTensor();
    bodies_.push_back(b);
  }

  joints_.assign(morphology.segments.size(), nullptr);
  for (size_t i = 0; i < morphology.segments.size(); ++i) {
    const body::Segment& s = morphology.segments[i];
    if (s.parent < 0) continue;
    btRigidBody* parent = bodies_[s.parent];
    btRigidBody* child = bodies_[i];
    const body::Joint& j = s.joint;
    // The joint frame at rest: at the pivot, axes of the character frame.
    btTransform jointFrame(toBt(yaw), toBt(place(j.pivot)));
    btTypedConstraint* c = nullptr;
    if (j.type == body::JointType::Hinge) {
      // btHingeConstraint turns about its frames' z axis: rotate z onto the DOF axis.
      const Eigen::Quaterniond zToAxis = Eigen::Quaterniond::FromTwoVectors(
          Eigen::Vector3d::UnitZ(), j.axes[0]);
      btTransform hingeFrame(toBt(yaw * zToAxis), toBt(place(j.pivot)));
      auto* h = new btHingeConstraint(*parent, *child,
                                      parent->getWorldTransform().inverse() * hingeFrame,
                                      child->getWorldTransform().inverse() * hingeFrame, false);
      // btHingeConstraint::getHingeAngle() measures the parent relative to the child, the
      // opposite sign of our right-handed child-relative-to-parent angle (measured:
      // docs/controller-notes.md, "Measured" 1), so the limits are mirrored.
      h->setLimit(static_cast<btScalar>(-j.upper[0]), static_cast<btScalar>(-j.lower[0]));
      c = h;
    } else {
      // Limit rows only near a limit (physics/joint.h).
      auto* g = new Joint(*parent, *child, parent->getWorldTransform().inverse() * jointFrame,
                          child->getWorldTransform().inverse() * jointFrame,
                          static_cast<btScalar>(kFixedStep / kPhysicsSubsteps),
                          world.dynamics().getSolverInfo().m_erp);
      g->setLinearLowerLimit(btVector3(0, 0, 0));
      g->setLinearUpperLimit(btVector3(0, 0, 0));
      // btGeneric6DofSpring2Constraint's Euler angles (matrixToEulerXYZ) read its relative basis
      // transposed: they are the parent's rotation relative to the child, the opposite sign of
      // ours, as the hinge's are. So these limits are mirrored too (the three angles they bound
      // are then those of Rz·Ry·Rx); read straight, a hip given 2.0 rad forwards and 0.7
      // backwards swung 0.7 forwards and 2.0 backwards (JointRange test; docs/controller-notes.md,
      // "The ball joints' ranges were mirrored").
      btVector3 lo(0, 0, 0), hi(0, 0, 0);  // DOFs the joint lacks stay locked
      for (int d = 0; d < body::dofCount(j.type); ++d) {
        const int a = axisIndex(j.axes[d]);
        lo[a] = static_cast<btScalar>(-j.upper[d]);
        hi[a] = static_cast<btScalar>(-j.lower[d]);
      }
      g->setAngularLowerLimit(lo);
      g->setAngularUpperLimit(hi);
      c = g;
    }
    // Jointed segments never collide: the collision filter already keeps all of a character's
    // segments apart (world.h, kCharacterMask). Bullet's own switch for it (true here) would give
    // each segment a list of its neighbours, searched for every contact pair in every sub-step.
    world.dynamics().addConstraint(c, false);
    joints_[i] = c;
  }
}

Character::~Character() {
  for (btTypedConstraint* c : joints_) {
    if (!c) continue;
    world_.dynamics().removeConstraint(c);
    delete c;
  }
  for (btRigidBody* b : bodies_) world_.removeBody(b);
}

SegmentState Character::segmentState(int segment) const {
  const btRigidBody* b = bodies_[segment];
  const btTransform& t = b->getCenterOfMassTransform();
  return {toEigen(t.getOrigin()), toEigen(t.getRotation()), toEigen(b->getLinearVelocity()),
          toEigen(b->getAngularVelocity())};
}

}  // namespace gaitlab::physics

namespace gaitlab::physics {

void Character::readState(gait::BodyState* out) const {
  for (size_t i = 0; i < bodies_.size(); ++i) out[i] = segmentState(static_cast<int>(i));
}

void Character::applyJointTorques(const Eigen::Vector3d* torques) {
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const int parent = morphology_.segments[i].parent;
    if (parent < 0) continue;
    const btVector3 t = toBt(torques[i]);
    bodies_[i]->applyTorque(t);
    bodies_[parent]->applyTorque(-t);
  }
}

void Character::setHipForwardStop(double stop) {
  for (const body::Leg& leg : morphology_.legs) {
    const body::Joint& j = morphology_.segments[leg.upper].joint;
    if (j.type == body::JointType::Hinge) continue;  // hips are ball joints (body/creature.h)
    auto* hip = static_cast<Joint*>(joints_[leg.upper]);
    // A forward swing turns about −x: the file's lower[0] bounds it, mirrored into the upper
    // limit as the constructor mirrors it.
    btVector3 upper;
    hip->getAngularUpperLimit(upper);
    upper[axisIndex(j.axes[0])] = static_cast<btScalar>(std::min(-j.lower[0], stop));
    hip->setAngularUpperLimit(upper);
  }
}

void Character::setFootContactFlag(int leg, bool* flag) {
  bodies_[morphology_.legs[leg].foot]->setUserPointer(flag);
}

void Character::holdFeet(bool hold) {
  for (const body::Leg& leg : morphology_.legs) {
    btRigidBody* foot = bodies_[leg.foot];
    const int flags = foot->getCollisionFlags();
    foot->setCollisionFlags(hold ? flags | btCollisionObject::CF_HAS_FRICTION_ANCHOR
                                 : flags & ~btCollisionObject::CF_HAS_FRICTION_ANCHOR);
  }
}

}  // namespace gaitlab::physics
