#include "sim/simulation.h"

#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <chrono>
#include <iterator>
#include <new>

#include "gait/defaults.h"
#include "physics/convert.h"

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

struct Fnv1a {
  uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  }
};

}  // namespace

Simulation::Simulation(int threads, uint32_t seed)
    : biped_(body::makeBiped()), quadruped_(body::makeQuadruped()), pool_(threads),
      seed_(seed ? seed : 1) {
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
  agents_.clear();  // constraints and bodies leave the world before it is destroyed
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
}

void Simulation::addRenderBody(btRigidBody* body, const BodyInfo& info) {
  info_[renderBodies_.size()] = info;
  renderBodies_.push_back({body, info});
  header_->infoVersion.fetch_add(1);
}

int Simulation::spawn(Kind kind, double x, double z, double heading) {
  if (kind == Kind::Box) {
    if (bodyCount() + 1 > kRenderCapacity) return -1;
    const Eigen::Vector3d half(0.15, 0.15, 0.15);
    btRigidBody* b = world_.addBox(
        half, 4.0, {x, 1.5, z}, Eigen::Quaterniond(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY())),
        physics::kPropGroup, physics::kPropMask, 0.8);
    addRenderBody(b, {{0.15f, 0.15f, 0.15f}, 0xe0c068ffu, -1, 0});
    return nextId_++;
  }
  const body::Morphology& m = kind == Kind::Biped ? biped_ : quadruped_;
  if (bodyCount() + static_cast<int>(m.segments.size()) > kRenderCapacity) return -1;
  const double groundY = world_.terrainHeight(x, z);
  agents_.push_back(std::make_unique<Agent>(world_, m, Eigen::Vector3d(x, groundY, z), heading));
  const int id = nextId_++;
  agentIds_.push_back(id);
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

int Simulation::characterIndex(int id) const {
  const auto it = std::find(agentIds_.begin(), agentIds_.end(), id);
  return it == agentIds_.end() ? -1 : static_cast<int>(it - agentIds_.begin());
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

void Simulation::step(int steps) {
  for (int s = 0; s < steps; ++s) {
    // The controller loop is the parallel-for (thesis §3.1, §4.3); physics is serial.
    const auto t0 = std::chrono::steady_clock::now();
    pool_.parallelFor(characterCount(), [this](int begin, int end, int) {
      for (int i = begin; i < end; ++i) control(*agents_[i]);
    });
    const auto t1 = std::chrono::steady_clock::now();
    world_.step();
    const auto t2 = std::chrono::steady_clock::now();
    controllerSeconds_ += std::chrono::duration<double>(t1 - t0).count();
    physicsSeconds_ += std::chrono::duration<double>(t2 - t1).count();
    for (auto& a : agents_) std::fill(std::begin(a->footContact), std::end(a->footContact), false);
    world_.updateContacts();
    ++stepIndex_;
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

}  // namespace gaitlab::sim
