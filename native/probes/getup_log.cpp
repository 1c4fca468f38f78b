// Probe, built only on request (`ninja -C build/native gaitlab_getup_log`): characters knocked
// over by the box-hit trial's throws (sim/box_hits.h, the same draws), then watched for
// SECONDS: when the controller noticed the fall, when it was back on its feet, and each leg
// frame's roll as it got up (docs/controller-notes.md, "Getting up").
//
// SECONDS count from the throw (the walking benchmark's get-up watch counts from the fall). VERBOSE
// 1 prints each fall every 0.25 s; 2 the landing, every 0.05 s for 3 s after it is up (centre of
// mass, torso, feet); 3 how it lies, every 0.25 s (D down or u up, then the heights of the torso's
// forward and up axes).
//
// With CAPTURE_PREFIX, each fall's first moment lying still on its back, front and side (as the
// get-up judges them, gait/get_up_two_legs.cpp: where its routines start) is appended to
// PREFIX-back.txt, -front.txt or -side.txt, every body's position and orientation, one line a
// body, and the moment it fell to PREFIX-fall.txt, with every body's velocities too: the starts
// the get-up search (getup_search.cpp) can take instead of a body laid down.
//
//   build/native/gaitlab_getup_log GAIT_FILE SPEED THROWS [SEED] [SECONDS] [VERBOSE] [TERRAIN] [CAPTURE_PREFIX] > log.txt
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <btBulletDynamicsCommon.h>
#include <map>
#include <string>

#include "gait/heading.h"
#include "gait/params_io.h"
#include "sim/box_hits.h"
#include "sim/simulation.h"
#include "sim/walk_trial.h"

using namespace gaitlab;

