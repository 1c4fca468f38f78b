// Probe: Bullet's Featherstone articulated bodies (btMultiBody, btMultiBodyDynamicsWorld) against
// gaitlab's rigid bodies joined by constraints, on the peer benchmark's reference scene
// (peers/reference_scene.h, docs/peers.md). It measures whether reduced coordinates would cut
// the physics cost per character, the cost the crowd benchmark's capacity goals depend on
// (docs/parallel.md, "Where the physics time goes": the solver's joint rows are most of it). It
// changes nothing in the simulation: both scenes are built here side by side and timed in one
// process, in turns.
//
// The multibody scene is the reference scene with another representation of the same bodies:
// one btMultiBody per character, its base the morphology's root segment (floating), one link per
// other segment with the same box, mass, inertia (armature included: body/morphology.h) and pivot;
// one btMultiBodyLinkCollider per link, on the same ground plane with the same friction, gravity,
// collision groups (characters touch the ground only: physics/world.h), contact pools, grid, fixed
// step (two Bullet sub-steps of 1/240 s per 1/120 s step) and solver iterations (10), and the same
// explicit PD torques (peers::holdingMotors, gait::jointPd) computed once per fixed step from the
// bodies' world states and applied as generalised joint forces before each sub-step. What differs
// is what the joints are:
//
//   body::Morphology   gaitlab (physics/character.cpp)              here
//   Hinge (knees)      btHingeConstraint, limit row at the limit     revolute link (setupRevolute)
//                                                                    + btMultiBodyJointLimitConstraint
//   Universal (ankles) btGeneric6DofSpring2 (physics::Joint): 3      two revolute links, pitch (x) then
//                      locked translations, locked y, x/z limit rows roll (z), through an intermediate
//                      near a limit                                  link of 1 g, 1e-6 kg·m², no collider;
//                                                                    each revolute with a
//                                                                    btMultiBodyJointLimitConstraint
//   Ball (hips, spine) btGeneric6DofSpring2 (physics::Joint): 3      spherical link (setupSpherical)
//                      locked translations, Euler-XYZ limit rows     + btMultiBodySphericalJointLimit
//                      near a limit                                  (symmetric swing x, swing y,
//                                                                    twist z: ±min(|lower|, |upper|))
//
// The universal as two revolutes is exactly gaitlab's joint: btGeneric6DofSpring2Constraint's
// RO_XYZ rotation with its y angle locked is Rx(pitch)·Rz(roll), the child relative to the parent,
// which is what a revolute about x followed by one about the rotated z composes; the locked axis
// then costs nothing (Featherstone's coordinates have no such direction), and the limits keep
// their asymmetric bounds. A spherical link limited by btMultiBodySphericalJointLimit would give
// the ankle a third, free-but-limited axis (its twist about z; the ankle's locked axis is y).
// Bullet 3.24's spherical limit is symmetric per axis and ignores its position target, so the
// biped's hip flexion range (−2.0 to 0.7 rad) becomes ±0.7 here; in the standing scene no limit is
// reached on either side (largestPoseError, printed by `stand`).
//
// The torques held for the whole 1/120 s step: with them the multibody quadruped diverges within
// 0.25 s, its spine first (pose error doubling about every two steps), while gaitlab's rigid
// quadruped stands; its bipeds stand. Recomputed before each 1/240 s sub-step (variant modifier
// `pd240`), the multibody quadruped stands. The quadruped's spine gains (kp 629.8, kd 1.444) are
// close to what a torque held over two sub-steps allows at all: for one joint of inertia I, the
// scheme is stable only while kd > kp·Δt/4 (1.31 here), whatever I. That gaitlab's rigid bodies
// stay stable there is from its constraint solve, not from these gains (inference).
//
// Featherstone's articulated-body algorithm (Featherstone 1987, "Robot Dynamics Algorithms";
// Featherstone 2008, "Rigid Body Dynamics Algorithms" ch. 7) gives each character's unconstrained
// accelerations in O(links) with no joint rows at all: what the solver sees are the contacts and
// the limits actually reached. Bullet solves those by sequential impulses on the multibody's
// generalised velocities (btMultiBodyConstraintSolver, Bullet's btMultiBody.cpp for the Jacobians
// and the "deltaV" response through the tree).
//
// Built only on request:
//
//   ninja -C build/native gaitlab_multibody_scene
//   build/native/gaitlab_multibody_scene stand LEGS CHARACTERS [SECONDS [VARIANTS [EVERY]]]
//       root height (ReferenceScene::meanRootHeight) and largest pose error of each variant (default
//       gaitlab,mb) every EVERY steps (default 30)
//   build/native/gaitlab_multibody_scene time LEGS CHARACTERS [STEPS [ROUNDS [VARIANTS [SETTLE]]]]
//       CPU time per fixed step of each variant, in turns in one process (order reversed every other
//       round), each round a fresh scene, SETTLE untimed steps (30, as the peer benchmark), then STEPS
//       timed (120; 5 rounds); VARIANTS (gaitlab,mb) a comma list of
//       gaitlab (one world), gaitlab16 (16 worlds, as the crowd's shards), mb (one multibody world)
//       or mb16, each with modifiers joined by '+': pd240 (the PD torques recomputed before each
//       sub-step, see `stand`), nogyro (setUseGyroTerm(false)), rk4 (useRK4Integration(true)),
//       nolimits (no limit constraints), it40 (40 solver iterations); e.g. mb16+pd240+nogyro
//   build/native/gaitlab_multibody_scene run VARIANT LEGS CHARACTERS STEPS
//       one variant alone, for `perf record -g`
//
// Times are the calling thread's CPU time (probe.h), so other processes on the machine do not
// count; everything runs on that one thread. The WebAssembly build (native/CMakeLists.txt) runs in
// Node with the same arguments, timed with the wall clock:
//
//   emcmake cmake -S native -B build/wasm -G Ninja && ninja -C build/wasm gaitlab_multibody_scene
//   node --no-experimental-fetch build/wasm/gaitlab_multibody_scene.cjs time 4 100
//
// (Debian's emcc needs NODE_PATH=/usr/share/nodejs to link, as scripts/lib.sh sets it; Emscripten
// 3.1.6's loader fetches its .wasm when Node has fetch, which fails on a file path.)
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <BulletDynamics/Featherstone/btMultiBodySphericalJointLimit.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "body/morphology.h"
#include "gait/pd.h"
#include "peers/reference_scene.h"
#include "physics/convert.h"
#include "physics/world.h"
#include "probe.h"
#include "sim/scene_layout.h"
#include "sim/thread_pool.h"

