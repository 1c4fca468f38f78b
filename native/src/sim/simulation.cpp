#include "sim/simulation.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <chrono>
#include <iterator>
#include <limits>
#include <new>

#include "gait/defaults.h"
#include "gait/heading.h"
#include "physics/convert.h"
#include "physics/fnv1a.h"
#include "sim/walk_trial.h"

namespace gaitlab::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Small deterministic generator for scene layout (xorshift32); std:: distributions are not
// guaranteed to give the same numbers across standard libraries (native vs Emscripten).
struct SceneRandom {
  uint32_t s;
  double next() {  // [0, 1)
    s ^= s << 13;
    s ^= s >> 17;
    s ^= s << 5;
    return (s >> 8) * (1.0 / 16777216.0);
  }
};

}  // namespace

const char* modeName(Mode mode) {
  switch (mode) {
    case Mode::Serial: return "serial";
    case Mode::Controller: return "controller";
    case Mode::Full: return "full";
  }
  return "?";
}

bool parseMode(const std::string& name, Mode* out) {
  for (Mode m : {Mode::Serial, Mode::Controller, Mode::Full}) {
    if (name == modeName(m)) {
      *out = m;
      return true;
    }
  }
  return false;
}

Simulation::Simulation(int threads, uint32_t seed, int shards)
    : biped_(body::makeBiped()), quadruped_(body::makeQuadruped()), pool_(threads),
      seed_(seed ? seed : 1) {
  if (shards < 1) shards = 1;
  // A shard holds about 1/S of the crowd's contacts; 256 pooled manifolds cover 20 fallen
  // quadrupeds (11 boxes each on the ground) before Bullet falls back to the heap.
  const int pool = shards == 1 ? physics::World::kDefaultContactPool
                               : std::max(256, physics::World::kDefaultContactPool / shards);
  for (int s = 0; s < shards; ++s) worlds_.push_back(std::make_unique<physics::World>(pool));
  terrain_ = std::make_shared<physics::Terrain>(physics::TerrainKind::Flat, seed_);
  shardAgents_.resize(shards);
  // One block: header, two matrix buffers, body info; offsets are relative to the header so the
  // layout reads the same from JavaScript (a 32-bit address space) and from native tests.
  const size_t matrixBytes = sizeof(float) * 16 * kRenderCapacity;
  const size_t total = sizeof(RenderHeader) + 2 * matrixBytes + sizeof(BodyInfo) * kRenderCapacity;
  renderMemory_.assign(total, 0);
  unsigned char* base = renderMemory_.data();
  header_ = new (base) RenderHeader{};
  header_->capacity = kRenderCapacity;
  header_->matrices[0] = sizeof(RenderHeader);
  header_->matrices[1] = static_cast<uint32_t>(sizeof(RenderHeader) + matrixBytes);
  header_->info = static_cast<uint32_t>(sizeof(RenderHeader) + 2 * matrixBytes);
  matrices_[0] = reinterpret_cast<float*>(base + header_->matrices[0]);
  matrices_[1] = reinterpret_cast<float*>(base + header_->matrices[1]);
  info_ = reinterpret_cast<BodyInfo*>(base + header_->info);
  publish();
}

Simulation::Agent::Agent(physics::World& w, const body::Morphology& m,
                         const Eigen::Vector3d& origin, double heading)
    : body(std::make_unique<physics::Character>(w, m, origin, heading)),
      controller(m, gait::defaultParams(m), heading),
      state(m.segments.size()),
      torques(m.segments.size(), Eigen::Vector3d::Zero()),
      world(&w) {
  for (size_t l = 0; l < m.legs.size(); ++l) body->setFootContactFlag(static_cast<int>(l), &footContact[l]);
}

Simulation::~Simulation() {
  agents_.clear();  // constraints and bodies leave the worlds before they are destroyed
}

void Simulation::setGoal(int i, const gait::Goal& goal) {
  if (i < 0) {
    for (auto& a : agents_) a->controller.setGoal(goal);
  } else if (i < characterCount()) {
    agents_[i]->controller.setGoal(goal);
  }
}

void Simulation::control(Agent& a) {
  // Algorithm 1 for one character: read state, compute torques, hand them to the physics.
  a.body->readState(a.state.data());
  gait::CharacterState cs;
  cs.segments = a.state.data();
  cs.footContact = a.footContact;
  cs.ground.context = a.world;
  cs.ground.height = [](const void* w, double x, double z) {
    return static_cast<const physics::World*>(w)->terrainHeight(x, z);
  };
  a.controller.update(physics::kFixedStep, cs, a.torques.data());
  a.body->applyJointTorques(a.torques.data());
  ++a.updates;
}

