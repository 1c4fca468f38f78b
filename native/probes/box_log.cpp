// Probe, built only on request (`ninja -C build/native gaitlab_box_log`): the walking benchmark's
// box-hit trial (sim/box_hits.h), throw for throw, with what each hit did to the character: how
// fast it moved the whole body, how far the leg frames tilted, and how and when it fell
// (docs/controller-notes.md, "What a thrown box does").
//
//   build/native/gaitlab_box_log GAIT_FILE SPEED HITS [SEED] > log.txt
//
// Per hit: the body part aimed at (render order), the direction the box came from relative to
// the heading (degrees, 0 = from straight ahead, + = from the left), the change of the centre of
// mass's velocity over the first 50 ms after the box first touched (m/s), the largest tilt of
// any leg frame from upright (degrees), and then `stood` or the walking criteria's reason for
// the fall (`tilt`: a leg frame more than 60° from upright, `low`: below half its standing
// height) with the seconds from the touch, and `air`: the seconds of the first 0.4 s after the
// touch in which no foot was within 2 cm of the trial's flat ground (the blow took the character
// off its feet: a foot swept from under it). The throws are the trial's own: the same draws in
// the same order (sim::throwBox), so the falls add up to `gaitlab walk --box-hits HITS --seed
// SEED`. Last, the falls per body part aimed at, and among the hits that took it off its feet
// for kOffItsFeet or more.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gait/heading.h"
#include "gait/params_io.h"
#include "sim/box_hits.h"
#include "sim/simulation.h"
#include "sim/walk_trial.h"

using namespace gaitlab;

