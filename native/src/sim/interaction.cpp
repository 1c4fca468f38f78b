// The demo page's commands on a running scene (interaction.h).
#include "sim/interaction.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "api/limits.h"
#include "gait/heading.h"
#include "physics/convert.h"
#include "sim/intercept.h"
#include "sim/simulation.h"

namespace gaitlab::sim {

void applyDragSpring(physics::Character& c, const Drag& drag) {
  btRigidBody* b = c.body(drag.segment);
  const btTransform& t = b->getCenterOfMassTransform();
  const btVector3 point = t * physics::toBt(drag.local);
  const btVector3 rel = point - t.getOrigin();
  const btVector3 v = b->getVelocityInLocalPoint(rel);
  // A critically damped spring sized for the whole character (ω = 5 rad/s: it follows the
  // pointer in about half a second), applied at one point of one segment. Explicit integration
  // at 120 Hz is stable only while k·dt²/m and c·dt/m stay below ~1 for the segment held
  // (a foot weighs ~1 kg against a 60 kg figure), hence the limits; and the force is capped at
  // three body weights, so a pointer far away pulls hard but never launches the character.
  const double mass = c.morphology().totalMass();
  const double segmentMass = 1.0 / std::max(1e-6, static_cast<double>(b->getInvMass()));
  const double dt = physics::kFixedStep;
  const double omega = 5.0;
  const double k = std::min(mass * omega * omega, 0.5 * segmentMass / (dt * dt));
  const double damping = std::min(2.0 * 0.9 * omega * mass, 0.5 * segmentMass / dt);
  btVector3 force = static_cast<btScalar>(k) * (physics::toBt(drag.target) - point) -
                    static_cast<btScalar>(damping) * v;
  const double cap = 3.0 * mass * 9.81;
  if (force.length() > cap) force *= static_cast<btScalar>(cap / force.length());
  // As an impulse over the whole fixed step: Bullet clears applied forces after each of the
  // world's sub-steps (stepSimulation ends in clearForces), so a force would act on the first only.
  b->applyImpulse(force * static_cast<btScalar>(dt), rel);
}

void Simulation::setGoal(int i, const gait::Goal& goal) {
  if (i < 0) {
    for (auto& a : agents_) a->controller.setGoal(goal);
  } else if (i < characterCount()) {
    agents_[i]->controller.setGoal(goal);
  }
}

int Simulation::throwBox(const Eigen::Vector3d& from, const Eigen::Vector3d& velocity,
                         double half) {
  // At the most boxes a scene takes, the oldest thrown box makes way first (when there is one).
  if (boxRoom() < 1 && !interaction_.thrown.empty() && boxes_ >= limits::kMaxBoxes) removeOldestThrown();
  if (boxRoom() < 1) return -1;
  const int id = ids_.create(-1);
  if (id < 0) return -1;
  // Solid wood, roughly (600 kg/m³): a 0.24 m box weighs ~8 kg, enough at 10-15 m/s to knock
  // a 1.7 m biped sideways without flinging it across the scene.
  const double mass = 600.0 * std::pow(2 * half, 3);
  // Like every prop, it starts in the shard of the character nearest to it and follows its
  // nearest character from shard to shard as it flies (PhysicsShards::rehomeProps).
  btRigidBody* b = shards_.addProp(agents_, Eigen::Vector3d::Constant(half), mass, from,
                                   Eigen::Quaterniond::Identity());
  b->setLinearVelocity(physics::toBt(velocity));
  // Thrown boxes are the warm wood colour of the scene's boxes, a shade darker to tell them apart.
  const float h = static_cast<float>(half);
  render_.add(b, {{h, h, h}, 0xc08a48ffu, -1, 0});
  interaction_.thrown.push_back({b, id});
  ++boxes_;
  if (static_cast<int>(interaction_.thrown.size()) > kMaxThrown) removeOldestThrown();
  return id;
}

Intercept Simulation::aimAt(int i, int segment, const Eigen::Vector3d& local,
                            const Eigen::Vector3d& from, double speed) const {
  const physics::Character& c = character(i);
  // The point aimed at, where it is now; and the character's centre-of-mass velocity, which
  // carries it along (the segment's own velocity would add a swinging limb's to the walk).
  const Eigen::Vector3d at =
      physics::toEigen(c.body(segment)->getCenterOfMassTransform() * physics::toBt(local));
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  double mass = 0;
  for (int k = 0; k < c.segmentCount(); ++k) {
    const btRigidBody* b = c.body(k);
    const double m = b->getInvMass() > 0 ? 1.0 / b->getInvMass() : 0.0;
    momentum += m * physics::toEigen(b->getLinearVelocity());
    mass += m;
  }
  const Eigen::Vector3d velocity = mass > 0 ? Eigen::Vector3d(momentum / mass) : Eigen::Vector3d::Zero();
  return interceptThrow(from, at, velocity, controller(i).goal().turnRate, speed,
                        shards_.world(agents_[i]->shard).gravity(),
                        physics::kFixedStep / physics::kPhysicsSubsteps);
}

void Simulation::removeOldestThrown() {
  const ThrownBox oldest = interaction_.thrown.front();
  interaction_.thrown.pop_front();
  render_.remove({oldest.body});
  shards_.removeProp(oldest.body);
  ids_.destroy(oldest.id);
  --boxes_;
}

bool Simulation::drag(int id, int segment, const Eigen::Vector3d& local,
                      const Eigen::Vector3d& target) {
  const int i = indexOf(id);
  if (i < 0 || segment < 0 || segment >= character(i).segmentCount()) return false;
  interaction_.drag = {id, segment, local, target};
  return true;
}

void Simulation::applyDrag() {
  if (interaction_.drag.id < 0) return;
  const int i = indexOf(interaction_.drag.id);
  if (i < 0) {  // the character was removed while held
    endDrag();
    return;
  }
  applyDragSpring(character(i), interaction_.drag);
}

bool Simulation::resetCharacter(int id) {
  const int i = indexOf(id);
  if (i < 0) return false;
  Agent& old = *agents_[i];
  const body::Morphology& m = old.body->morphology();
  const int root = m.legFrames[0];
  physics::SegmentState s = old.body->segmentState(root);
  double heading = gait::headingOf(s.orientation);
  if (old.broken) {  // rebuilt where it last stood with a finite state (isolate)
    s.position = old.lastGood;
    heading = old.lastGoodHeading;
  }
  // The rest pose puts the root at `center` in the character frame: place the new figure so
  // that its root stands where the old one's is now.
  const Eigen::Vector3d offset =
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY()) * m.segments[root].center;
  const double x = s.position.x() - offset.x(), z = s.position.z() - offset.z();

