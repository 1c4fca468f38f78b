#include "sim/physics_shards.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "gait/heading.h"
#include "sim/walk_trial.h"

namespace gaitlab::sim {

namespace {

// Whether every body of a character has a finite position, orientation and velocities.
bool finiteState(const physics::Character& c) {
  for (int k = 0; k < c.segmentCount(); ++k) {
    const btRigidBody* b = c.body(k);
    const btTransform& t = b->getCenterOfMassTransform();
    const btQuaternion q = t.getRotation();
    const btVector3& p = t.getOrigin();
    const btVector3& v = b->getLinearVelocity();
    const btVector3& w = b->getAngularVelocity();
    // NaN and infinity both make the sum non-finite (inf - inf, or inf itself).
    const double sum = double(p.x()) + p.y() + p.z() + q.x() + q.y() + q.z() + q.w() + v.x() + v.y() + v.z() +
                       w.x() + w.y() + w.z();
    if (!std::isfinite(sum)) return false;
  }
  return true;
}

}  // namespace

PhysicsShards::PhysicsShards(int shards, uint32_t seed) {
  if (shards < 1) shards = 1;
  // A shard holds about 1/S of the crowd's contacts; 256 pooled manifolds cover 20 fallen
  // quadrupeds (11 boxes each on the ground) before Bullet falls back to the heap.
  const int pool = shards == 1 ? physics::World::kDefaultContactPool
                               : std::max(256, physics::World::kDefaultContactPool / shards);
  for (int s = 0; s < shards; ++s) worlds_.push_back(std::make_unique<physics::World>(pool));
  terrain_ = std::make_shared<physics::Terrain>(physics::TerrainKind::Flat, seed);
  shardAgents_.resize(shards);
}

int PhysicsShards::leastPopulated() const {
  int shard = 0;
  for (int s = 1; s < count(); ++s)
    if (shardAgents_[s].size() < shardAgents_[shard].size()) shard = s;
  return shard;
}

void PhysicsShards::removeAgent(const Agent* agent) {
  auto& inShard = shardAgents_[agent->shard];
  inShard.erase(std::find(inShard.begin(), inShard.end(), agent));
}

void PhysicsShards::replaceAgent(Agent* old, Agent* fresh) {
  auto& inShard = shardAgents_[old->shard];
  std::replace(inShard.begin(), inShard.end(), old, fresh);
}

double PhysicsShards::standingHeight(int shard, const body::Morphology& m, double x, double z,
                                     double heading) const {
  const double ground = worlds_[shard]->terrainHeight(x, z);
  if (terrain_->flat()) return ground;
  // The rest pose's soles lie on y = 0 in the character frame (body/morphology.h). The highest
  // ground under any of them, on a 1 cm grid over each sole (a ridge or a bump's top between
  // two grid points rises less than 0.5 mm above them at these grades).
  const Eigen::Quaterniond yaw(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY()));
  double top = -std::numeric_limits<double>::infinity();
  for (const body::Leg& leg : m.legs) {
    const body::Segment& foot = m.segments[leg.foot];
    const int nx = static_cast<int>(std::ceil(2 * foot.halfExtents.x() / 0.01));
    const int nz = static_cast<int>(std::ceil(2 * foot.halfExtents.z() / 0.01));
    for (int i = 0; i <= nx; ++i) {
      for (int k = 0; k <= nz; ++k) {
        const Eigen::Vector3d local(foot.center.x() + foot.halfExtents.x() * (2.0 * i / nx - 1), 0,
                                    foot.center.z() + foot.halfExtents.z() * (2.0 * k / nz - 1));
        const Eigen::Vector3d p = yaw * local;
        top = std::max(top, terrain_->height(x + p.x(), z + p.z()));
      }
    }
  }
  return std::isfinite(top) ? top : ground;
}