namespace {

using namespace gaitlab;
using physics::toBt;
using physics::toEigen;

// The timing clock: the calling thread's CPU time natively (probe.h). Emscripten's clock_gettime
// has no CPU-time clocks (it fails with EINVAL), so the WebAssembly build takes the monotonic wall
// clock: in Node the figures then include time the thread was preempted.
#ifdef __EMSCRIPTEN__
#define GAITLAB_TIME_KEY "wall_ms_per_step"
#else
#define GAITLAB_TIME_KEY "cpu_ms_per_step"
#endif
double clockSeconds() {
#ifdef __EMSCRIPTEN__
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
#else
  return probe::threadSeconds();
#endif
}

// The universal joint's intermediate link (between its two revolutes): next to nothing, so that
// the foot's dynamics are the foot's. Featherstone's recursion needs no mass there (the foot's
// articulated inertia makes both joints' D = sᵀIᴬs positive), 1 g keeps it clear of degenerate
// cases.
constexpr btScalar kMidMass = 0.001f, kMidInertia = 1e-6f;
// gaitlab's limit rows have no bound on their impulse (Bullet's rigid-body limits); Bullet's
// multibody limits default to 100 N·s.
constexpr btScalar kUnbounded = 1e18f;

struct Options {
  bool gyro = true;    // btMultiBody::setUseGyroTerm: Bullet's default
  bool rk4 = false;    // btMultiBody::useRK4Integration: Bullet's default
  bool limits = true;  // the joint limit constraints
  bool pdEverySubstep = false;  // the PD torques recomputed before each sub-step (240 Hz)
  int iterations = physics::kSolverIterations;
};

// One Bullet world for multibodies, as physics::World is one for rigid bodies: the same collision
// configuration and pools, broadphase, gravity, iterations, ground plane and filter groups.
class MultiBodyWorld {
 public:
  MultiBodyWorld(int contactPool, int iterations) {
    btDefaultCollisionConstructionInfo info;
    info.m_defaultMaxPersistentManifoldPoolSize = contactPool;
    info.m_defaultMaxCollisionAlgorithmPoolSize = contactPool;
    config_ = std::make_unique<btDefaultCollisionConfiguration>(info);
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btMultiBodyConstraintSolver>();
    dynamics_ = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                           solver_.get(), config_.get());
    dynamics_->setGravity(btVector3(0, -9.81f, 0));
    dynamics_->getSolverInfo().m_numIterations = iterations;
    // As physics::DiscreteWorld: bounding boxes at the present transforms, no CCD.
    dynamics_->getDispatchInfo().m_useContinuous = false;
    ground_shape_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0);
    btRigidBody::btRigidBodyConstructionInfo g(0, nullptr, ground_shape_.get());
    g.m_friction = 1.0f;
    ground_ = std::make_unique<btRigidBody>(g);
    dynamics_->addRigidBody(ground_.get(), physics::kGroundGroup, physics::kGroundMask);
  }
  ~MultiBodyWorld() { dynamics_->removeRigidBody(ground_.get()); }
  btMultiBodyDynamicsWorld& dynamics() { return *dynamics_; }

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btMultiBodyConstraintSolver> solver_;
  std::unique_ptr<btMultiBodyDynamicsWorld> dynamics_;
  std::unique_ptr<btCollisionShape> ground_shape_;
  std::unique_ptr<btRigidBody> ground_;
};

