#include "gait/schema.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>

#include "body/creature.h"
#include "gait/defaults.h"

namespace gaitlab::gait {

namespace {

// Groups, in the order a parameter panel shows them.
constexpr const char* kTiming = "timing";
constexpr const char* kGaitDiagram = "gait diagram";
constexpr const char* kLegFrame = "leg frame";
constexpr const char* kStance = "stance";
constexpr const char* kSwing = "swing";
constexpr const char* kFootAngles = "foot angles";
constexpr const char* kFootPlacement = "foot placement";
constexpr const char* kJointGains = "joint gains";

struct Bounds {
  double min, max;
};

// A schema entry and where its knots sit inside any GaitParams (byte offset: GaitParams holds
// only doubles, in plain structs and arrays, so an offset taken on one instance is valid on all).
struct Entry {
  ParamSpec spec;
  std::ptrdiff_t offset;
};

struct Table {
  std::vector<Entry> entries;
  std::vector<ParamSpec> specs;
  std::vector<ParamRun> runs;
  int dimension = 0;
};

// The schema itself. Bounds are wide enough for the optimiser to explore (its steps are a tenth
// of the range, thesis §3.3) and physically sensible; gains whose sensible magnitude differs
// between the 70 kg biped and the lighter-legged quadruped get bounds per character so that a
// step stays proportionate.
Table build(Character c) {
  Table t;
  GaitParams proto;
  const bool biped = c == Character::Biped;
  // The leg frame or leg the entries being added belong to (set by the loops below).
  int legFrame = -1, leg = -1;
  std::string owner;  // its name and a dot, "" for controller-wide parameters
  const auto add = [&](std::string name, const char* group, Bounds b, const char* unit,
                       const char* description, double* values, int knots) {
    const auto offset = reinterpret_cast<const char*>(values) - reinterpret_cast<const char*>(&proto);
    std::string field = name.substr(owner.size());
    t.entries.push_back(
        {{std::move(name), group, b.min, b.max, unit, description, knots, std::move(field), legFrame, leg}, offset});
    t.dimension += knots;
  };
  const auto scalar = [&](std::string name, const char* group, Bounds b, const char* unit,
                          const char* description, double& field) {
    add(std::move(name), group, b, unit, description, &field, 1);
  };
  const auto graph = [&](std::string name, const char* group, Bounds b, const char* unit,
                         const char* description, MotionGraph& g) {
    add(std::move(name), group, b, unit, description, g.knots, MotionGraph::kKnots);
  };

  // ---- per controller (§3.3: "the parameter tweaked per controller was the gait period") ----
  scalar("period", kTiming, {0.3, 3.0}, "s", "gait period T: one full cycle of every leg (§3.1.1)",
         proto.period);
  scalar("maxAcceleration", kFootPlacement, {0.1, 5.0}, "m/s²",
         "bound on how fast the desired velocity ramps towards the goal speed (§3.1.6)",
         proto.maxAcceleration);

  scalar("speedIntegralGain", kStance, {0, 2}, "1/s",
         "speed tracking: F_v aims at v_d plus the integral of the speed error (v_d − v, bounded "
         "to 0.15 m/s; started again at each change of gait) at this rate, so the measured speed "
         "settles on the goal; 0: F_v towards v_d only (eq. 3.6)",
         proto.speedIntegralGain);
  scalar("speedProportionalGain", kStance, {0, 20}, "1",
         "speed tracking: F_v also aims this many times the speed error averaged over about a "
         "stride (0.5 s, bounded to 0.1 m/s) above v_d; 0: no such term",
         proto.speedProportionalGain);
  scalar("standSpeed", kStance, {0, 0.5}, "m/s",
         "standing: at goal 0, once the body has moved slower than this for half a second, it "
         "stands on planted feet and steps only to recover; 0: it steps in place",
         proto.standSpeed);
  scalar("maxSpeedTrim", kStance, {0, 2}, "m/s",
         "speed tracking: bound on the integral trim (speedIntegralGain) F_v aims above v_d",
         proto.maxSpeedTrim);
  scalar("speedTrackedFrom", kStance, {0.01, 1}, "m/s",
         "speed tracking: the desired speed from which the trim integrates the speed error; below "
         "it the trim fades and the capture-point placement governs",
         proto.speedTrackedFrom);
  scalar("transitionPhase", kTiming, {0, 1}, "1",
         "gait phase of this key's cycle at which a change to another footfall pattern (a gait "
         "transition) is taken up; 0: where the cycle starts",
         proto.transitionPhase);
  scalar("maxTurnSlip", kLegFrame, {0.1, kNoTurnSlipBound}, "m/s",
         "turning: the goal heading leads the direction the body travels by at most "
         "asin(maxTurnSlip / speed), so the body slides sideways past its heading at most this "
         "fast while it turns; 5: no bound",
         proto.maxTurnSlip);
  scalar("turnPlacement", kLegFrame, {0, 2}, "1",
         "turning: the strike points move outwards from the turn by this many times h·v·ω/g, the "
         "offset at which the ground force that turns the body passes through its centre of mass "
         "(h: its height, v: its speed, ω: the turn rate); 0: placed as if going straight",
         proto.turnPlacement);
  if (biped) {  // a thigh's forward swing; the quadruped's legs fold both ways
    scalar("hipForwardStop", kJointGains, {0.3, kNoHipForwardStop}, "rad",
           "while it walks or stands, the hip joint stops each thigh swinging forwards of the leg "
           "frame's down axis beyond this, as an end stop would (every biped gait was searched on "
           "one at 0.7); beyond the hip's range (π): no stop",
           proto.hipForwardStop);
  } else {  // the whole-body stance it acts in is that of bodies of several leg frames
    scalar("turnRollMoment", kLegFrame, {0, 4}, "1",
           "turning: the whole-body stance is asked for this many times the roll moment m·v·ω·h "
           "that the turn's sideways ground force exerts about the centre of mass from the ground, "
           "instead of cancelling it with its feet (h: the centre of mass's height); 0: cancelled",
           proto.turnRollMoment);
  }

  // ---- joint gains (§3.1.7), shared by all legs ----
  JointGains& g = proto.gains;
  scalar("gains.hipKp", kJointGains, biped ? Bounds{0, 1500} : Bounds{0, 400}, "N·m/rad",
         "hip PD proportional gain", g.hipKp);
  // Explicit PD at 120 Hz is stable while k_d·dt/I_eff < ~1. The quadruped's limbs carry
  // 0.05 kg·m² of armature and little more (I_eff ≈ 0.05): hip, knee and stance ankle damping
  // above ~6 N·m·s/rad is unstable by construction (controller-notes §8).
  scalar("gains.hipKd", kJointGains, biped ? Bounds{0, 60} : Bounds{0, 5}, "N·m·s/rad",
         "hip PD derivative gain", g.hipKd);
  scalar("gains.kneeKp", kJointGains, biped ? Bounds{0, 1500} : Bounds{0, 400}, "N·m/rad",
         "knee PD proportional gain (target from two-link IK, §3.1.5)", g.kneeKp);
  scalar("gains.kneeKd", kJointGains, biped ? Bounds{0, 60} : Bounds{0, 5}, "N·m·s/rad",
         "knee PD derivative gain", g.kneeKd);
  scalar("gains.ankleKp", kJointGains, biped ? Bounds{0, 40} : Bounds{0, 20}, "N·m/rad",
         "ankle PD proportional gain (foot take-off and strike angles)", g.ankleKp);
  // A foot's roll inertia is ~0.003 kg·m²: an explicit PD at 120 Hz needs k_d·dt/I < ~1.
  scalar("gains.ankleKd", kJointGains, {0, 0.3}, "N·m·s/rad", "ankle PD derivative gain",
         g.ankleKd);
  scalar("gains.stanceAnkleKp", kJointGains, biped ? Bounds{0, 3000} : Bounds{0, 800}, "N·m/rad",
         "stance ankle PD proportional gain, foot relative to its shin (§3.1.7)", g.stanceAnkleKp);
  scalar("gains.stanceAnkleKd", kJointGains, biped ? Bounds{0, 40} : Bounds{0, 5}, "N·m·s/rad",
         "stance ankle PD derivative gain", g.stanceAnkleKd);
  if (!biped) {  // the biped has no spine
    scalar("gains.spineKp", kJointGains, {0, 800}, "N·m/rad",
           "spine PD proportional gain (each of the spine links)", g.spineKp);
    // Spine joints join two 2 kg links (I ≈ 0.05 kg·m² each, relative ≈ 0.025, and the chain's
    // fastest mode less): k_d = 5 alternated ±45 N·m every step, k_d ≤ 1 is smooth (§8).
    scalar("gains.spineKd", kJointGains, {0, 1.5}, "N·m·s/rad", "spine PD derivative gain",
           g.spineKd);
  }
  scalar("gains.stanceKneeFlexion", kStance, {0, 1.0}, "rad", "knee bend the stance knee's PD holds",
         g.stanceKneeFlexion);
  scalar("gains.hipTwistScale", kJointGains, {0, 1}, "1",
         "share of hip torque kept about the thigh's own axis (its small inertia needs less)",
         g.hipTwistScale);
  scalar("gains.swingTargetRate", kJointGains, {0, 1}, "1",
         "share of the swing targets' velocity the swing hip and knee PDs follow (0: position only)",
         g.swingTargetRate);
  scalar("gains.maxTorque", kJointGains, biped ? Bounds{20, 1000} : Bounds{10, 400}, "N·m",
         "clamp on the magnitude of every joint torque", g.maxTorque);

  // ---- per leg frame (§3.3: orientation, height, foot-tracking gain, h_sw, t_sw, F_h gains,
  //      K_v, F_D's c0..c3, take-off and strike angles, s, step lengths) ----
  for (size_t i = 0; i < legFrameNames(c).size(); ++i) {
    LegFrameParams& f = proto.legFrames[i];
    const std::string n = legFrameNames(c)[i] + ".";
    legFrame = static_cast<int>(i);
    owner = n;
    graph(n + "pitch", kLegFrame, {-0.5, 0.5}, "rad",
          "desired leg-frame pitch over the gait phase, heading frame (+ = nose down) (§3.1.3)", f.pitch);
    graph(n + "roll", kLegFrame, {-0.3, 0.3}, "rad", "desired leg-frame roll over the gait phase (§3.1.3)",
          f.roll);
    graph(n + "yaw", kLegFrame, {-0.3, 0.3}, "rad",
          "desired leg-frame yaw relative to the heading, over the gait phase (§3.1.3)", f.yaw);
    graph(n + "heightOffset", kLegFrame, {-0.25, 0.1}, "m",
          "desired leg-frame height relative to standing height, over the gait phase (§3.1.4)",
          f.heightOffset);
    scalar(n + "orientationKp", kLegFrame, biped ? Bounds{0, 3000} : Bounds{0, 800}, "N·m/rad",
           "leg-frame orientation PD gain, torque delivered through the stance legs (eq. 3.4–3.5)",
           f.orientationKp);
    scalar(n + "orientationKd", kLegFrame, biped ? Bounds{0, 200} : Bounds{0, 50}, "N·m·s/rad",
           "leg-frame orientation PD derivative gain", f.orientationKd);
    scalar(n + "heightKp", kStance, biped ? Bounds{0, 6000} : Bounds{0, 2000}, "N/m",
           "F_h proportional gain: stance force towards the height graph (§3.1.4)", f.heightKp);
    scalar(n + "heightKd", kStance, biped ? Bounds{0, 600} : Bounds{0, 200}, "N·s/m",
           "F_h derivative gain", f.heightKd);
    scalar(n + "velocityGain", kStance, {0, 400}, "N·s/m",
           "K_v of the stance velocity force F_v = K_v (v_d − v) (eq. 3.6)", f.velocityGain);
    scalar(n + "fdC0", kStance, {-200, 200}, "N", "c0 of F_D(D): vertical force at D = 0 (eq. 3.8)",
           f.fd[0]);
    scalar(n + "fdC1", kStance, {-1000, 1000}, "N/m", "c1 of F_D(D): vertical force per metre of D (eq. 3.8)",
           f.fd[1]);
    scalar(n + "fdC2", kStance, {-200, 200}, "N", "c2 of F_D(D): forward force at D = 0 (eq. 3.8)",
           f.fd[2]);
    scalar(n + "fdC3", kStance, {-1000, 1000}, "N/m", "c3 of F_D(D): forward force per metre of D (eq. 3.8)",
           f.fd[3]);
    graph(n + "footTrackingGain", kSwing, {0, 400}, "N/m",
          "k_ft: swing-foot virtual force gain over swing progress; K_d = 0.1 k_ft (§3.1.4)",
          f.footTrackingGain);
    graph(n + "stepHeight", kSwing, {0, 0.25}, "m", "h_sw: swing foot height over swing progress (§3.1.6)",
          f.stepHeight);
    graph(n + "swingEase", kSwing, {0, 1}, "1",
          "t_sw: share of the way from lift-off to strike point over swing progress (§3.1.6)",
          f.swingEase);
    scalar(n + "toeOffAngle", kFootAngles, {-0.8, 0.8}, "rad",
           "foot pitch targeted at lift-off (+ = toes down) (§3.1.6)", f.toeOffAngle);
    scalar(n + "strikeAngle", kFootAngles, {-0.8, 0.8}, "rad",
           "foot pitch targeted at strike (− = toes up) (§3.1.6)", f.strikeAngle);
    scalar(n + "footPlacementScale", kFootPlacement, {0, 1}, "s",
           "s of P1 = P_lf + (v − v_d)·s: velocity feedback on the strike point (§3.1.6)",
           f.footPlacementScale);
    scalar(n + "footPlacementLead", kFootPlacement, {0, 1}, "s",
           "the nominal strike point moves ahead by v_d × this: at the goal speed the foot lands "
           "where the step carries the body over it, not under the leg frame",
           f.footPlacementLead);
    scalar(n + "stepSideways", kFootPlacement, {0, 0.3}, "m",
           "nominal strike point's sideways offset from the leg frame's centre", f.stepSideways);
    scalar(n + "stepForward", kFootPlacement, {-0.3, 0.3}, "m",
           "nominal strike point's forward offset from the hip", f.stepForward);
    scalar(n + "capturePlacement", kFootPlacement, {0, 1}, "1",
           "at low speed the strike point moves this far (at v_d = 0) towards the centre of mass's "
           "capture point x + v·√(h/g): the inverted-pendulum placement that stops the body over it "
           "(Coros et al. 2010); 0: the thesis's placement only",
           f.capturePlacement);
    scalar(n + "captureBlendSpeed", kFootPlacement, {0.05, 3}, "m/s",
           "desired speed at which the capture-point placement has faded out (linearly from v_d = 0)",
           f.captureBlendSpeed);
    scalar(n + "captureSideways", kFootPlacement, {0, 0.3}, "m",
           "capture-point placement: the strike point's offset to the leg's side", f.captureSideways);
  }

  // ---- per leg (§3.3: step trigger, duty factor, foot take-off time, foot strike time) ----
  for (size_t i = 0; i < legNames(c).size(); ++i) {
    LegParams& l = proto.legs[i];
    const std::string n = legNames(c)[i] + ".";
    legFrame = -1;
    leg = static_cast<int>(i);
    owner = n;
    scalar(n + "stepTrigger", kGaitDiagram, {0, 1}, "1",
           "gait phase at which the leg lifts off (§3.1.1)", l.stepTrigger);
    scalar(n + "dutyFactor", kGaitDiagram, {0.2, 0.9}, "1", "share of the gait cycle spent in stance (§3.1.1)",
           l.dutyFactor);
    scalar(n + "toeOffTime", kFootAngles, {0, 1}, "1",
           "stance progress after which the foot pitches to the take-off angle", l.toeOffTime);
    scalar(n + "strikeTime", kFootAngles, {0, 1}, "1",
           "swing progress after which the foot pitches to the strike angle", l.strikeTime);
  }

  for (const Entry& e : t.entries) t.specs.push_back(e.spec);
  // The entries' doubles as runs, in the order they lie in GaitParams, adjacent ones merged
  // (paramRuns).
  std::vector<ParamRun> fields;
  for (const Entry& e : t.entries)
    fields.push_back({static_cast<int>(e.offset / static_cast<std::ptrdiff_t>(sizeof(double))), e.spec.knots});
  std::sort(fields.begin(), fields.end(), [](const ParamRun& a, const ParamRun& b) { return a.first < b.first; });
  for (const ParamRun& r : fields) {
    if (!t.runs.empty() && t.runs.back().first + t.runs.back().count == r.first)
      t.runs.back().count += r.count;
    else
      t.runs.push_back(r);
  }
  return t;
}

const Table& table(Character c) {
  static const Table tables[kCharacterCount] = {build(Character::Biped), build(Character::Quadruped),
                                                build(Character::Hexapod), build(Character::Octopod)};
  return tables[static_cast<int>(c)];
}

double* at(GaitParams& p, std::ptrdiff_t offset) {
  return reinterpret_cast<double*>(reinterpret_cast<char*>(&p) + offset);
}

// The shipped creature file each kind stands for (public/creatures/).
const char* shippedBodyName(Character c) {
  static const char* const names[kCharacterCount] = {"biped", "quadruped", "insect", "spider"};
  return names[static_cast<int>(c)];
}

}  // namespace

const body::Morphology& shippedBody(Character c) {
  static const body::Morphology bodies[kCharacterCount] = {
      body::shippedCreature(shippedBodyName(Character::Biped)),
      body::shippedCreature(shippedBodyName(Character::Quadruped)),
      body::shippedCreature(shippedBodyName(Character::Hexapod)),
      body::shippedCreature(shippedBodyName(Character::Octopod))};
  return bodies[static_cast<int>(c)];
}

bool derivesGait(Character c) { return legFrameNames(c).size() > 2; }

const std::vector<std::string>& legFrameNames(Character c) {
  static const std::vector<std::string> names[kCharacterCount] = {
      {"legFrame"}, {"front", "back"}, {"front", "middle", "back"}, {"front", "frontMiddle", "backMiddle", "back"}};
  return names[static_cast<int>(c)];
}

const std::vector<std::string>& legNames(Character c) {
  // Each leg frame's left leg, then its right (body/creature.h numbers them so).
  static const std::array<std::vector<std::string>, kCharacterCount> names = [] {
    std::array<std::vector<std::string>, kCharacterCount> out{{{"left", "right"}}};
    for (int k = 1; k < kCharacterCount; ++k) {
      for (const std::string& frame : legFrameNames(kCharacters[k])) {
        out[k].push_back(frame + "Left");
        out[k].push_back(frame + "Right");
      }
    }
    return out;
  }();
  return names[static_cast<int>(c)];
}

const char* characterName(Character c) {
  static const char* const names[kCharacterCount] = {"biped", "quadruped", "hexapod", "octopod"};
  return names[static_cast<int>(c)];
}

std::optional<Character> characterFromName(const std::string& name) {
  for (Character c : kCharacters) {
    if (name == characterName(c)) return c;
  }
  return std::nullopt;
}

std::optional<Character> characterFromKind(int kind) {
  for (Character c : kCharacters) {
    if (kind == kindNumber(c)) return c;
  }
  return std::nullopt;
}

const ParamSpec* findParam(Character c, const std::string& name) {
  for (const ParamSpec& s : paramSpecs(c)) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

Character characterOf(const body::Morphology& m) {
  // body/creature.h refuses a body of no leg frame or more than kCharacterCount.
  return kCharacters[std::clamp<size_t>(m.legFrames.size(), 1, kCharacterCount) - 1];
}

void forEachParam(Character c, GaitParams& params, const std::function<void(const ParamField&)>& visit) {
  for (const Entry& e : table(c).entries) visit(ParamField{e.spec, at(params, e.offset)});
}

const std::vector<ParamSpec>& paramSpecs(Character c) { return table(c).specs; }

const std::vector<ParamRun>& paramRuns(Character c) { return table(c).runs; }

int paramDimension(Character c) { return table(c).dimension; }

std::vector<double> toVector(Character c, const GaitParams& params) {
  std::vector<double> v;
  v.reserve(paramDimension(c));
  GaitParams copy = params;
  forEachParam(c, copy, [&](const ParamField& f) { v.insert(v.end(), f.values, f.values + f.spec.knots); });
  return v;
}

void fromVector(Character c, const std::vector<double>& values, GaitParams* params) {
  size_t i = 0;
  forEachParam(c, *params, [&](const ParamField& f) {
    for (int k = 0; k < f.spec.knots; ++k) f.values[k] = values.at(i++);
  });
}

void bounds(Character c, std::vector<double>* lo, std::vector<double>* hi) {
  lo->clear();
  hi->clear();
  for (const ParamSpec& s : paramSpecs(c)) {
    lo->insert(lo->end(), s.knots, s.min);
    hi->insert(hi->end(), s.knots, s.max);
  }
}

void clampToBounds(Character c, std::vector<double>* values) {
  std::vector<double> lo, hi;
  bounds(c, &lo, &hi);
  for (size_t i = 0; i < values->size() && i < lo.size(); ++i) (*values)[i] = std::clamp((*values)[i], lo[i], hi[i]);
}

std::string schemaJson(std::optional<Character> only) {
  using ordered = nlohmann::ordered_json;
  ordered characters = ordered::object(), morphologies = ordered::object();
  for (Character c : kCharacters) {
    if (only && *only != c) continue;
    GaitParams defaults = defaultParams(c);
    ordered entries = ordered::array();
    forEachParam(c, defaults, [&](const ParamField& f) {
      const ParamSpec& s = f.spec;
      ordered d = s.knots == 1 ? ordered(f.values[0])
                               : ordered(std::vector<double>(f.values, f.values + s.knots));
      ordered e = {{"name", s.name}, {"group", s.group}, {"min", s.min}, {"max", s.max},
                   {"default", d}, {"unit", s.unit}, {"description", s.description},
                   {"knots", s.knots}, {"field", s.field}};
      if (s.legFrame >= 0) e["legFrame"] = {{"index", s.legFrame}, {"name", legFrameNames(c)[s.legFrame]}};
      if (s.leg >= 0) e["leg"] = {{"index", s.leg}, {"name", legNames(c)[s.leg]}};
      entries.push_back(std::move(e));
    });
    characters[characterName(c)] = entries;

    // The body the parameters belong to: which leg frame each leg hangs from, and its side (the
    // sign of its hip's x in the rest pose: the character faces +z, so +x is its left).
    const body::Morphology& m = shippedBody(c);
    ordered frames = ordered::array(), legs = ordered::array();
    for (size_t i = 0; i < legFrameNames(c).size(); ++i)
      frames.push_back({{"index", i}, {"name", legFrameNames(c)[i]}});
    for (size_t i = 0; i < legNames(c).size(); ++i) {
      const body::Leg& leg = m.legs[i];
      int frame = 0;
      for (size_t k = 0; k < m.legFrames.size(); ++k) {
        if (m.legFrames[k] == leg.legFrame) frame = static_cast<int>(k);
      }
      const bool left = m.segments[leg.upper].center.x() > 0;
      legs.push_back({{"index", i}, {"name", legNames(c)[i]}, {"legFrame", frame},
                      {"side", left ? "left" : "right"}});
    }
    morphologies[characterName(c)] = {{"kind", kindNumber(c)}, {"legFrames", frames}, {"legs", legs}};
  }
  return ordered{{"version", kSchemaVersion}, {"characters", characters}, {"morphologies", morphologies}}.dump();
}

}  // namespace gaitlab::gait
