#include "sim/simulation.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "api/limits.h"
#include "gait/derived_gait.h"
#include "gait/heading.h"
#include "sim/capacity.h"
#include "sim/state_hash.h"

namespace gaitlab::sim {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Small deterministic generator for scene building (xorshift32); std:: distributions are not
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

Simulation::Simulation(int threads, uint32_t seed, int shards)
    : seed_(seed ? seed : 1),
      bodies_{gait::shippedBody(Character::Biped), gait::shippedBody(Character::Quadruped),
              gait::shippedBody(Character::Hexapod), gait::shippedBody(Character::Octopod)},
      shards_(shards, seed_),
      stepping_(threads) {
  publish();
}

Simulation::~Simulation() {
  agents_.clear();  // constraints and bodies leave the worlds before they are destroyed
}

// ---- Scenes -------------------------------------------------------------------------------------

int Simulation::spawn(Character kind, double x, double z, double heading) {
  return spawnCharacter(kind, x, z, heading, shards_.leastPopulated());
}

void Simulation::setBody(Character kind, const body::Morphology& morphology) {
  bodies_[static_cast<int>(kind)] = morphology;
}

int Simulation::spawnBox(double x, double z, double heading) {
  if (boxRoom() < 1) return -1;
  const int id = ids_.create(-1);
  if (id < 0) return -1;
  btRigidBody* b = shards_.addProp(
      agents_, Eigen::Vector3d::Constant(0.15), 4.0, {x, 1.5, z},
      Eigen::Quaterniond(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY())));
  render_.add(b, {{0.15f, 0.15f, 0.15f}, 0xe0c068ffu, -1, 0});
  ++boxes_;
  return id;
}

int Simulation::spawnCharacter(Character kind, double x, double z, double heading, int shard) {
  if (characterRoom(kind) < 1) return -1;
  return spawnBody(bodies_[static_cast<int>(kind)], kind, x, z, heading, shard);
}

int Simulation::spawnCreature(const body::Morphology& morphology, double x, double z, double heading) {
  if (creatureRoom(morphology) < 1) return -1;
  creatures_.push_back(morphology);
  const body::Morphology& m = creatures_.back();
  const int id = spawnBody(m, gait::characterOf(m), x, z, heading, shards_.leastPopulated());
  if (id < 0) creatures_.pop_back();
  return id;
}

int Simulation::spawnBody(const body::Morphology& m, Character kind, double x, double z, double heading, int shard) {
  const int id = ids_.create(characterCount());
  if (id < 0) return -1;
  physics::World& world = shards_.world(shard);
  const double groundY = shards_.standingHeight(shard, m, x, z, heading);
  agents_.push_back(std::make_unique<Agent>(world, m, Eigen::Vector3d(x, groundY, z), heading));
  Agent& a = *agents_.back();
  a.shard = shard;
  a.id = id;
  a.kind = kind;
  shards_.addAgent(&a);
  world.reserve();  // scene building, not the next step, sizes the solver for the new figure
  // A body of more than two leg frames has no preset: it walks the gait derived from it (its kind's
  // default gait is the one derived from the kind's shipped body, gait/defaults.h).
  if (gait::derivesGait(kind)) a.controller.setGait(gait::Gait::single(gait::derivedGait(m), gait::kDerivedFromSpeed));
  render_.addCharacter(*a.body, id);
  return id;
}

int Simulation::addCharacters(Crowd crowd, int count) {
  layout_.plan(count);
  int added = 0;
  for (int i = 0; i < count; ++i) {
    const Place p = layout_.next();
    const Character kind = crowdKind(crowd, i);
    if (spawn(kind, p.x, p.z, p.heading) < 0) break;  // the render buffer is full
    agents_.back()->controller.setGoal({cruiseSpeed(kind), 0.0});
    ++added;
  }
  return added;
}

int Simulation::addApart(Character kind) {
  const Place p = layout_.apart();
  return spawn(kind, p.x, p.z, p.heading);
}

int Simulation::addApartCreature(const body::Morphology& morphology) {
  const Place p = layout_.apart();
  return spawnCreature(morphology, p.x, p.z, p.heading);
}