class Scene {
 public:
  virtual ~Scene() = default;
  virtual void step(int steps) = 0;
  virtual double meanRootHeight() const = 0;
  virtual double largestPoseError() const = 0;
  // Contact points per character in the worlds' manifolds (−1: not counted here).
  virtual double contactPoints() const { return -1; }
};

class GaitlabScene final : public Scene {
 public:
  GaitlabScene(gait::Character c, int n, int shards) : scene_(c, n, 1, shards) {}
  void step(int steps) override { scene_.step(steps); }
  double meanRootHeight() const override { return scene_.meanRootHeight(); }
  double largestPoseError() const override { return scene_.largestPoseError(); }

 private:
  peers::ReferenceScene scene_;
};

// The reference scene with one btMultiBody per character.
class MultiBodyScene final : public Scene {
 public:
  MultiBodyScene(gait::Character character, int characters, int worlds, const Options& options,
                 double spacing = 2.5)
      : morphology_(character == gait::Character::Biped ? body::makeBiped() : body::makeQuadruped()),
        motors_(peers::holdingMotors(character)),
        options_(options) {
    // Contact pools as peers::ReferenceScene sizes them.
    const int pool = worlds == 1 ? physics::World::kDefaultContactPool
                                 : std::max(256, physics::World::kDefaultContactPool / worlds);
    for (int w = 0; w < worlds; ++w) worlds_.push_back(std::make_unique<MultiBodyWorld>(pool, options.iterations));
    byWorld_.resize(worlds);
    for (int i = 0; i < characters; ++i) {
      int w = 0;
      while (w + 1 < worlds && i >= sim::ThreadPool::chunk(characters, worlds, w).end) ++w;
      const sim::Place p = sim::benchmarkPlace(i, characters, spacing);
      addRagdoll(w, Eigen::Vector3d(p.x, 0, p.z), p.heading);
      byWorld_[w].push_back(i);
    }
  }

