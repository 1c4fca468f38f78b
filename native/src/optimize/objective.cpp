#include "optimize/objective.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "gait/heading.h"
#include "gait/schema.h"
#include "optimize/random.h"
#include "sim/box_hits.h"
#include "sim/walk_trial.h"

namespace gaitlab::optimize {

namespace {
constexpr double kGravity = 9.81;
}

void forEachSetting(ObjectiveSettings& s, const std::function<void(const SettingSpec&, double&)>& visit) {
  visit({"wd", 0, 1000, "1", "w_d: weight of motion deviation f_d (eq. 3.10)"}, s.wd);
  visit({"wv", 0, 1000, "s²/m²", "w_v: weight of velocity deviation f_v (eq. 3.10)"}, s.wv);
  visit({"wa", 0, 1000, "1", "w_h: weight of leg-frame acceleration f_a (eq. 3.10)"}, s.wa);
  visit({"wr", 0, 1000, "1/rad²", "w_r: weight of leg-frame rotation deviation f_r (eq. 3.10)"}, s.wr);
  visit({"wt", 0, 1000, "1", "w_t: weight of footfall timing deviation f_t, duty factors measured against configured (ours)"}, s.wt);
  visit({"wf", 0, 1000, "1", "w_f: weight of flight f_f, the share of time with no foot on the ground: a walk has none (ours)"}, s.wf);
  visit({"wk", 0, 1000, "1", "w_k: weight of speed tracking f_k, the share of a ramp episode's 2 s speed samples off the goal by more than 10 % (the walking benchmark's ramp criterion; ours)"}, s.wk);
  visit({"ws", 0, 1000, "s²/m²", "w_s: weight of speed deviation f_s, the horizontal speed against the goal speed whatever its direction: unlike f_v, not lowered by a slower turn (ours)"}, s.ws);
  visit({"wp", 0, 1000, "1", "w_p: weight of f_p, the share of an episode held at goal 0 not standing on planted feet (the walking benchmark's standing skill; ours)"}, s.wp);
  visit({"wo", 0, 1000, "1/m", "w_o: weight of f_o, how far a scheduled episode that ends at goal 0 goes on after the goal reaches 0 (the walking benchmark's standing drift after its ramp; ours)"}, s.wo);
  visit({"fallPenalty", 0, 1e6, "1", "added for a fall, scaled by 1 + the share of the episode left"},
        s.fallPenalty);
  visit({"seconds", 0.5, 120, "s", "length of one episode (thesis: 800 steps at 120 Hz)"}, s.seconds);
  visit({"warmup", 0, 60, "s", "time before travel and velocity are measured"}, s.warmup);
  double starts = s.starts;
  visit({"starts", 1, 32, "1", "start states per goal speed (the first stands still)", true}, starts);
  s.starts = static_cast<int>(std::lround(starts));
  visit({"startImpulse", 0, 500, "N·s", "horizontal nudge at t = 0 for start states after the first"},
        s.startImpulse);
  visit({"startPhases", 0, 1, "1", "1: start states after the first also begin at their own gait phase, as a crowd starts", true},
        s.startPhases);
  visit({"turnRate", -3, 3, "rad/s", "goal turn rate"}, s.turnRate);
  visit({"turnBothWays", 0, 1, "1", "1: odd start states turn the other way (−turnRate), so a search meets turns to both sides", true},
        s.turnBothWays);
  visit({"turnStraight", 0, 1, "1", "1: start states turn at turnRate, at −turnRate and walk straight in turn, so a search for turning keeps the straight walk", true},
        s.turnStraight);
  visit({"pushImpulse", 0, 1000, "N·s", "pushes at the leg frame during an episode (0: none)"}, s.pushImpulse);
  visit({"pushEvery", 0.5, 60, "s", "time between pushes, phase jittered"}, s.pushEvery);
  visit({"pushDuration", 0, 0.3, "s", "how long each push lasts (0: in one step; Yin et al. 2007 push for 0.2 s)"},
        s.pushDuration);
  visit({"pushAnyWay", 0, 1, "1", "1: each push lateral, forward or backward at random; 0: lateral only", true},
        s.pushAnyWay);
  visit({"ramp", 0, 1, "1", "1: also an episode per ground and start whose goal ramps 0 → the top speed → 0", true}, s.ramp);
  visit({"stopFrom", 0, kMaxGoalSpeed, "m/s", "also an episode per ground and start that walks and stops, unpushed: the goal ramps 0 → stopFrom → 0, then stays 0 for 5 s, whose drift f_o measures (0: none)"},
        s.stopFrom);
  double boxHits = s.boxHits;
  visit({"boxHits", 0, 50, "1", "box-hit episodes per goal speed: a box thrown as the demo throws one, only a fall counts", true},
        boxHits);
  s.boxHits = static_cast<int>(std::lround(boxHits));
  double speedChanges = s.speedChanges;
  visit({"speedChanges", 0, 256, "1", "speed-change episodes per ground: the goal changes between the slowest and the fastest goal speed, each held 1–4 s (the walking benchmark's gait-change trial)", true},
        speedChanges);
  s.speedChanges = static_cast<int>(std::lround(speedChanges));
}

std::string setSetting(ObjectiveSettings& s, const std::string& name, double value) {
  std::string error = "unknown objective setting '" + name + "'";
  forEachSetting(s, [&](const SettingSpec& spec, double& field) {
    if (name != spec.name) return;
    if (!std::isfinite(value) || value < spec.min || value > spec.max) {
      error = name + ": " + nlohmann::json(value).dump() + " is outside [" + nlohmann::json(spec.min).dump() +
              ", " + nlohmann::json(spec.max).dump() + "]";
    } else if (spec.integer && value != std::floor(value)) {
      error = name + ": " + nlohmann::json(value).dump() + " is not a whole number";
    } else {
      field = value;
      error.clear();
    }
  });
  return error;
}

std::string parseGround(const std::string& text, Ground* out) {
  const size_t at = text.find('@');
  const std::string name = text.substr(0, at);
  Ground g;
  if (!physics::parseTerrain(name, &g.terrain))
    return "grounds: '" + name + "' is not flat, slope or bumps";
  if (at != std::string::npos) {
    const std::string number = text.substr(at + 1);
    char* end = nullptr;
    g.heading = std::strtod(number.c_str(), &end);
    if (number.empty() || *end != '\0' || !std::isfinite(g.heading) || std::abs(g.heading) > kMaxGroundHeading)
      return "grounds: '" + text + "': the heading after '@' is not a number in [-7, 7] rad";
  }
  *out = g;
  return "";
}

std::string groundText(const Ground& g) {
  std::string text = physics::terrainName(g.terrain);
  if (g.heading != 0) text += "@" + nlohmann::json(g.heading).dump();
  return text;
}

std::string settingsJson(const ObjectiveSettings& settings) {
  ObjectiveSettings s = settings;
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  forEachSetting(s, [&](const SettingSpec& spec, double& v) { j[spec.name] = v; });
  j["speeds"] = s.speeds;
  nlohmann::ordered_json grounds = nlohmann::ordered_json::array();
  for (const Ground& g : s.grounds) grounds.push_back(groundText(g));
  j["grounds"] = grounds;
  return j.dump();
}

ObjectiveRecorder::ObjectiveRecorder(const ObjectiveSettings& settings, double goalSpeed,
                                     double startHeading, double dt)
    : settings_(settings), goalSpeed_(goalSpeed), startHeading_(startHeading), dt_(dt) {}

void ObjectiveRecorder::setGoalSchedule(std::vector<std::pair<double, double>> schedule) {
  schedule_ = std::move(schedule);
  // Back from the end over the points at goal 0: the earliest of them starts the final hold.
  stoppedFrom_ = std::numeric_limits<double>::infinity();
  for (auto p = schedule_.rbegin(); p != schedule_.rend() && p->second == 0.0; ++p) stoppedFrom_ = p->first;
}

void ObjectiveRecorder::add(double time, const LegFrameSample* frames, int count) {
  const double heading = goalHeading(time);
  const Eigen::Quaterniond goalFrame = gait::headingQuat(heading);
  if (static_cast<int>(lastVelocity_.size()) != count) lastVelocity_.assign(count, Eigen::Vector3d::Zero());
  const bool first = frameSamples_ == 0;
  for (int i = 0; i < count; ++i) {
    const LegFrameSample& f = frames[i];
    const double posture = (f.heightAboveGround - f.standingHeight) / f.standingHeight;
    postureSum_ += posture * posture;
    const double angle = goalFrame.angularDistance(f.orientation);
    rotationSum_ += angle * angle;
    if (!first) {
      const Eigen::Vector3d a = (f.velocity - lastVelocity_[i]) / (time - lastTime_);
      accelSum_ += a.squaredNorm() / (kGravity * kGravity);
      ++accelSamples_;
    }
    lastVelocity_[i] = f.velocity;
  }
  frameSamples_ += count;
  if (time > settings_.warmup + 1e-9) {
    // Root leg frame's horizontal velocity in the goal heading frame (x left, z forward).
    const Eigen::Vector3d v = gait::worldToHeading(heading, frames[0].velocity);
    const double goal = schedule_.empty() ? goalSpeed_ : sim::scheduleAt(schedule_, time);
    const double forwardError = v.z() - goal;
    goalTravel_ += goal * dt_;
    velocitySum_ += forwardError * forwardError + v.x() * v.x();
    const double speedError = std::hypot(v.x(), v.z()) - goal;
    speedSum_ += speedError * speedError;
    ++velocityCount_;
    travel_ += v.z() * dt_;
  }
  if (time >= stoppedFrom_ - 1e-9 && !stopPosition_) stopPosition_ = frames[0].position;
  lastPosition_ = frames[0].position;
  lastTime_ = time;
}

ObjectiveTerms ObjectiveRecorder::finish(bool fell, double fallTime, double ft, double ff, double fk, double standing) const {
  ObjectiveTerms t;
  const double travel = (travel_ - goalTravel_) / std::max(std::abs(goalTravel_), 1.0);
  const double posture = frameSamples_ ? postureSum_ / frameSamples_ : 0.0;
  t.fd = travel * travel + posture;
  t.fv = velocityCount_ ? velocitySum_ / velocityCount_ : 0.0;
  t.fs = velocityCount_ ? speedSum_ / velocityCount_ : 0.0;
  t.fa = accelSamples_ ? accelSum_ / accelSamples_ : 0.0;
  t.fr = frameSamples_ ? rotationSum_ / frameSamples_ : 0.0;
  t.ft = ft;
  t.ff = ff;
  t.fk = fk;
  t.fp = goalSpeed_ == 0.0 && schedule_.empty() ? 1.0 - standing : 0.0;
  if (stopPosition_) {
    const Eigen::Vector3d moved = lastPosition_ - *stopPosition_;
    t.fo = std::hypot(moved.x(), moved.z());
  }
  t.fell = fell;
  t.seconds = fell ? fallTime : lastTime_;
  if (fell) {
    const double left = std::clamp((settings_.seconds - fallTime) / settings_.seconds, 0.0, 1.0);
    t.fall = settings_.fallPenalty * (1.0 + left);
  }
  t.total = settings_.wd * t.fd + settings_.wv * t.fv + settings_.wa * t.fa + settings_.wr * t.fr +
            settings_.wt * t.ft + settings_.wf * t.ff + settings_.wk * t.fk + settings_.ws * t.fs +
            settings_.wp * t.fp + settings_.wo * t.fo + t.fall;
  return t;
}

ObjectiveTerms runEpisode(gait::Character c, const gait::Gait& gait,
                          const ObjectiveSettings& settings, double speed, int start, uint32_t seed,
                          const Ground& ground, const body::Morphology* body,
                          const std::vector<std::pair<double, double>>& schedule) {
  // A scheduled episode lasts as long as its schedule; the fall penalty's "share of the episode
  // left" is of that length.
  ObjectiveSettings episode = settings;
  if (!schedule.empty()) episode.seconds = schedule.back().first;
  episode.turnRate = episodeTurnRate(settings, start);
  sim::WalkOptions w;
  w.body = body;
  w.terrain = ground.terrain;
  w.heading = ground.heading;
  w.character = c;
  w.gait = &gait;
  w.speed = speed;
  w.speedSchedule = schedule;
  w.turnRate = episode.turnRate;
  w.seconds = episode.seconds;
  w.pushImpulse = settings.pushImpulse;
  w.pushEvery = settings.pushEvery;
  w.pushDuration = settings.pushDuration;
  w.pushDirection = settings.pushAnyWay > 0 ? sim::PushDirection::Any : sim::PushDirection::Lateral;
  w.seed = seed + 7919u * static_cast<uint32_t>(start);
  if (start > 0) {
    // A nudge in a direction drawn from the seed: the same start state for every candidate.
    Random r((static_cast<uint64_t>(seed) << 32) ^ static_cast<uint64_t>(start));
    const double angle = r.uniform(0.0, 2.0 * gait::kPi);
    w.startImpulseLeft = settings.startImpulse * std::sin(angle);
    w.startImpulseForward = settings.startImpulse * std::cos(angle);
    if (settings.startPhases > 0) w.startPhase = std::fmod(start * 0.6180339887498949, 1.0);
  }
  ObjectiveRecorder recorder(episode, speed, w.heading, physics::kFixedStep);
  if (!w.speedSchedule.empty()) recorder.setGoalSchedule(w.speedSchedule);
  std::vector<LegFrameSample> frames;
  w.observe = [&](const sim::Simulation& s) {
    const physics::Character& ch = s.character(0);
    const body::Morphology& m = ch.morphology();
    frames.resize(m.legFrames.size());
    for (size_t i = 0; i < m.legFrames.size(); ++i) {
      const int lf = m.legFrames[i];
      const physics::SegmentState st = ch.segmentState(lf);
      frames[i] = {st.position, st.linearVelocity, st.orientation,
                   st.position.y() - s.groundHeight(st.position.x(), st.position.z()),
                   m.segments[lf].center.y()};
    }
    recorder.add(s.time(), frames.data(), static_cast<int>(frames.size()));
  };
  const sim::WalkResult r = sim::runWalk(w);
  return recorder.finish(r.fell, r.fallTime, timingDeviation(r.dutyMeasured, r.dutyConfig), r.flightFraction,
                         trackingMisses(r.trackingSamples, r.trackingWithin), r.standingFraction);
}

double episodeTurnRate(const ObjectiveSettings& settings, int start) {
  if (settings.turnStraight > 0) {
    const int way = start % 3;
    return way == 0 ? settings.turnRate : way == 1 ? -settings.turnRate : 0.0;
  }
  return settings.turnBothWays > 0 && start % 2 == 1 ? -settings.turnRate : settings.turnRate;
}

std::vector<std::string> unmeasuredParameters(gait::Character c, const ObjectiveSettings& settings) {
  std::vector<std::string> names;
  if (settings.turnRate != 0) return names;
  for (const char* name : {"maxTurnSlip", "turnPlacement", "turnRollMoment"})
    if (gait::findParam(c, name)) names.push_back(name);
  return names;
}

std::vector<std::pair<double, double>> speedChangeSchedule(double lo, double hi, int index, uint32_t seed) {
  Random r((static_cast<uint64_t>(seed) << 32) ^ (0x5EEDC4A6ull + static_cast<uint64_t>(index)));
  std::vector<std::pair<double, double>> points;
  double t = 0;
  for (int k = 0; k < kSpeedChangeHolds; ++k) {
    const double goal = k % 2 == 0 ? lo : hi;
    const double hold = r.uniform(1.0, 4.0);
    // Held to just before the next hold starts: the goal steps, the controller's own
    // acceleration limit ramps the desired speed (as the benchmark's schedules do).
    points.push_back({t, goal});
    points.push_back({t + hold - 0.001, goal});
    t += hold;
  }
  return points;
}

uint32_t speedChangeSeed(uint32_t seed, int index) { return seed + 104729u * static_cast<uint32_t>(index); }

std::vector<std::pair<double, double>> rampSchedule(double top, double seconds) {
  return {{0.0, 0.0}, {0.5 * seconds, top}, {seconds, 0.0}};
}

std::vector<std::pair<double, double>> stopSchedule(double top, double seconds) {
  std::vector<std::pair<double, double>> points = rampSchedule(top, seconds);
  points.push_back({seconds + kStopHoldSeconds, 0.0});
  return points;
}

double trackingMisses(int samples, int within) {
  return samples > 0 ? static_cast<double>(samples - within) / samples : 0.0;
}

double timingDeviation(const std::vector<double>& measured, const std::vector<double>& configured) {
  const size_t legs = std::min(measured.size(), configured.size());
  if (legs == 0) return 0.0;
  double sum = 0;
  for (size_t l = 0; l < legs; ++l) sum += (measured[l] - configured[l]) * (measured[l] - configured[l]);
  return sum / static_cast<double>(legs);
}

ObjectiveTerms runBoxHitEpisode(gait::Character c, const gait::Gait& gait,
                                const ObjectiveSettings& settings, double speed, int index, uint32_t seed,
                                const body::Morphology* body) {
  sim::BoxHitOptions o;
  o.walk.body = body;
  o.walk.character = c;
  o.walk.gait = &gait;
  o.walk.speed = speed;
  o.walk.turnRate = settings.turnRate;
  o.walk.seed = seed;
  // Its own draws per throw index and speed, so that adding a speed or a throw leaves the others'.
  sim::TrialDraws draw(seed ^ (0x9E3779B9u * static_cast<uint32_t>(index + 1)) ^
                       static_cast<uint32_t>(std::lround(1000.0 * std::abs(speed))));
  ObjectiveTerms t;
  sim::BoxHit hit;
  for (int attempt = 0; attempt < 3; ++attempt) {
    if (!sim::throwBox(o, draw, &hit)) continue;
    t.seconds = hit.throwTime + (hit.fell ? hit.fallAfter : sim::kBoxJudgeSeconds);
    if (hit.fell) {
      t.fell = true;
      const double left = std::clamp((sim::kBoxJudgeSeconds - hit.fallAfter) / sim::kBoxJudgeSeconds, 0.0, 1.0);
      t.fall = settings.fallPenalty * (1.0 + left);
    }
    break;
  }
  t.total = t.fall;
  return t;
}

ObjectiveTerms evaluate(gait::Character c, const gait::Gait& gait,
                        const ObjectiveSettings& settings, uint32_t seed, const body::Morphology* body) {
  ObjectiveTerms mean;
  int episodes = 0;
  // Every episode, walking or box-hit, counts once in the mean (a box-hit episode's walking
  // terms are 0).
  // The terms and the total are averaged over the episodes (the simulated seconds are summed).
  const auto add = [&](const ObjectiveTerms& t) {
    for (const TermName& term : kTermNames) mean.*term.member += t.*term.member;
    mean.total += t.total;
    mean.seconds += t.seconds;
    mean.fell = mean.fell || t.fell;
    ++episodes;
  };
  // The goal speeds held, then (with `ramp`) the ramp up to the fastest of them, then (with
  // `stopFrom`) the walk and stop, for every start.
  struct Goal {
    double speed;
    std::vector<std::pair<double, double>> schedule;  // empty: held
    bool pushed = true;                               // false: pushImpulse ignored
  };
  std::vector<Goal> goals;
  for (double speed : settings.speeds) goals.push_back({speed, {}});
  if (settings.ramp > 0 && !settings.speeds.empty()) {
    const double top = *std::max_element(settings.speeds.begin(), settings.speeds.end());
    goals.push_back({top, rampSchedule(top, settings.seconds)});
  }
  if (settings.stopFrom > 0) goals.push_back({settings.stopFrom, stopSchedule(settings.stopFrom, settings.seconds), false});
  ObjectiveSettings unpushed = settings;
  unpushed.pushImpulse = 0.0;
  for (const Ground& ground : settings.grounds) {
    for (const Goal& goal : goals) {
      for (int start = 0; start < settings.starts; ++start) {
        add(runEpisode(c, gait, goal.pushed ? settings : unpushed, goal.speed, start, seed, ground, body, goal.schedule));
      }
    }
  }
  if (settings.speedChanges > 0 && !settings.speeds.empty()) {
    const auto [lo, hi] = std::minmax_element(settings.speeds.begin(), settings.speeds.end());
    for (const Ground& ground : settings.grounds)
      for (int k = 0; k < settings.speedChanges; ++k)
        add(runEpisode(c, gait, settings, *lo, 0, speedChangeSeed(seed, k), ground, body,
                       speedChangeSchedule(*lo, *hi, k, seed)));
  }
  for (double speed : settings.speeds)
    for (int k = 0; k < settings.boxHits; ++k) add(runBoxHitEpisode(c, gait, settings, speed, k, seed, body));
  if (episodes) {
    for (const TermName& term : kTermNames) mean.*term.member /= episodes;
    mean.total /= episodes;
  }
  return mean;
}

}  // namespace gaitlab::optimize