int PhysicsShards::nearestShard(const Agents& agents, double x, double z, int fallback) const {
  // Distance in the ground plane to each character's first segment (a leg frame), first of equals.
  int shard = fallback;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& a : agents) {
    const btVector3 r = a->body->body(0)->getCenterOfMassPosition();
    const double d = (r.x() - x) * (r.x() - x) + (r.z() - z) * (r.z() - z);
    if (d < best) best = d, shard = a->shard;
  }
  return shard;
}

btRigidBody* PhysicsShards::addProp(const Agents& agents, const Eigen::Vector3d& half, double mass,
                                    const Eigen::Vector3d& at, const Eigen::Quaterniond& orientation) {
  const int shard = nearestShard(agents, at.x(), at.z(), 0);
  btRigidBody* b = worlds_[shard]->addBox(half, mass, at, orientation, physics::kPropGroup,
                                          physics::kPropMask, 0.8);
  props_.push_back({b, shard});
  worlds_[shard]->reserve();  // scene building, not the next step, sizes the solver for it
  return b;
}

void PhysicsShards::removeProp(btRigidBody* body) {
  const auto prop = std::find_if(props_.begin(), props_.end(), [&](const Prop& p) { return p.body == body; });
  if (prop == props_.end()) return;
  worlds_[prop->shard]->removeBody(body);
  props_.erase(prop);
}

void PhysicsShards::rehomeProps(const Agents& agents) {
  if (count() == 1) return;
  for (Prop& p : props_) {
    const btVector3 q = p.body->getCenterOfMassPosition();
    const int shard = nearestShard(agents, q.x(), q.z(), p.shard);
    if (shard != p.shard) {
      worlds_[p.shard]->moveBodyTo(p.body, *worlds_[shard]);
      p.shard = shard;
    }
  }
}

void PhysicsShards::step(int shard) {
  for (Agent* a : shardAgents_[shard]) std::fill(std::begin(a->footContact), std::end(a->footContact), false);
  worlds_[shard]->step();
  worlds_[shard]->updateContacts();
  // The fall test here rather than after the step: in full mode it then runs on the shard's
  // thread instead of in the serial tail of the step (a ground-height query per character).
  for (Agent* a : shardAgents_[shard]) {
    if (!a->broken && !finiteState(*a->body)) a->broken = true;
    a->down = a->broken || hasFallen(*a->body, *worlds_[shard]);
    if (!a->broken) {
      const physics::SegmentState root = a->body->segmentState(a->body->morphology().legFrames[0]);
      a->lastGood = root.position;
      a->lastGoodHeading = gait::headingOf(root.orientation);
    }
  }
}

void PhysicsShards::setTerrain(std::shared_ptr<const physics::Terrain> terrain) {
  terrain_ = std::move(terrain);
  for (auto& w : worlds_) w->setTerrain(terrain_);
}

void PhysicsShards::liftPropsOutOfGround() {
  // The ground under a prop's box, at 9 points of its bounds' footprint.
  for (Prop& p : props_) {
    btVector3 lo, hi;
    p.body->getAabb(lo, hi);
    const physics::World& w = *worlds_[p.shard];
    double ground = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < 9; ++i) {
      const double fx = 0.5 * (i % 3), fz = 0.5 * (i / 3);
      ground = std::max(ground, w.terrainHeight(lo.x() + fx * (hi.x() - lo.x()),
                                                lo.z() + fz * (hi.z() - lo.z())));
    }
    const double rise = ground + 0.005 - lo.y();
    if (rise > 0) {
      btTransform t = p.body->getWorldTransform();
      t.setOrigin(t.getOrigin() + btVector3(0, static_cast<btScalar>(rise), 0));
      p.body->setWorldTransform(t);
      p.body->setInterpolationWorldTransform(t);
      p.body->activate(true);
    }
  }
}

std::pair<long, long> PhysicsShards::solverBatches() const {
  std::pair<long, long> n{0, 0};
  for (const auto& w : worlds_) {
    const auto b = w->solverBatches();
    n.first += b.first;
    n.second += b.second;
  }
  return n;
}

}  // namespace gaitlab::sim