  ~MultiBodyScene() override {
    for (Ragdoll& r : ragdolls_) {
      btMultiBodyDynamicsWorld& d = worlds_[r.world]->dynamics();
      for (auto& c : r.limits) d.removeMultiBodyConstraint(c.get());
      for (auto& c : r.colliders) d.removeCollisionObject(c.get());
      d.removeMultiBody(r.body.get());
    }
  }

  void step(int steps) override {
    const auto h = static_cast<btScalar>(physics::kFixedStep / physics::kPhysicsSubsteps);
    for (int k = 0; k < steps; ++k) {
      for (size_t w = 0; w < worlds_.size(); ++w) {
        for (int sub = 0; sub < physics::kPhysicsSubsteps; ++sub) {
          if (sub == 0 || options_.pdEverySubstep)
            for (int i : byWorld_[w]) holdPose(&ragdolls_[i]);
          // stepSimulation clears the applied forces (clearForces), so the step's torques are
          // applied again before every sub-step, as physics::World::step does.
          for (int i : byWorld_[w]) {
            Ragdoll& r = ragdolls_[i];
            for (const JointForce& f : r.forces) r.body->addJointTorqueMultiDof(f.link, f.dof, f.q);
          }
          worlds_[w]->dynamics().stepSimulation(h, 0, h);
        }
      }
    }
  }

  double meanRootHeight() const override {
    if (ragdolls_.empty()) return 0;
    double sum = 0;
    for (const Ragdoll& r : ragdolls_) sum += r.body->getBasePos().y();  // the base: legFrames[0]
    return sum / static_cast<double>(ragdolls_.size());
  }

  double contactPoints() const override {
    long points = 0;
    for (const auto& w : worlds_) {
      btDispatcher* d = w->dynamics().getDispatcher();
      for (int i = 0; i < d->getNumManifolds(); ++i) points += d->getManifoldByIndexInternal(i)->getNumContacts();
    }
    return ragdolls_.empty() ? 0 : static_cast<double>(points) / static_cast<double>(ragdolls_.size());
  }

  double largestPoseError() const override {
    double largest = 0;
    for (const Ragdoll& r : ragdolls_) {
      for (size_t s = 0; s < morphology_.segments.size(); ++s) {
        const int parent = morphology_.segments[s].parent;
        if (parent < 0) continue;
        const Eigen::Quaterniond a = orientation(r, parent), b = orientation(r, static_cast<int>(s));
        largest = std::max(largest, gait::rotationVector(a.conjugate() * b).norm());
      }
    }
    return largest;
  }

 private:
  struct JointForce {
    int link, dof;
    btScalar q;
  };
  struct Ragdoll {
    std::unique_ptr<btMultiBody> body;
    int world = 0;
    std::vector<int> link;  // per segment: its multibody link, −1 for the base
    std::vector<int> mid;   // per universal segment: the intermediate link, else −1
    std::vector<std::unique_ptr<btBoxShape>> shapes;
    std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders;  // per segment
    std::vector<std::unique_ptr<btMultiBodyConstraint>> limits;
    std::vector<JointForce> forces;  // this fixed step's generalised joint forces
    std::vector<btVector3> omega, vel;  // scratch: compTreeLinkVelocities
  };

  static Eigen::Quaterniond orientation(const Ragdoll& r, int segment) {
    return toEigen(r.colliders[segment]->getWorldTransform().getRotation());
  }

