// Probe, built only on request (`ninja -C build/native gaitlab_crowd_throw_log`): the demo's
// shift-click throw at a walking biped in the demo's crowd, many times over, and what the box
// touched first (docs/design.md, "Physics modelling": a throw at a character).
//
//   build/native/gaitlab_crowd_throw_log [THROWS] [wander|straight] [DISTANCE] > log.txt
//
// The demo's opening scene: 24 characters, bipeds and quadrupeds in turn, each at its type's
// cruise speed, wandering in an arena of 12 m (or, with `straight`, keeping the goal they were
// given). Ten throws a scene, the camera a little further round the arena each scene: every
// 0.5 s the next walking biped is thrown at as the page throws (sim::aimAt, from 1 m in front of
// a camera DISTANCE m (default 25) from the arena's centre and 30° above the ground, at the
// page's throw speed), aimed at its root body's centre. Each throw prints what the box touched
// first: the target, another character (and how far that one's root is from the target's), or
// nothing within the flight time and 0.3 s; last, the count of each.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <btBulletDynamicsCommon.h>

#include "physics/world.h"
#include "sim/box_hits.h"
#include "sim/simulation.h"

using namespace gaitlab;

namespace {

// The character (index) the box touches now, a contact point within 1 cm, or -1.
int touchedBy(const sim::Simulation& s, const btCollisionObject* box) {
  btDispatcher& d = *const_cast<physics::World&>(s.world(0)).dynamics().getDispatcher();
  for (int m = 0; m < d.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = d.getManifoldByIndexInternal(m);
    const btCollisionObject* other = manifold->getBody0() == box ? manifold->getBody1()
                                     : manifold->getBody1() == box ? manifold->getBody0() : nullptr;
    if (!other || other->isStaticObject()) continue;
    bool near = false;
    for (int p = 0; p < manifold->getNumContacts(); ++p) near = near || manifold->getContactPoint(p).getDistance() < 0.01;
    if (!near) continue;
    for (int i = 0; i < s.characterCount(); ++i)
      for (int k = 0; k < s.character(i).segmentCount(); ++k)
        if (s.character(i).body(k) == other) return i;
  }
  return -1;
}

}  // namespace

int main(int argc, char** argv) {
  const int throws = argc > 1 ? std::atoi(argv[1]) : 100;
  const bool wander = !(argc > 2 && std::string(argv[2]) == "straight");
  const double distance = argc > 3 ? std::atof(argv[3]) : 25;
  int hits = 0, others = 0, none = 0, thrown = 0;
  // A scene per ten throws (as the demo's test throws ten), the camera a little further round
  // the arena each time.
  for (int scene = 0; thrown < throws; ++scene) {
    sim::Simulation s(1, 1 + scene);
    s.addCharacters(sim::Crowd::Mixed, 24);
    if (s.shards() != 1) return std::fprintf(stderr, "expected one physics shard, got %d\n", s.shards()), 1;
    for (int i = 0; i < s.characterCount(); ++i) s.setGoal(i, {sim::Simulation::cruiseSpeed(s.kindOf(i)), 0.0});
    if (wander) s.setWander(-1, 12);
    const double azimuth = 0.7 * scene;
    const Eigen::Vector3d camera(distance * std::cos(M_PI / 6) * std::sin(azimuth), distance * std::sin(M_PI / 6),
                                 distance * std::cos(M_PI / 6) * std::cos(azimuth));
    s.step(240);
    int target = scene % 2;
    for (int k = 0; k < 10 && thrown < throws; ++k) {
      s.step(60);
      // The next biped on foot, in turn.
      int tries = 0;
      do target = (target + 1) % s.characterCount();
      while ((s.kindOf(target) != gait::Character::Biped || s.fallen(target)) && ++tries < s.characterCount());
      if (tries >= s.characterCount()) break;
      const Eigen::Vector3d at = s.character(target).segmentState(0).position;
      const Eigen::Vector3d from = camera + (at - camera).normalized();
      const double speed = sim::pageThrowSpeed((at - from).norm());
      const sim::Intercept aim = s.aimAt(target, 0, Eigen::Vector3d::Zero(), from, speed);
      s.throwBox(from, aim.velocity, 0.12);
      const btCollisionObjectArray& objects = s.world(0).dynamics().getCollisionObjectArray();
      const btCollisionObject* box = objects[objects.size() - 1];
      ++thrown;
      int touched = -1;
      const int steps = static_cast<int>((aim.flightTime + 0.3) * 120);
      for (int step = 0; step < steps && touched < 0; ++step) {
        s.step(1);
        touched = touchedBy(s, box);
      }
      const Eigen::Vector3d now = s.character(target).segmentState(0).position;
      if (touched == target) {
        ++hits;
        std::printf("scene %d throw at %d: target (flight %.2f s)\n", scene, target, aim.flightTime);
      } else if (touched >= 0) {
        ++others;
        const Eigen::Vector3d o = s.character(touched).segmentState(0).position;
        std::printf("scene %d throw at %d: character %d first, %.2f m from the target (flight %.2f s)\n", scene, target,
                    touched, std::hypot(o.x() - now.x(), o.z() - now.z()), aim.flightTime);
      } else {
        ++none;
        std::printf("scene %d throw at %d: nothing (flight %.2f s; the target %.2f m from the aim)\n", scene, target,
                    aim.flightTime, std::hypot(aim.aim.x() - now.x(), aim.aim.z() - now.z()));
      }
    }
  }
  std::printf("%s, camera %.0f m: %d throws, target first %d (%.0f%%), another character %d, nothing %d\n",
              wander ? "wandering" : "straight", distance, thrown, hits, 100.0 * hits / thrown, others, none);
}