void Simulation::demoScene(int characters) {
  addCharacters(Crowd::Mixed, characters);
  // The boxes scatter over the grid's width, so some land among the characters.
  SceneRandom rng{seed_};
  const double width = SceneLayout::kSpacingX * std::max(1.0, std::ceil(std::sqrt(characters)));
  for (int i = 0; i < std::max(2, characters / 2); ++i) {
    const double x = (rng.next() - 0.5) * width, z = (rng.next() - 0.5) * width;
    if (spawnBox(x, z, rng.next() * kPi) < 0) break;  // no room for more
  }
  publish();
}

void Simulation::crowdScene(Crowd crowd, int characters, double spacing) {
  benchmarkCrowd(characters, spacing, [&](int i, const Place& p, int shard) {
    return spawnCharacter(crowdKind(crowd, i), p.x, p.z, p.heading, shard);
  });
}

void Simulation::creatureScene(const std::vector<body::Morphology>& bodies, int characters, double spacing) {
  const size_t first = creatures_.size();
  creatures_.insert(creatures_.end(), bodies.begin(), bodies.end());  // one of each for the whole crowd
  benchmarkCrowd(characters, spacing, [&](int i, const Place& p, int shard) {
    const body::Morphology& m = creatures_[first + static_cast<size_t>(i) % bodies.size()];
    return creatureRoom(m) < 1 ? -1 : spawnBody(m, gait::characterOf(m), p.x, p.z, p.heading, shard);
  });
}

void Simulation::benchmarkCrowd(int characters, double spacing,
                                const std::function<int(int, const Place&, int)>& spawnAt) {
  for (int i = 0; i < characters; ++i) {
    const Place p = benchmarkPlace(i, characters, spacing);
    // Contiguous chunks of the grid per shard, split like the thesis's thread chunks (§4.3).
    int shard = 0;
    while (ThreadPool::chunk(characters, shards(), shard).end <= i) ++shard;
    if (spawnAt(i, p, shard) < 0) break;
    gait::Controller& c = agents_.back()->controller;
    c.setGoal({cruiseSpeed(agents_.back()->kind), 0.0});
    c.setPhase(std::fmod(i * 0.6180339887498949, 1.0));  // golden-ratio sequence: evenly spread
  }
  publish();
}

// ---- Capacity -----------------------------------------------------------------------------------

namespace {
// Memory a body takes: measured for the biped and the quadruped (capacity.h); any other body's as
// the quadruped's in proportion to its segments.
int64_t bytesOf(const body::Morphology& m, Character kind, const body::Morphology& quadruped) {
  if (kind == Character::Biped) return kBipedBytes;
  if (kind == Character::Quadruped) return kQuadrupedBytes;
  return kQuadrupedBytes / static_cast<int64_t>(quadruped.segments.size()) * static_cast<int64_t>(m.segments.size());
}
// How many things of `bytes` and `bodies` the heap can still afford (natively: no heap limit).
int heapRoom(int64_t bytes, int bodies, int worldBodies) {
  const int64_t headroom = heapHeadroom();
  if (headroom < 0) return std::numeric_limits<int>::max();
  return static_cast<int>(std::min<int64_t>(affordable(headroom, bytes, bodies, worldBodies),
                                            std::numeric_limits<int>::max()));
}
}  // namespace

int Simulation::characterRoom(Character kind) const {
  const body::Morphology& m = bodies_[static_cast<int>(kind)];
  return roomFor(m, bytesOf(m, kind, bodies_[static_cast<int>(Character::Quadruped)]));
}

int Simulation::creatureRoom(const body::Morphology& m) const {
  return roomFor(m, bytesOf(m, gait::characterOf(m), bodies_[static_cast<int>(Character::Quadruped)]));
}

int Simulation::roomFor(const body::Morphology& m, int64_t bytes) const {
  const int segments = static_cast<int>(m.segments.size());
  const int render = (kRenderCapacity - render_.count()) / segments;
  // Every body of the scene counts towards the world's solver pools: one shard's world holds at
  // most all of them.
  return std::max(0, std::min({render, ids_.room(), heapRoom(bytes, segments, render_.count())}));
}