  void addRagdoll(int world, const Eigen::Vector3d& origin, double heading) {
    const body::Morphology& m = morphology_;
    const int n = static_cast<int>(m.segments.size());
    const Eigen::Quaterniond yaw(Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitY()));
    Ragdoll r;
    r.world = world;
    r.link.assign(n, -1);
    r.mid.assign(n, -1);
    // Links in the morphology's order (every parent precedes its children, as btMultiBody wants),
    // a universal joint's intermediate link just before its segment's.
    int links = 0;
    for (int s = 0; s < n; ++s) {
      if (m.segments[s].parent < 0) {
        if (s != 0) std::abort();  // the root is segment 0 in both morphologies
        continue;
      }
      if (m.segments[s].joint.type == body::JointType::Universal) r.mid[s] = links++;
      r.link[s] = links++;
    }
    // Boxes and inertias exactly as physics::World::addBox and physics::Character make them: the
    // same margin, Bullet's box inertia, each principal moment raised to the armature.
    std::vector<btVector3> inertia(n);
    for (int s = 0; s < n; ++s) {
      const body::Segment& seg = m.segments[s];
      auto box = std::make_unique<btBoxShape>(toBt(seg.halfExtents));
      box->setMargin(static_cast<btScalar>(std::min(0.01, 0.2 * seg.halfExtents.minCoeff())));
      btVector3 i;
      box->calculateLocalInertia(static_cast<btScalar>(seg.mass), i);
      for (int a = 0; a < 3; ++a) i[a] = std::max(static_cast<btScalar>(m.armature), i[a]);
      inertia[s] = i;
      r.shapes.push_back(std::move(box));
    }
    const body::Segment& root = m.segments[0];
    r.body = std::make_unique<btMultiBody>(links, static_cast<btScalar>(root.mass), inertia[0],
                                           /*fixedBase=*/false, /*canSleep=*/false);
    btMultiBody* mb = r.body.get();
    const btQuaternion identity = btQuaternion::getIdentity();
    for (int s = 1; s < n; ++s) {
      const body::Segment& seg = m.segments[s];
      const body::Joint& j = seg.joint;
      const int parentLink = r.link[seg.parent];
      // At rest every segment is unrotated (body/morphology.h): parent, joint and child frames are
      // the character frame, so offsets are plain differences of rest positions.
      const btVector3 parentComToPivot = toBt(j.pivot - m.segments[seg.parent].center);
      const btVector3 pivotToCom = toBt(seg.center - j.pivot);
      const auto mass = static_cast<btScalar>(seg.mass);
      switch (j.type) {
        case body::JointType::Hinge:
          mb->setupRevolute(r.link[s], mass, inertia[s], parentLink, identity, toBt(j.axes[0]),
                            parentComToPivot, pivotToCom, false);
          break;
        case body::JointType::Universal:
          mb->setupRevolute(r.mid[s], kMidMass, btVector3(kMidInertia, kMidInertia, kMidInertia), parentLink,
                            identity, toBt(j.axes[0]), parentComToPivot, btVector3(0, 0, 0), false);
          mb->setupRevolute(r.link[s], mass, inertia[s], r.mid[s], identity, toBt(j.axes[1]),
                            btVector3(0, 0, 0), pivotToCom, false);
          break;
        case body::JointType::Ball:
          mb->setupSpherical(r.link[s], mass, inertia[s], parentLink, identity, parentComToPivot,
                             pivotToCom, false);
          break;
        case body::JointType::Root:
          std::abort();
      }
    }
    mb->finalizeMultiDof();
    mb->setBasePos(toBt(Eigen::Vector3d(origin + yaw * root.center)));
    mb->setWorldToBaseRot(toBt(yaw).inverse());
    mb->setLinearDamping(0);  // Bullet's default is 0.04; no gaitlab body is damped
    mb->setAngularDamping(0);
    mb->setHasSelfCollision(false);
    mb->setUseGyroTerm(options_.gyro);
    mb->useRK4Integration(options_.rk4);
    btMultiBodyDynamicsWorld& d = worlds_[world]->dynamics();
    d.addMultiBody(mb);