namespace {

double rollOf(const physics::SegmentState& s) {
  const Eigen::Vector3d up = s.orientation * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d left = s.orientation * Eigen::Vector3d::UnitX();
  return std::atan2(-left.y(), up.y()) * 180.0 / gait::kPi;
}

// One start for the get-up search: a "start SEED THROW" line, then per body its position and
// orientation (x y z w), and with `velocities` its linear and angular velocity.
void writeStart(FILE* f, const physics::Character& c, uint32_t seed, int throwIndex, bool velocities) {
  std::fprintf(f, "start %u %d\n", seed, throwIndex);
  for (int k = 0; k < c.segmentCount(); ++k) {
    const physics::SegmentState b = c.segmentState(k);
    std::fprintf(f, "%.6f %.6f %.6f %.6f %.6f %.6f %.6f", b.position.x(), b.position.y(), b.position.z(), b.orientation.x(),
                 b.orientation.y(), b.orientation.z(), b.orientation.w());
    if (velocities)
      std::fprintf(f, " %.6f %.6f %.6f %.6f %.6f %.6f", b.linearVelocity.x(), b.linearVelocity.y(), b.linearVelocity.z(),
                   b.angularVelocity.x(), b.angularVelocity.y(), b.angularVelocity.z());
    std::fprintf(f, "\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: gaitlab_getup_log GAIT_FILE SPEED THROWS [SEED] [SECONDS] [VERBOSE] [TERRAIN]\n");
    return 2;
  }
  gait::GaitFile file;
  if (const auto error = gait::loadGaitFile(argv[1], std::nullopt, &file)) {
    std::fprintf(stderr, "%s: %s\n", argv[1], error->describe().c_str());
    return 2;
  }
  sim::WalkOptions o;
  o.character = file.character;
  o.gait = &file.gait;
  o.speed = std::atof(argv[2]);
  o.seed = argc > 4 ? static_cast<uint32_t>(std::atol(argv[4])) : 7;
  const int throws = std::max(1, std::atoi(argv[3]));
  const double watch = argc > 5 ? std::atof(argv[5]) : 15.0;
  const int verboseLevel = argc > 6 ? std::atoi(argv[6]) : 0;
  const bool verbose = verboseLevel == 1;
  const bool traceUp = verboseLevel == 2;  // the landing: every 0.05 s for 3 s after it is up
  const bool traceLie = verboseLevel == 3;  // how it lies: the torso's forward and up axes' heights every 0.25 s
  if (argc > 7 && !physics::parseTerrain(argv[7], &o.terrain)) {
    std::fprintf(stderr, "%s: not flat, slope or bumps\n", argv[7]);
    return 2;
  }

  FILE* capture[4] = {nullptr, nullptr, nullptr, nullptr};  // back, front, side; the fall
  for (int l = 0; l < 4 && argc > 8; ++l)
    capture[l] = std::fopen((std::string(argv[8]) + "-" + (l == 0 ? "back" : l == 1 ? "front" : l == 2 ? "side" : "fall") + ".txt").c_str(), "a");
  sim::TrialDraws draw(o.seed);
  int fallen = 0, gotUp = 0, standing = 0, upAndStanding = 0;
  double progress = 0;  // over the fallen: 1 − the worse leg frame's |roll| at the end / 180°
  for (int t = 0; t < throws; ++t) {
    sim::Simulation sim(1, o.seed);
    sim::setUpWalk(sim, o);
    const double walkFor = 2.0 + 2.0 * draw.unit();
    const int segment = std::min(sim.character(0).segmentCount() - 1,
                                 static_cast<int>(draw.unit() * sim.character(0).segmentCount()));
    const double azimuth = 2 * gait::kPi * draw.unit(), distance = 8 + 10 * draw.unit(), height = 1.5 + 2.5 * draw.unit();
    sim.step(static_cast<int>(std::lround(walkFor / physics::kFixedStep)));
    const Eigen::Vector3d trunk = sim.character(0).segmentState(0).position;
    const Eigen::Vector3d from(trunk.x() + distance * std::cos(azimuth), height, trunk.z() + distance * std::sin(azimuth));
    const Eigen::Vector3d target = sim.character(0).segmentState(segment).position;
    const double speed = sim::pageThrowSpeed((target - from).norm());
    const sim::Intercept aim = sim.aimAt(0, segment, Eigen::Vector3d::Zero(), from, speed);
    sim.throwBox(from, aim.velocity, 0.12);
    const double thrown = sim.time();
    double fellAt = -1, downAt = -1, upAt = -1;
    const int steps = static_cast<int>(std::lround(watch / physics::kFixedStep));
    const body::Morphology& m = sim.character(0).morphology();
    Eigen::Vector3d lastLeg = Eigen::Vector3d::Zero();  // the root leg frame 3 s before the end
    bool captured[3] = {false, false, false};
    Eigen::Vector3d lastForward = Eigen::Vector3d::Zero(), lastUp = Eigen::Vector3d::Zero();
    for (int k = 0; k < steps; ++k) {
      sim.step(1);
      if (k == steps - static_cast<int>(std::lround(3.0 / physics::kFixedStep))) lastLeg = sim.character(0).segmentState(0).position;
      if (fellAt < 0 && sim::hasFallen(sim, 0)) {
        fellAt = sim.time() - thrown;
        if (capture[3]) writeStart(capture[3], sim.character(0), o.seed, t, true);  // the moment of the fall
      }
      const bool down = sim.controller(0).down();
      if (down && downAt < 0) downAt = sim.time() - thrown;
      if (!down && downAt >= 0 && upAt < 0) upAt = sim.time() - thrown;
      if (capture[0] && down && k % 24 == 0) {
        const physics::SegmentState tr = sim.character(0).segmentState(m.legFrames[0]);
        const Eigen::Vector3d fw = tr.orientation * Eigen::Vector3d::UnitZ(), upAxis = tr.orientation * Eigen::Vector3d::UnitY();
        const int lying = fw.y() > 0.6 ? 0 : fw.y() < -0.6 ? 1 : upAxis.y() < 0.5 ? 2 : -1;  // back, front, side
        if (lying >= 0 && !captured[lying] && (fw - lastForward).norm() < 0.2 && (upAxis - lastUp).norm() < 0.2) {
          captured[lying] = true;
          writeStart(capture[lying], sim.character(0), o.seed, t, false);
        }
        lastForward = fw;
        lastUp = upAxis;
      }
      if (traceLie && fellAt >= 0 && k % 30 == 0) {
        const physics::SegmentState tr = sim.character(0).segmentState(m.legFrames[0]);
        std::printf("%c%+.1f/%+.1f ", down ? 'D' : 'u', (tr.orientation * Eigen::Vector3d::UnitZ()).y(), (tr.orientation * Eigen::Vector3d::UnitY()).y());
      }
      if (traceUp && upAt >= 0 && sim.time() - thrown - upAt < 3.0 && k % 6 == 0) {
        const physics::SegmentState tr = sim.character(0).segmentState(m.legFrames[0]);
        const Eigen::Vector3d fw = tr.orientation * Eigen::Vector3d::UnitZ();
        const Eigen::Vector3d heading = Eigen::Vector3d(fw.x(), 0, fw.z()).normalized();
        Eigen::Vector3d comV = Eigen::Vector3d::Zero(), com = Eigen::Vector3d::Zero();
        double mass = 0;
        for (int q = 0; q < sim.character(0).segmentCount(); ++q) {
          const physics::SegmentState sq = sim.character(0).segmentState(q);
          comV += m.segments[q].mass * sq.linearVelocity;
          com += m.segments[q].mass * sq.position;
          mass += m.segments[q].mass;
        }
        comV /= mass;
        com /= mass;
        std::printf("  com h %.2f v (%5.2f %5.2f) off (%5.2f %5.2f)", com.y(), comV.dot(heading), comV.dot(Eigen::Vector3d::UnitY().cross(heading)),
                    (com - tr.position).dot(heading), (com - tr.position).dot(Eigen::Vector3d::UnitY().cross(heading)));
        std::printf("  t %5.2f stand %d pitch %6.1f roll %6.1f h %.2f v_fwd %5.2f v_side %5.2f", sim.time() - thrown,
                    sim.controller(0).standing() ? 1 : 0, std::asin(std::clamp(fw.y(), -1.0, 1.0)) * 180 / gait::kPi,
                    rollOf(tr), tr.position.y(), tr.linearVelocity.dot(heading),
                    tr.linearVelocity.dot(Eigen::Vector3d::UnitY().cross(heading)));
        for (size_t l = 0; l < m.legs.size(); ++l) {
          const physics::SegmentState fr = sim.character(0).segmentState(m.legs[l].legFrame);
          const physics::SegmentState ft = sim.character(0).segmentState(m.legs[l].foot);
          const Eigen::Vector3d local = fr.orientation.conjugate() * (ft.position - fr.position);
          std::printf(" | foot%zu %5.2f %5.2f %5.2f st %d", l, local.x(), local.y(), local.z(),
                      sim.controller(0).player().leg(static_cast<int>(l)).stance ? 1 : 0);
        }
        std::printf("\n");
      }
      if (verbose && fellAt >= 0 && k % 30 == 0) {
        std::printf("  t %5.2f down %d", sim.time() - thrown, down ? 1 : 0);
        for (int lf : m.legFrames) {
          const physics::SegmentState st = sim.character(0).segmentState(lf);
          std::printf("  roll %6.1f h %.2f", rollOf(st), st.position.y());
        }
        if (k % 120 == 0) {
          for (size_t l = 0; l < m.legs.size(); ++l) {
            const physics::SegmentState fr = sim.character(0).segmentState(m.legs[l].legFrame);
            const physics::SegmentState ft = sim.character(0).segmentState(m.legs[l].foot);
            const Eigen::Vector3d local = fr.orientation.conjugate() * (ft.position - fr.position);
            std::printf("    leg %zu foot in frame (%.2f %.2f %.2f) height %.2f\n", l, local.x(), local.y(), local.z(), ft.position.y());
          }
        }
        std::printf("\n");
      }
    }
    const bool stands = !sim::hasFallen(sim, 0);
    if (verbose) {  // who touches the ground, and where (root leg frame's coordinates)
      const physics::Character& c = sim.character(0);
      std::map<const btCollisionObject*, int> own;
      for (int k = 0; k < c.segmentCount(); ++k) own[c.body(k)] = k;
      btDispatcher& d = *const_cast<physics::World&>(sim.world(0)).dynamics().getDispatcher();
      const physics::SegmentState root = c.segmentState(0);
      for (int mi = 0; mi < d.getNumManifolds(); ++mi) {
        const btPersistentManifold* mf = d.getManifoldByIndexInternal(mi);
        const btCollisionObject* a = mf->getBody0();
        const btCollisionObject* b = mf->getBody1();
        if (!own.count(a)) std::swap(a, b);
        if (!own.count(a) || own.count(b)) continue;
        for (int p = 0; p < mf->getNumContacts(); ++p) {
          const btManifoldPoint& pt = mf->getContactPoint(p);
          if (pt.getDistance() > 0.005) continue;
          const btVector3 w = mf->getBody0() == a ? pt.getPositionWorldOnA() : pt.getPositionWorldOnB();
          const Eigen::Vector3d local = root.orientation.conjugate() * (Eigen::Vector3d(w.x(), w.y(), w.z()) - root.position);
          std::printf("    contact %-22s (%.2f %.2f %.2f) impulse %.1f\n", m.segments[own[a]].name.c_str(), local.x(), local.y(), local.z(), pt.getAppliedImpulse());
        }
      }
    }
    if (fellAt >= 0) {
      ++fallen;
      if (upAt >= 0) ++gotUp;
      if (stands) ++standing;
      if (stands && upAt >= 0) ++upAndStanding;
      double worst = 0;
      for (int lf : m.legFrames) worst = std::max(worst, std::abs(rollOf(sim.character(0).segmentState(lf))));
      progress += 1.0 - worst / 180.0;
    }
    const Eigen::Vector3d moved = sim.character(0).segmentState(0).position - lastLeg;
    std::printf("throw %2d part %2d fell %5.2f down %5.2f up %5.2f end %s", t, segment, fellAt, downAt, upAt,
                stands ? "standing" : "fallen");
    std::printf(" last3s %.2f m", std::hypot(moved.x(), moved.z()));
    for (int lf : m.legFrames) std::printf(" roll %6.1f", rollOf(sim.character(0).segmentState(lf)));
    std::printf("\n");
  }
  for (FILE* f : capture)
    if (f) std::fclose(f);
  std::printf("fell %d, got up %d, standing at the end %d, both %d, progress %.3f\n", fallen, gotUp, standing,
              upAndStanding, fallen ? progress / fallen : 0.0);
  return 0;
}