void Simulation::addRenderBody(btRigidBody* body, const BodyInfo& info) {
  info_[renderBodies_.size()] = info;
  renderBodies_.push_back({body, info});
  header_->infoVersion.fetch_add(1);
}

int Simulation::spawn(Kind kind, double x, double z, double heading) {
  if (kind == Kind::Box) {
    if (bodyCount() + 1 > kRenderCapacity) return -1;
    // The prop starts in the shard of the character nearest to it (rehomeProps keeps it there).
    const int shard = nearestShard(x, z, 0);
    const Eigen::Vector3d half(0.15, 0.15, 0.15);
    btRigidBody* b = worlds_[shard]->addBox(
        half, 4.0, {x, 1.5, z}, Eigen::Quaterniond(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY())),
        physics::kPropGroup, physics::kPropMask, 0.8);
    props_.push_back({b, shard});
    worlds_[shard]->reserve();
    addRenderBody(b, {{0.15f, 0.15f, 0.15f}, 0xe0c068ffu, -1, 0});
    return nextId_++;
  }
  // A character spawned one at a time goes to the least populated shard (the first of equals).
  int shard = 0;
  for (int s = 1; s < shards(); ++s)
    if (shardAgents_[s].size() < shardAgents_[shard].size()) shard = s;
  return spawnCharacter(kind, x, z, heading, shard);
}

int Simulation::spawnCharacter(Kind kind, double x, double z, double heading, int shard) {
  const body::Morphology& m = kind == Kind::Biped ? biped_ : quadruped_;
  if (bodyCount() + static_cast<int>(m.segments.size()) > kRenderCapacity) return -1;
  physics::World& world = *worlds_[shard];
  const double groundY = standingHeight(world, m, x, z, heading);
  agents_.push_back(std::make_unique<Agent>(world, m, Eigen::Vector3d(x, groundY, z), heading));
  agents_.back()->shard = shard;
  shardAgents_[shard].push_back(agents_.back().get());
  world.reserve();  // scene building, not the next step, sizes the solver for the new figure
  const int id = nextId_++;
  agents_.back()->id = id;
  agents_.back()->kind = kind;
  const physics::Character& c = *agents_.back()->body;
  for (int i = 0; i < c.segmentCount(); ++i) {
    const body::Segment& s = m.segments[i];
    addRenderBody(c.body(i), {{static_cast<float>(s.halfExtents.x()),
                               static_cast<float>(s.halfExtents.y()),
                               static_cast<float>(s.halfExtents.z())},
                              s.rgba, id, 0});
  }
  return id;
}


double Simulation::standingHeight(const physics::World& world, const body::Morphology& m,
                                  double x, double z, double heading) const {
  const double ground = world.terrainHeight(x, z);
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

void Simulation::setTerrain(physics::TerrainKind kind) {
  setTerrain(std::make_shared<const physics::Terrain>(kind, seed_));
}

void Simulation::setTerrain(std::shared_ptr<const physics::Terrain> terrain) {
  terrain_ = std::move(terrain);
  for (auto& w : worlds_) w->setTerrain(terrain_);
  // Characters: each stands up anew where its leg frame is, on the new ground.
  std::vector<int> ids;
  for (const auto& a : agents_) ids.push_back(a->id);
  for (int id : ids) resetCharacter(id);
  // Props: lifted so that their lowest point clears the highest ground under them.
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
  publish();
}

void Simulation::demoScene(int characters) {
  SceneRandom rng{seed_};
  const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(characters))));
  const double spacing = 2.5;
  for (int i = 0; i < characters; ++i) {
    const double x = (i % columns - (columns - 1) / 2.0) * spacing;
    const double z = (i / columns - (columns - 1) / 2.0) * spacing;
    spawn(i % 2 == 0 ? Kind::Biped : Kind::Quadruped, x, z, (rng.next() - 0.5) * 2 * kPi);
  }
  for (int i = 0; i < std::max(2, characters / 2); ++i) {
    spawn(Kind::Box, (rng.next() - 0.5) * spacing * columns, (rng.next() - 0.5) * spacing * columns,
          rng.next() * kPi);
  }
  publish();
}