  auto fresh = std::make_unique<Agent>(
      shards_.world(old.shard), m,
      Eigen::Vector3d(x, shards_.standingHeight(old.shard, m, x, z, heading), z), heading);
  fresh->id = id;
  fresh->kind = old.kind;
  fresh->shard = old.shard;
  fresh->controller.setGait(old.controller.gait());
  fresh->controller.setGoal(old.controller.goal());
  shards_.replaceAgent(&old, fresh.get());
  // Same morphology, same number of bodies in the same order: the render entries keep their
  // places and colours and only point at the new bodies.
  render_.rebind(id, *fresh->body);
  agents_[i] = std::move(fresh);  // the old character's bodies leave the world here
  if (interaction_.drag.id == id) endDrag();
  return true;
}

bool Simulation::removeCharacter(int id) {
  const int i = indexOf(id);
  if (i < 0) return false;
  const Agent& a = *agents_[i];
  std::vector<btRigidBody*> bodies;
  for (int k = 0; k < a.body->segmentCount(); ++k) bodies.push_back(a.body->body(k));
  render_.remove(bodies);
  shards_.removeAgent(&a);
  agents_.erase(agents_.begin() + i);
  ids_.destroy(id);
  // The characters after it moved up one place in the controller loop's order.
  for (int k = i; k < characterCount(); ++k) ids_.setValue(agents_[k]->id, k);
  if (interaction_.drag.id == id) endDrag();
  return true;
}

void Simulation::isolate(Agent& a) {
  // Its bodies leave the simulation where it last stood: finite transforms (the render buffer,
  // the state hash and the props' nearest-character search read them), no velocity, never
  // integrated again (DISABLE_SIMULATION), and no contact response, so nothing that touches them
  // inherits what is not finite. The constraints between them are never solved, as neither of
  // their bodies is active. A reset rebuilds the character from `lastGood`.
  btDiscreteDynamicsWorld& world = shards_.world(a.shard).dynamics();
  btTransform parked(btQuaternion(btVector3(0, 1, 0), static_cast<btScalar>(a.lastGoodHeading)),
                     physics::toBt(a.lastGood));
  for (int k = 0; k < a.body->segmentCount(); ++k) {
    btRigidBody* b = a.body->body(k);
    b->setCenterOfMassTransform(parked);
    b->setInterpolationWorldTransform(parked);
    b->setLinearVelocity(btVector3(0, 0, 0));
    b->setAngularVelocity(btVector3(0, 0, 0));
    b->clearForces();
    b->setCollisionFlags(b->getCollisionFlags() | btCollisionObject::CF_NO_CONTACT_RESPONSE);
    b->forceActivationState(DISABLE_SIMULATION);
    world.updateSingleAabb(b);
  }
  a.parked = true;
  if (interaction_.drag.id == a.id) endDrag();
}

void Simulation::updateFallen() {
  const double now = time();
  std::vector<int> toReset;  // empty, so no allocation, unless a reset is due
  for (auto& agent : agents_) {
    Agent& a = *agent;
    if (a.broken && !a.parked) isolate(a);
    if (!a.down) {
      a.fallenSince = -1;
      continue;
    }
    if (a.fallenSince < 0) a.fallenSince = now;
    if (interaction_.autoResetSeconds > 0 && now - a.fallenSince >= interaction_.autoResetSeconds)
      toReset.push_back(a.id);
  }
  for (int id : toReset) resetCharacter(id);
}

}  // namespace gaitlab::sim