namespace {

constexpr double kImpactWindow = 0.05;  // s after the first touch: the box's blow is over
constexpr double kOffItsFeet = 0.1;     // s with no foot down, in the summary

struct Outcome {
  double velocityChange = 0;  // m/s, centre of mass, over kImpactWindow
  double maxTilt = 0;         // degrees, any leg frame
  const char* how = "stood";
  double fellAfter = -1;  // s from the touch
  double airborne = 0;    // s within 0.4 s of the touch with every foot off the ground
};

Eigen::Vector3d comVelocity(const physics::Character& ch) {
  const body::Morphology& m = ch.morphology();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < ch.segmentCount(); ++k) p += m.segments[k].mass * ch.segmentState(k).linearVelocity;
  return p / m.totalMass();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: gaitlab_box_log GAIT_FILE SPEED HITS [SEED]\n");
    return 2;
  }
  gait::GaitFile file;
  if (const auto error = gait::loadGaitFile(argv[1], std::nullopt, &file)) {
    std::fprintf(stderr, "%s: %s\n", argv[1], error->describe().c_str());
    return 2;
  }
  sim::BoxHitOptions o;
  o.walk.character = file.character;
  o.walk.gait = &file.gait;
  o.walk.speed = std::atof(argv[2]);
  o.walk.seed = argc > 4 ? static_cast<uint32_t>(std::atol(argv[4])) : 7;
  const int hits = std::max(1, std::atoi(argv[3]));
  const int judgeSteps = static_cast<int>(std::lround(sim::kBoxJudgeSeconds / physics::kFixedStep));

  // The draws and the throw are sim::throwBox's, step for step; only the watching is added.
  sim::TrialDraws draw(o.walk.seed);
  int hit = 0, falls = 0, offFeet = 0, offFeetFalls = 0;
  std::vector<int> partHits, partFalls;  // per body part aimed at
  std::vector<std::string> partNames;
  for (int throws = 0; hit < hits && throws < 3 * hits; ++throws) {
    sim::Simulation sim(1, o.walk.seed);
    sim::setUpWalk(sim, o.walk);
    const physics::Character& ch = sim.character(0);
    const body::Morphology& m = ch.morphology();
    const double walkFor = 2.0 + 2.0 * draw.unit();
    const int segment = std::min(ch.segmentCount() - 1, static_cast<int>(draw.unit() * ch.segmentCount()));
    const double azimuth = 2 * gait::kPi * draw.unit(), distance = 8 + 10 * draw.unit(), height = 1.5 + 2.5 * draw.unit();
    sim.step(static_cast<int>(std::lround(walkFor / physics::kFixedStep)));
    if (sim::hasFallen(sim, 0)) {
      ++hit, ++falls;
      std::printf("hit %2d part %2d fell before the throw\n", hit, segment);
      continue;
    }
    const Eigen::Vector3d trunk = ch.segmentState(0).position;
    const Eigen::Vector3d from(trunk.x() + distance * std::cos(azimuth), height, trunk.z() + distance * std::sin(azimuth));
    const Eigen::Vector3d target = ch.segmentState(segment).position;
    const double speed = sim::pageThrowSpeed((target - from).norm());
    const sim::Intercept aim = sim.aimAt(0, segment, Eigen::Vector3d::Zero(), from, speed);
    const double yaw = gait::headingOf(ch.segmentState(0).orientation);
    sim.throwBox(from, aim.velocity, o.half);

    const int missSteps = static_cast<int>(std::lround((aim.flightTime + 0.3) / physics::kFixedStep));
    Outcome out;
    double touchedAt = -1;
    Eigen::Vector3d before = Eigen::Vector3d::Zero();
    for (int step = 0; step < judgeSteps; ++step) {
      const Eigen::Vector3d v = comVelocity(ch);
      sim.step(1);
      if (touchedAt < 0 && sim::boxTouches(sim, 0)) touchedAt = sim.time(), before = v;
      if (touchedAt < 0) {
        if (step >= missSteps) break;
        continue;
      }
      const double since = sim.time() - touchedAt;
      if (since <= 0.4) {
        bool down = false;
        for (const body::Leg& leg : m.legs) {
          const physics::SegmentState f = ch.segmentState(leg.foot);
          const Eigen::Vector3d e = m.segments[leg.foot].halfExtents;
          for (int c = 0; c < 8; ++c) {
            const Eigen::Vector3d corner((c & 1 ? 1 : -1) * e.x(), (c & 2 ? 1 : -1) * e.y(), (c & 4 ? 1 : -1) * e.z());
            down = down || (f.position + f.orientation * corner).y() < 0.02;
          }
        }
        if (!down) out.airborne += physics::kFixedStep;
      }
      if (since <= kImpactWindow + 1e-9) out.velocityChange = (comVelocity(ch) - before).norm();
      for (int lf : m.legFrames) {
        const physics::SegmentState s = ch.segmentState(lf);
        const Eigen::Vector3d up = s.orientation * Eigen::Vector3d::UnitY();
        out.maxTilt = std::max(out.maxTilt, std::acos(std::clamp(up.y(), -1.0, 1.0)) * 180 / gait::kPi);
      }
      if (sim::hasFallen(sim, 0)) {  // which of the criterion's two tests fired
        out.how = "low";
        for (int lf : m.legFrames) {
          if ((ch.segmentState(lf).orientation * Eigen::Vector3d::UnitY()).y() < std::cos(gait::kPi / 3)) out.how = "tilt";
        }
        out.fellAfter = since;
        break;
      }
    }
    if (touchedAt < 0) continue;  // a miss: the trial throws again
    ++hit;
    if (out.fellAfter >= 0) ++falls;
    if (partHits.empty()) {
      partHits.assign(m.segments.size(), 0), partFalls.assign(m.segments.size(), 0);
      for (const body::Segment& seg : m.segments) partNames.push_back(seg.name);
    }
    ++partHits[segment];
    if (out.fellAfter >= 0) ++partFalls[segment];
    if (out.airborne >= kOffItsFeet) ++offFeet, offFeetFalls += out.fellAfter >= 0 ? 1 : 0;
    // Where the box came from, relative to the way the character faces (+z turned by yaw).
    const Eigen::Vector3d toThrower = gait::worldToHeading(yaw, from - trunk);
    std::printf("hit %2d part %2d from %4.0f°  dv %.2f m/s  tilt %3.0f°  %s", hit, segment,
                std::atan2(toThrower.x(), toThrower.z()) * 180 / gait::kPi, out.velocityChange, out.maxTilt, out.how);
    if (out.fellAfter >= 0) std::printf(" %.2f s", out.fellAfter);
    std::printf("  air %.2f", out.airborne);
    std::printf("\n");
  }
  std::printf("falls %d of %d\n", falls, hit);
  for (size_t k = 0; k < partHits.size(); ++k)
    if (partHits[k]) std::printf("  part %2zu %-16s falls %2d of %2d\n", k, partNames[k].c_str(), partFalls[k], partHits[k]);
  std::printf("  off its feet for %.1f s or more: %d hits, %d fell\n", kOffItsFeet, offFeet, offFeetFalls);
}