void Simulation::crowdScene(Crowd crowd, int characters, double spacing) {
  const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(characters))));
  for (int i = 0; i < characters; ++i) {
    const double x = (i % columns - (columns - 1) / 2.0) * spacing;
    const double z = (i / columns - (columns - 1) / 2.0) * spacing;
    const Kind k = crowd == Crowd::Bipeds       ? Kind::Biped
                   : crowd == Crowd::Quadrupeds ? Kind::Quadruped
                   : i % 2 == 0                 ? Kind::Biped
                                                : Kind::Quadruped;
    // Contiguous chunks of the grid per shard, split like the thesis's thread chunks (§4.3).
    int shard = 0;
    while (ThreadPool::chunk(characters, shards(), shard).end <= i) ++shard;
    if (spawnCharacter(k, x, z, 0.0, shard) < 0) break;
    gait::Controller& c = agents_.back()->controller;
    c.setGoal({cruiseSpeed(k), 0.0});
    c.setPhase(std::fmod(i * 0.6180339887498949, 1.0));  // golden-ratio sequence: evenly spread
  }
  publish();
}

void Simulation::stepShard(int shard) {
  for (Agent* a : shardAgents_[shard]) std::fill(std::begin(a->footContact), std::end(a->footContact), false);
  worlds_[shard]->step();
  worlds_[shard]->updateContacts();
  // The fall test, here rather than in updateFallen: in full mode it then runs on the shard's
  // thread instead of in the serial tail of the step (a ground-height query per character).
  for (Agent* a : shardAgents_[shard]) a->down = hasFallen(*a->body, *worlds_[shard]);
}

int Simulation::nearestShard(double x, double z, int fallback) const {
  // Distance in the ground plane to each character's first segment (a leg frame), first of equals.
  int shard = fallback;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& a : agents_) {
    const btVector3 r = a->body->body(0)->getCenterOfMassPosition();
    const double d = (r.x() - x) * (r.x() - x) + (r.z() - z) * (r.z() - z);
    if (d < best) best = d, shard = a->shard;
  }
  return shard;
}

void Simulation::rehomeProps() {
  if (shards() == 1) return;
  for (Prop& p : props_) {
    const btVector3 q = p.body->getCenterOfMassPosition();
    const int shard = nearestShard(q.x(), q.z(), p.shard);
    if (shard != p.shard) {
      worlds_[p.shard]->moveBodyTo(p.body, *worlds_[shard]);
      p.shard = shard;
    }
  }
}

void Simulation::step(int steps) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const auto controlChunk = [this](int begin, int end, int) {
    for (int i = begin; i < end; ++i) control(*agents_[i]);
  };
  const auto physicsChunk = [this](int begin, int end, int) {
    for (int s = begin; s < end; ++s) stepShard(s);
  };
  for (int s = 0; s < steps; ++s) {
    // The controller loop is the parallel-for (thesis §3.1, §4.3), timed from before the first
    // thread starts until the last is done (§4.1).
    const auto t0 = Clock::now();
    if (mode_ == Mode::Serial) {
      controlChunk(0, characterCount(), 0);
    } else {
      pool_.parallelFor(characterCount(), controlChunk);
    }
    const auto t1 = Clock::now();
    applyDrag();
    // Physics: the shards one after another, or (full mode) each shard taken by the next free
    // thread (ThreadPool::forEach: shards differ in cost, and on a shared machine a thread may
    // start late; docs/parallel.md). Each shard computes the same thing either way; only the
    // thread that runs it differs.
    if (mode_ == Mode::Full) {
      pool_.forEach(shards(), [this](int shard) { stepShard(shard); });
    } else {
      physicsChunk(0, shards(), 0);
    }
    const auto t2 = Clock::now();
    rehomeProps();
    ++stepIndex_;
    updateFallen();
    const auto t3 = Clock::now();
    lastStep_ = {seconds(t0, t1), seconds(t1, t2), seconds(t0, t3)};
    controllerSeconds_ += lastStep_.controller;
    physicsSeconds_ += lastStep_.physics;
  }
  publish();
}

void Simulation::publish() {
  // Seqlock over two buffers (render_buffer.h): seq is bumped once when the writer starts on
  // the back buffer and once when it has published it, so a reader that sees seq advance by 2 or
  // more during its read knows the buffer it read may have been rewritten.
  const uint32_t back = 1 - header_->front.load(std::memory_order_relaxed);
  header_->seq.fetch_add(1, std::memory_order_acq_rel);
  float* m = matrices_[back];
  for (size_t i = 0; i < renderBodies_.size(); ++i) {
    const btTransform& t = renderBodies_[i].body->getCenterOfMassTransform();
    const btMatrix3x3& r = t.getBasis();
    const float* half = renderBodies_[i].info.halfExtents;
    float* o = m + 16 * i;
    // Column-major 4x4 = [R * diag(2 * half) | p], three.js Matrix4.elements order.
    for (int col = 0; col < 3; ++col) {
      const float scale = 2.0f * half[col];
      for (int row = 0; row < 3; ++row) o[col * 4 + row] = static_cast<float>(r[row][col]) * scale;
      o[col * 4 + 3] = 0.0f;
    }
    o[12] = static_cast<float>(t.getOrigin().x());
    o[13] = static_cast<float>(t.getOrigin().y());
    o[14] = static_cast<float>(t.getOrigin().z());
    o[15] = 1.0f;
  }
  header_->bodyCount[back] = static_cast<uint32_t>(renderBodies_.size());
  header_->stepIndex[back] = stepIndex_;
  header_->simTime[back] = time();
  header_->front.store(back, std::memory_order_release);
  header_->seq.fetch_add(1, std::memory_order_release);
}