    for (int s = 0; s < n; ++s) {
      const std::string& name = m.segments[s].name;
      // Feet get more friction than the rest, as in physics::Character.
      const bool isFoot = name.size() > 5 && name.compare(name.size() - 5, 5, ".foot") == 0;
      auto c = std::make_unique<btMultiBodyLinkCollider>(mb, r.link[s]);
      c->setCollisionShape(r.shapes[s].get());
      c->setFriction(isFoot ? 1.0f : 0.6f);
      c->setActivationState(DISABLE_DEACTIVATION);
      if (r.link[s] < 0)
        mb->setBaseCollider(c.get());
      else
        mb->getLink(r.link[s]).m_collider = c.get();
      r.colliders.push_back(std::move(c));
    }
    btAlignedObjectArray<btQuaternion> worldToLocal;
    btAlignedObjectArray<btVector3> localOrigin;
    mb->forwardKinematics(worldToLocal, localOrigin);
    mb->updateCollisionObjectWorldTransforms(worldToLocal, localOrigin);
    for (auto& c : r.colliders)
      d.addCollisionObject(c.get(), physics::kCharacterGroup, physics::kCharacterMask);

    if (options_.limits) {
      for (int s = 1; s < n; ++s) {
        const body::Joint& j = m.segments[s].joint;
        auto limit = [&](int link, int dof) {
          auto* c = new btMultiBodyJointLimitConstraint(mb, link, static_cast<btScalar>(j.lower[dof]),
                                                        static_cast<btScalar>(j.upper[dof]));
          c->setMaxAppliedImpulse(kUnbounded);
          r.limits.emplace_back(c);
        };
        switch (j.type) {
          case body::JointType::Hinge: limit(r.link[s], 0); break;
          case body::JointType::Universal:
            limit(r.mid[s], 0);
            limit(r.link[s], 1);
            break;
          case body::JointType::Ball: {
            btScalar range[3];
            for (int a = 0; a < 3; ++a)
              range[a] = static_cast<btScalar>(std::min(std::fabs(j.lower[a]), std::fabs(j.upper[a])));
            r.limits.emplace_back(new btMultiBodySphericalJointLimit(mb, r.link[s], range[0], range[1],
                                                                     range[2], kUnbounded));
            break;
          }
          case body::JointType::Root: break;
        }
      }
      for (auto& c : r.limits) {
        c->finalizeMultiDof();
        d.addMultiBodyConstraint(c.get());
      }
    }
    r.omega.resize(links + 1);
    r.vel.resize(links + 1);
    r.forces.reserve(3 * n);
    ragdolls_.push_back(std::move(r));
  }

  // peers::ReferenceScene::holdPose for a multibody: every segment's world orientation (its
  // collider's transform, updated at the end of each step) and world angular velocity (Bullet's
  // per-link velocities in link frames, rotated to the world), the same joint PD torque τ (world
  // frame, +τ on the child, −τ on the parent), then τ as generalised forces: the pair's virtual
  // work on each of the joint's own coordinates, Q = τ·axis (for a spherical joint its three axes
  // are the child's frame: Q = Rᵀτ). The pair does no work on any other joint's coordinates.
  void holdPose(Ragdoll* r) const {
    const body::Morphology& m = morphology_;
    const int n = static_cast<int>(m.segments.size());
    btMultiBody* mb = r->body.get();
    mb->compTreeLinkVelocities(r->omega.data(), r->vel.data());
    Eigen::Quaterniond q[32];
    Eigen::Vector3d w[32];
    for (int s = 0; s < n; ++s) {
      const btQuaternion rot = r->colliders[s]->getWorldTransform().getRotation();
      q[s] = toEigen(rot);
      w[s] = toEigen(quatRotate(rot, r->omega[r->link[s] + 1]));
    }
    r->forces.clear();
    for (int s = 1; s < n; ++s) {
      const int parent = m.segments[s].parent;
      const Eigen::Vector3d tau = gait::jointPd(motors_[s].kp, motors_[s].kd, q[parent], q[s],
                                                Eigen::Quaterniond::Identity(), w[parent], w[s]);
      const btVector3 t = toBt(tau);
      const int link = r->link[s];
      const btQuaternion child = toBt(q[s]);
      switch (m.segments[s].joint.type) {
        case body::JointType::Ball: {
          const btVector3 local = quatRotate(child.inverse(), t);
          for (int dof = 0; dof < 3; ++dof) r->forces.push_back({link, dof, local[dof]});
          break;
        }
        case body::JointType::Hinge:
          r->forces.push_back({link, 0, t.dot(quatRotate(child, mb->getLink(link).getAxisTop(0)))});
          break;
        case body::JointType::Universal: {
          // The first revolute's axis turns with the parent (a rotation about x keeps x).
          const int mid = r->mid[s];
          r->forces.push_back({mid, 0, t.dot(quatRotate(toBt(q[parent]), mb->getLink(mid).getAxisTop(0)))});
          r->forces.push_back({link, 0, t.dot(quatRotate(child, mb->getLink(link).getAxisTop(0)))});
          break;
        }
        case body::JointType::Root: break;
      }
    }
  }

  body::Morphology morphology_;
  std::vector<peers::Motor> motors_;
  Options options_;
  std::vector<std::unique_ptr<MultiBodyWorld>> worlds_;
  std::vector<Ragdoll> ragdolls_;
  std::vector<std::vector<int>> byWorld_;
};