int Simulation::boxRoom() const {
  return std::max(0, std::min({kRenderCapacity - render_.count(), ids_.room(), limits::kMaxBoxes - boxes_,
                               heapRoom(kBoxBytes, 1, render_.count())}));
}

std::string Simulation::fullReason(std::optional<Character> kind) const {
  const bool box = !kind;
  const int segments = box ? 1 : static_cast<int>(bodies_[static_cast<int>(*kind)].segments.size());
  if (box && boxes_ >= limits::kMaxBoxes)
    return "the scene holds " + std::to_string(limits::kMaxBoxes) + " boxes, the most a simulation takes";
  if (kRenderCapacity - render_.count() < segments)
    return "the render buffer is full (" + std::to_string(kRenderCapacity) + " bodies)";
  if (ids_.room() < 1) return "every id is in use";
  return "the module's memory is nearly full (" + std::to_string(std::max<int64_t>(0, heapHeadroom()) >> 20) +
         " MiB left beside its reserve, and another " + (box ? std::string("box") : gait::characterName(*kind)) +
         " with the physics world's growth needs more)";
}

// ---- Stepping -----------------------------------------------------------------------------------

void Simulation::step(int steps) {
  if (!wander_.any()) {
    runSteps(steps);
  } else {
    // Wandering steers at fixed step indices (every kWanderPeriodSteps), whatever the batches
    // the caller steps in, so a run replays the same however it is stepped.
    while (steps > 0) {
      const int into = static_cast<int>(stepIndex() % kWanderPeriodSteps);
      if (into == 0) steerWanderers();
      const int chunk = std::min(steps, kWanderPeriodSteps - into);
      runSteps(chunk);
      steps -= chunk;
    }
  }
  publish();
}

void Simulation::runSteps(int steps) {
  stepping_.run(
      steps, characterCount(), shards(), [this](int i) { agents_[i]->control(); },
      [this] { applyDrag(); }, [this](int shard) { shards_.step(shard); },
      [this] {
        shards_.rehomeProps(agents_);
        updateFallen();
      });
}

// ---- Wandering ----------------------------------------------------------------------------------

bool Simulation::setWander(int id, double arenaRadius) {
  const bool on = arenaRadius > 0;
  if (on) wander_.setArenaRadius(arenaRadius);
  if (id == -1) {
    for (const auto& a : agents_) wander_.set(a->id, on);
    return true;
  }
  if (indexOf(id) < 0) return false;
  wander_.set(id, on);
  return true;
}

void Simulation::steerWanderers() {
  const int n = characterCount();
  std::vector<WanderBody> bodies(n);
  for (int i = 0; i < n; ++i) {
    const physics::Character& c = *agents_[i]->body;
    const auto root = c.segmentState(c.morphology().legFrames[0]);
    bodies[i] = {agents_[i]->id, root.position.x(), root.position.z(), gait::headingOf(root.orientation),
                 agents_[i]->controller.goal().speed, wander_.wanders(agents_[i]->id), fallen(i)};
  }
  for (int i = 0; i < n; ++i) {
    if (!bodies[i].wanders || bodies[i].fallen) continue;
    gait::Goal goal = agents_[i]->controller.goal();
    goal.turnRate = wanderTurnRate(bodies, i, wander_.arenaRadius(), time());
    agents_[i]->controller.setGoal(goal);
  }
}

// ---- Physics shards -----------------------------------------------------------------------------

void Simulation::setTerrain(physics::TerrainKind kind) {
  setTerrain(std::make_shared<const physics::Terrain>(kind, seed_));
}

void Simulation::setTerrain(std::shared_ptr<const physics::Terrain> terrain) {
  shards_.setTerrain(std::move(terrain));
  // Characters: each stands up anew where its leg frame is, on the new ground.
  std::vector<int> ids;
  for (const auto& a : agents_) ids.push_back(a->id);
  for (int id : ids) resetCharacter(id);
  shards_.liftPropsOutOfGround();
  publish();
}

// ---- Characters and output ----------------------------------------------------------------------

int Simulation::indexOf(int id) const {
  // A prop's id is live too, with no character index (-1).
  return ids_.value(id);
}

std::string Simulation::stateHash() const { return sim::stateHash(render_); }

}  // namespace gaitlab::sim