std::string Simulation::stateHash() const {
  Fnv1a h;
  for (const RenderBody& rb : renderBodies_) {
    const btRigidBody* b = rb.body;
    const btTransform& t = b->getCenterOfMassTransform();
    const btQuaternion q = t.getRotation();
    const btScalar v[] = {t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z(),
                          q.x(), q.y(), q.z(), q.w(),
                          b->getLinearVelocity().x(), b->getLinearVelocity().y(),
                          b->getLinearVelocity().z(), b->getAngularVelocity().x(),
                          b->getAngularVelocity().y(), b->getAngularVelocity().z()};
    h.bytes(v, sizeof(v));
  }
  char out[17];
  std::snprintf(out, sizeof(out), "%016llx", static_cast<unsigned long long>(h.h));
  return out;
}

// ---- Interaction (the demo page, issue 5) ----------------------------------------------------

int Simulation::indexOf(int id) const {
  for (size_t i = 0; i < agents_.size(); ++i)
    if (agents_[i]->id == id) return static_cast<int>(i);
  return -1;
}

int Simulation::throwBox(const Eigen::Vector3d& from, const Eigen::Vector3d& velocity,
                         double half) {
  if (bodyCount() + 1 > kRenderCapacity) return -1;
  // Solid wood, roughly (600 kg/m³): a 0.24 m box weighs ~8 kg, enough at 10-15 m/s to knock
  // a 1.7 m biped sideways without flinging it across the scene.
  const double mass = 600.0 * std::pow(2 * half, 3);
  // Like every prop, it starts in the shard of the character nearest to it and follows its
  // nearest character from shard to shard as it flies (rehomeProps, docs/parallel.md).
  const int shard = nearestShard(from.x(), from.z(), 0);
  btRigidBody* b = worlds_[shard]->addBox(Eigen::Vector3d::Constant(half), mass, from,
                                          Eigen::Quaterniond::Identity(), physics::kPropGroup,
                                          physics::kPropMask, 0.8);
  props_.push_back({b, shard});
  worlds_[shard]->reserve();
  b->setLinearVelocity(physics::toBt(velocity));
  // Thrown boxes are the warm wood colour of the scene's boxes, a shade darker to tell them apart.
  const float h = static_cast<float>(half);
  addRenderBody(b, {{h, h, h}, 0xc08a48ffu, -1, 0});
  thrown_.push_back(b);
  if (static_cast<int>(thrown_.size()) > kMaxThrown) {
    btRigidBody* oldest = thrown_.front();
    thrown_.erase(thrown_.begin());
    removeRenderBodies({oldest});
    const auto prop = std::find_if(props_.begin(), props_.end(), [&](const Prop& q) { return q.body == oldest; });
    worlds_[prop->shard]->removeBody(oldest);
    props_.erase(prop);
  }
  return nextId_++;
}

bool Simulation::drag(int id, int segment, const Eigen::Vector3d& local,
                      const Eigen::Vector3d& target) {
  const int i = indexOf(id);
  if (i < 0 || segment < 0 || segment >= character(i).segmentCount()) return false;
  drag_ = {id, segment, local, target};
  return true;
}