// "a,b,c" -> {"a", "b", "c"} (as optimize/settings.cpp splits its lists), with any separator.
std::vector<std::string> split(const std::string& text, char separator = ',') {
  std::vector<std::string> parts;
  for (size_t begin = 0;;) {
    const size_t at = text.find(separator, begin);
    parts.push_back(text.substr(begin, at - begin));
    if (at == std::string::npos) return parts;
    begin = at + 1;
  }
}

std::unique_ptr<Scene> makeScene(const std::string& variant, gait::Character c, int n) {
  if (variant == "gaitlab") return std::make_unique<GaitlabScene>(c, n, 1);
  if (variant == "gaitlab16") return std::make_unique<GaitlabScene>(c, n, 16);
  // "mb" or "mb16", then modifiers joined by '+': pd240, nogyro, rk4, nolimits, it40.
  Options o;
  int worlds = 1;
  const std::vector<std::string> parts = split(variant, '+');
  if (parts[0] == "mb16")
    worlds = 16;
  else if (parts[0] != "mb")
    return nullptr;
  for (size_t i = 1; i < parts.size(); ++i) {
    if (parts[i] == "pd240")
      o.pdEverySubstep = true;
    else if (parts[i] == "nogyro")
      o.gyro = false;
    else if (parts[i] == "rk4")
      o.rk4 = true;
    else if (parts[i] == "nolimits")
      o.limits = false;
    else if (parts[i] == "it40")
      o.iterations = 40;
    else
      return nullptr;
  }
  return std::make_unique<MultiBodyScene>(c, n, worlds, o);
}