void Simulation::applyDrag() {
  if (drag_.id < 0) return;
  const int i = indexOf(drag_.id);
  if (i < 0) {  // the character was removed while held
    endDrag();
    return;
  }
  btRigidBody* b = character(i).body(drag_.segment);
  const btTransform& t = b->getCenterOfMassTransform();
  const btVector3 point = t * physics::toBt(drag_.local);
  const btVector3 rel = point - t.getOrigin();
  const btVector3 v = b->getVelocityInLocalPoint(rel);
  // A critically damped spring sized for the whole character (ω = 5 rad/s: it follows the
  // pointer in about half a second), applied at one point of one segment. Explicit integration
  // at 120 Hz is stable only while k·dt²/m and c·dt/m stay below ~1 for the segment held
  // (a foot weighs ~1 kg against a 60 kg figure), hence the limits; and the force is capped at
  // three body weights, so a pointer far away pulls hard but never launches the character.
  const double mass = character(i).morphology().totalMass();
  const double segmentMass = 1.0 / std::max(1e-6, static_cast<double>(b->getInvMass()));
  const double dt = physics::kFixedStep;
  const double omega = 5.0;
  const double k = std::min(mass * omega * omega, 0.5 * segmentMass / (dt * dt));
  const double c = std::min(2.0 * 0.9 * omega * mass, 0.5 * segmentMass / dt);
  btVector3 force = static_cast<btScalar>(k) * (physics::toBt(drag_.target) - point) -
                    static_cast<btScalar>(c) * v;
  const double cap = 3.0 * mass * 9.81;
  if (force.length() > cap) force *= static_cast<btScalar>(cap / force.length());
  // As an impulse over the whole fixed step: Bullet clears applied forces after each of the
  // world's sub-steps (stepSimulation ends in clearForces), so a force would act on the first only.
  b->applyImpulse(force * static_cast<btScalar>(dt), rel);
}

bool Simulation::resetCharacter(int id) {
  const int i = indexOf(id);
  if (i < 0) return false;
  Agent& old = *agents_[i];
  const body::Morphology& m = old.body->morphology();
  const int root = m.legFrames[0];
  const physics::SegmentState s = old.body->segmentState(root);
  const double heading = gait::headingOf(s.orientation);
  // The rest pose puts the root at `center` in the character frame: place the new figure so
  // that its root stands where the old one's is now.
  const Eigen::Vector3d offset =
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY()) * m.segments[root].center;
  const double x = s.position.x() - offset.x(), z = s.position.z() - offset.z();
  const gait::GaitParams params = old.controller.params();
  const gait::Goal goal = old.controller.goal();
  const Kind kind = old.kind;
  std::vector<btRigidBody*> oldBodies;
  for (int k = 0; k < old.body->segmentCount(); ++k) oldBodies.push_back(old.body->body(k));

  physics::World& world = *worlds_[old.shard];
  auto fresh = std::make_unique<Agent>(
      world, m, Eigen::Vector3d(x, standingHeight(world, m, x, z, heading), z), heading);
  fresh->id = id;
  fresh->kind = kind;
  fresh->shard = old.shard;
  std::replace(shardAgents_[old.shard].begin(), shardAgents_[old.shard].end(), &old, fresh.get());
  fresh->controller.setParams(params);
  fresh->controller.setGoal(goal);
  // Same morphology, same number of bodies in the same order: the render entries keep their
  // places and colours and only point at the new bodies.
  int k = 0;
  for (RenderBody& rb : renderBodies_)
    if (rb.info.owner == id) rb.body = fresh->body->body(k++);
  agents_[i] = std::move(fresh);  // the old character's bodies leave the world here
  if (drag_.id == id) endDrag();
  return true;
}

bool Simulation::removeCharacter(int id) {
  const int i = indexOf(id);
  if (i < 0) return false;
  std::vector<btRigidBody*> bodies;
  for (int k = 0; k < agents_[i]->body->segmentCount(); ++k) bodies.push_back(agents_[i]->body->body(k));
  removeRenderBodies(bodies);
  auto& inShard = shardAgents_[agents_[i]->shard];
  inShard.erase(std::find(inShard.begin(), inShard.end(), agents_[i].get()));
  agents_.erase(agents_.begin() + i);
  if (drag_.id == id) endDrag();
  return true;
}

void Simulation::removeRenderBodies(const std::vector<btRigidBody*>& bodies) {
  const auto gone = [&](const RenderBody& rb) {
    return std::find(bodies.begin(), bodies.end(), rb.body) != bodies.end();
  };
  renderBodies_.erase(std::remove_if(renderBodies_.begin(), renderBodies_.end(), gone),
                      renderBodies_.end());
  for (size_t i = 0; i < renderBodies_.size(); ++i) info_[i] = renderBodies_[i].info;
  // After the entries: a reader that saw the old version reads them again (render_buffer.h).
  header_->infoVersion.fetch_add(1);
}

void Simulation::updateFallen() {
  const double now = time();
  std::vector<int> toReset;
  for (int i = 0; i < characterCount(); ++i) {
    Agent& a = *agents_[i];
    if (!a.down) {
      a.fallenSince = -1;
      continue;
    }
    if (a.fallenSince < 0) a.fallenSince = now;
    if (autoResetSeconds_ > 0 && now - a.fallenSince >= autoResetSeconds_) toReset.push_back(a.id);
  }
  for (int id : toReset) resetCharacter(id);
}

}  // namespace gaitlab::sim