int usage(const char* self) {
  std::fprintf(stderr,
               "usage: %s stand LEGS CHARACTERS [SECONDS [VARIANTS [EVERY]]]\n"
               "       %s time LEGS CHARACTERS [STEPS [ROUNDS [VARIANTS [SETTLE]]]]\n"
               "       %s run VARIANT LEGS CHARACTERS STEPS\n"
               "VARIANTS: comma list of gaitlab, gaitlab16, mb or mb16 with modifiers +pd240 +nogyro +rk4 +nolimits +it40\n",
               self, self, self);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) return usage(argv[0]);
  const std::string mode = argv[1];
  const bool run = mode == "run";
  if (run && argc < 6) return usage(argv[0]);
  const int legs = std::atoi(argv[run ? 3 : 2]);
  const int characters = std::atoi(argv[run ? 4 : 3]);
  if ((legs != 2 && legs != 4) || characters < 1) return usage(argv[0]);
  const auto character = legs == 2 ? gait::Character::Biped : gait::Character::Quadruped;

  if (mode == "stand") {
    const double seconds = argc > 4 ? std::atof(argv[4]) : 2.0;
    const double standing = (legs == 2 ? body::makeBiped() : body::makeQuadruped()).standingHeight();
    for (const std::string& v : split(argc > 5 ? argv[5] : "gaitlab,mb")) {
      auto scene = makeScene(v, character, characters);
      if (!scene) return usage(argv[0]);
      std::printf("{\"scene\": \"%s\", \"legs\": %d, \"characters\": %d, \"standing_height\": %.4f, \"t\": [",
                  v.c_str(), legs, characters, standing);
      const int steps = static_cast<int>(std::lround(seconds / physics::kFixedStep));
      const int every = argc > 6 ? std::atoi(argv[6]) : 30;
      for (int k = 0; k <= steps; k += every) {
        std::printf("%s{\"s\": %.2f, \"root_height\": %.4f, \"pose_error\": %.4f, \"contact_points\": %.2f}",
                    k ? ", " : "", k * physics::kFixedStep, scene->meanRootHeight(), scene->largestPoseError(),
                    scene->contactPoints());
        if (k < steps) scene->step(std::min(every, steps - k));
      }
      std::printf("]}\n");
    }
    return 0;
  }

  if (run) {
    auto scene = makeScene(argv[2], character, characters);
    if (!scene) return usage(argv[0]);
    const int steps = std::atoi(argv[5]);
    scene->step(30);
    const double t0 = clockSeconds();
    scene->step(steps);
    std::printf("{\"variant\": \"%s\", \"" GAITLAB_TIME_KEY "\": %.3f, \"root_height\": %.4f}\n", argv[2],
                1e3 * (clockSeconds() - t0) / steps, scene->meanRootHeight());
    return 0;
  }

  if (mode != "time") return usage(argv[0]);
  const int steps = argc > 4 ? std::atoi(argv[4]) : 120;
  const int rounds = argc > 5 ? std::atoi(argv[5]) : 5;
  const std::vector<std::string> variants = split(argc > 6 ? argv[6] : "gaitlab,mb");
  const int settle = argc > 7 ? std::atoi(argv[7]) : 30;
  for (const std::string& v : variants)
    if (!makeScene(v, character, 1)) return usage(argv[0]);
  // Every variant's code runs once untimed first (a small scene), so that the WebAssembly build
  // has compiled it with its optimising tier before the first round, as the peer benchmark does.
  for (const std::string& v : variants) makeScene(v, character, std::min(characters, 4))->step(60);
  std::vector<std::vector<double>> ms(variants.size());
  std::vector<std::vector<double>> height(variants.size());
  for (int round = 0; round < rounds; ++round) {
    for (size_t k = 0; k < variants.size(); ++k) {
      const size_t v = round % 2 == 0 ? k : variants.size() - 1 - k;
      auto scene = makeScene(variants[v], character, characters);
      scene->step(settle);  // the first contacts: 30 steps, as the peer benchmark settles them
      const double t0 = clockSeconds();
      scene->step(steps);
      ms[v].push_back(1e3 * (clockSeconds() - t0) / steps);
      height[v].push_back(scene->meanRootHeight());
    }
  }
  for (size_t v = 0; v < variants.size(); ++v) {
    // Per round, this variant's step over the first variant's, taken in the same round.
    std::vector<double> ratio;
    for (int r = 0; r < rounds; ++r) ratio.push_back(ms[v][r] / ms[0][r]);
    std::vector<double> sorted = ms[v];
    std::sort(sorted.begin(), sorted.end());
    std::printf("{\"legs\": %d, \"characters\": %d, \"variant\": \"%s\", \"steps\": %d, \"rounds\": %d, "
                "\"" GAITLAB_TIME_KEY "\": %.3f, \"min\": %.3f, \"max\": %.3f, \"ratio_to_%s\": %.3f, "
                "\"ratio_min\": %.3f, \"ratio_max\": %.3f, \"root_height\": %.4f, \"settle\": %d}\n",
                legs, characters, variants[v].c_str(), steps, rounds, probe::quantile(ms[v], 0.5), sorted.front(),
                sorted.back(), variants[0].c_str(), probe::quantile(ratio, 0.5),
                *std::min_element(ratio.begin(), ratio.end()), *std::max_element(ratio.begin(), ratio.end()),
                height[v].back(), settle);
  }
  return 0;
}
