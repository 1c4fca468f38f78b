#include "body/creature.h"

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <sstream>
#include <vector>

#include "api/limits.h"
#include "gait/params_io.h"

namespace gaitlab::body {

namespace {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string at(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }

// Reads one document field by field, keeping the first problem: each read returns false once
// anything is wrong, so a caller stops at the first `false` and reports `error`.
struct Reader {
  std::optional<CreatureError> error;

  bool fail(const std::string& field, std::string message) {
    if (!error) error = CreatureError{field, std::move(message)};
    return false;
  }
  // `v` is an object with every field of `names` and none but those and the `optional` ones.
  bool fields(const json& v, const std::string& path, std::initializer_list<const char*> names,
              std::initializer_list<const char*> optional = {}) {
    if (!v.is_object()) return fail(path, "expected an object, got " + gait::jsonTypeName(v));
    for (const auto& item : v.items()) {
      bool known = false;
      for (const char* n : names) known = known || item.key() == n;
      for (const char* n : optional) known = known || item.key() == n;
      if (!known) return fail(join(path, item.key()), "unknown field");
    }
    for (const char* n : names)
      if (!v.contains(n)) return fail(join(path, n), "missing");
    return true;
  }
  bool number(const json& v, const std::string& path, double lo, double hi, double* out) {
    if (!v.is_number()) return fail(path, "expected a number, got " + gait::jsonTypeName(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) return fail(path, "not finite");
    if (x < lo || x > hi)
      return fail(path, json(x).dump() + " is outside [" + json(lo).dump() + ", " + json(hi).dump() + "]");
    *out = x;
    return true;
  }
  bool triple(const json& v, const std::string& path, double lo, double hi, std::array<double, 3>* out) {
    if (!v.is_array() || v.size() != 3) return fail(path, "expected an array of 3 numbers, got " + gait::jsonTypeName(v));
    for (size_t i = 0; i < 3; ++i)
      if (!number(v[i], at(path, i), lo, hi, &(*out)[i])) return false;
    return true;
  }
  bool vector(const json& v, const std::string& path, double lo, double hi, Vector3d* out) {
    std::array<double, 3> a{};
    if (!triple(v, path, lo, hi, &a)) return false;
    *out = Vector3d(a[0], a[1], a[2]);
    return true;
  }
  bool integer(const json& v, const std::string& path, int lo, int hi, int* out) {
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
      return fail(path, "expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                            ", got " + gait::jsonShown(v));
    *out = static_cast<int>(v.get<long long>());
    return true;
  }
  bool text(const json& v, const std::string& path, size_t minLength, std::string* out) {
    constexpr size_t kMaxName = 64;
    if (!v.is_string()) return fail(path, "expected a string, got " + gait::jsonTypeName(v));
    const std::string s = v.get<std::string>();
    if (s.size() < minLength || s.size() > kMaxName)
      return fail(path, "expected " + std::to_string(minLength) + " to " + std::to_string(kMaxName) +
                            " characters, got " + std::to_string(s.size()));
    *out = s;
    return true;
  }
  // "#rrggbb" as 0xrrggbbff (the renderer's RGBA).
  bool colour(const json& v, const std::string& path, unsigned* out) {
    const std::string s = v.is_string() ? v.get<std::string>() : std::string();
    bool ok = s.size() == 7 && s[0] == '#';
    for (size_t i = 1; ok && i < s.size(); ++i) ok = std::isxdigit(static_cast<unsigned char>(s[i])) != 0;
    if (!ok) return fail(path, "expected a colour \"#rrggbb\", got " + gait::jsonShown(v));
    *out = (static_cast<unsigned>(std::stoul(s.substr(1), nullptr, 16)) << 8) | 0xffu;
    return true;
  }
};

// Ranges every file is held to: a body a browser can simulate at 120 Hz, not a physical law.
constexpr double kMinSize = 0.002, kMaxSize = 2.0;   // m, half extents and lengths
constexpr double kMinMass = 0.01, kMaxMass = 500.0;  // kg, per segment

struct LimbSpec {
  double length = 0, halfThickness = 0, mass = 0;
};
struct LegsSpec {
  std::string name;
  double hipSpacing = 0;
  std::array<double, 3> hipLower{}, hipUpper{};
  bool kneeForward = true;
  double flexion = 0, hyperextension = 0, anklePitch = 0, ankleRoll = 0;
  LimbSpec upper, lower;
  // A third segment (file version 2): length 0 for legs of two segments.
  LimbSpec tarsus;
  double hockFlexion = 0, hockHyperextension = 0;
  Vector3d footHalf = Vector3d::Zero();
  double footForward = 0, footMass = 0, ankleAboveFoot = 0;
  unsigned left = 0, right = 0, foot = 0;
};
struct FrameSpec {
  std::string name;
  double z = 0, mass = 0, aboveHips = 0;
  Vector3d half = Vector3d::Zero();
  unsigned colour = 0;
  LegsSpec legs;
};
struct SpineSpec {
  double from = 0, to = 0, halfWidth = 0, halfHeight = 0, mass = 0, limit = 0;
  int links = 0;
  unsigned colour = 0;
};

bool readLimb(Reader& r, const json& v, const std::string& path, LimbSpec* out) {
  return r.fields(v, path, {"length", "halfThickness", "mass"}) &&
         r.number(v["length"], join(path, "length"), 0.01, kMaxSize, &out->length) &&
         r.number(v["halfThickness"], join(path, "halfThickness"), kMinSize, 0.5, &out->halfThickness) &&
         r.number(v["mass"], join(path, "mass"), kMinMass, kMaxMass, &out->mass);
}

// The third segment, "tarsus" (version 2, optional): a limb and its hock's range, which bends the
// other way to the knee.
bool readTarsus(Reader& r, const json& v, const std::string& path, LegsSpec* out) {
  const std::string hock = join(path, "hock");
  return r.fields(v, path, {"length", "halfThickness", "mass", "hock"}) &&
         r.number(v["length"], join(path, "length"), 0.01, kMaxSize, &out->tarsus.length) &&
         r.number(v["halfThickness"], join(path, "halfThickness"), kMinSize, 0.5, &out->tarsus.halfThickness) &&
         r.number(v["mass"], join(path, "mass"), kMinMass, kMaxMass, &out->tarsus.mass) &&
         r.fields(v["hock"], hock, {"flexion", "hyperextension"}) &&
         r.number(v["hock"]["flexion"], join(hock, "flexion"), 0, kPi, &out->hockFlexion) &&
         r.number(v["hock"]["hyperextension"], join(hock, "hyperextension"), 0, kPi / 2, &out->hockHyperextension);
}

bool readLegs(Reader& r, const json& v, const std::string& path, int version, LegsSpec* out) {
  const bool three = v.is_object() && v.contains("tarsus");
  if (three && version < 2) return r.fail(join(path, "tarsus"), "a third leg segment needs version 2 of the format");
  if (three && !readTarsus(r, v["tarsus"], join(path, "tarsus"), out)) return false;
  if (!r.fields(v, path, {"name", "hipSpacing", "hip", "knee", "ankle", "upper", "lower", "foot", "colours"}, {"tarsus"}) ||
      !r.text(v["name"], join(path, "name"), 0, &out->name) ||
      !r.number(v["hipSpacing"], join(path, "hipSpacing"), 0, 1, &out->hipSpacing))
    return false;
  const std::string hip = join(path, "hip");
  if (!r.fields(v["hip"], hip, {"lower", "upper"}) ||
      !r.triple(v["hip"]["lower"], join(hip, "lower"), -kPi, kPi, &out->hipLower) ||
      !r.triple(v["hip"]["upper"], join(hip, "upper"), -kPi, kPi, &out->hipUpper))
    return false;
  for (size_t i = 0; i < 3; ++i)
    if (out->hipLower[i] > out->hipUpper[i]) return r.fail(at(join(hip, "lower"), i), "above hip.upper[" + std::to_string(i) + "]");
  // Before version 3 the physics mirrored the hip's range (creature.h): read so, a file walks as
  // it did when it was written. A symmetric range is the same either way.
  if (version < 3)
    for (size_t i = 0; i < 3; ++i) {
      const double lower = out->hipLower[i];
      out->hipLower[i] = -out->hipUpper[i];
      out->hipUpper[i] = -lower;
    }
  const std::string knee = join(path, "knee");
  if (!r.fields(v["knee"], knee, {"points", "flexion", "hyperextension"})) return false;
  const json& points = v["knee"]["points"];
  if (points != "forward" && points != "backward")
    return r.fail(join(knee, "points"), "expected \"forward\" or \"backward\", got " + gait::jsonShown(points));
  out->kneeForward = points == "forward";
  const std::string ankle = join(path, "ankle");
  const std::string foot = join(path, "foot"), colours = join(path, "colours");
  return r.number(v["knee"]["flexion"], join(knee, "flexion"), 0, kPi, &out->flexion) &&
         r.number(v["knee"]["hyperextension"], join(knee, "hyperextension"), 0, kPi / 2, &out->hyperextension) &&
         r.fields(v["ankle"], ankle, {"pitch", "roll"}) &&
         r.number(v["ankle"]["pitch"], join(ankle, "pitch"), 0, kPi / 2, &out->anklePitch) &&
         r.number(v["ankle"]["roll"], join(ankle, "roll"), 0, kPi / 2, &out->ankleRoll) &&
         readLimb(r, v["upper"], join(path, "upper"), &out->upper) &&
         readLimb(r, v["lower"], join(path, "lower"), &out->lower) &&
         r.fields(v["foot"], foot, {"halfExtents", "forward", "mass", "ankleAboveFoot"}) &&
         r.vector(v["foot"]["halfExtents"], join(foot, "halfExtents"), kMinSize, 0.5, &out->footHalf) &&
         r.number(v["foot"]["forward"], join(foot, "forward"), -0.5, 0.5, &out->footForward) &&
         r.number(v["foot"]["mass"], join(foot, "mass"), kMinMass, kMaxMass, &out->footMass) &&
         r.number(v["foot"]["ankleAboveFoot"], join(foot, "ankleAboveFoot"), 0, 0.2, &out->ankleAboveFoot) &&
         r.fields(v["colours"], colours, {"left", "right", "foot"}) &&
         r.colour(v["colours"]["left"], join(colours, "left"), &out->left) &&
         r.colour(v["colours"]["right"], join(colours, "right"), &out->right) &&
         r.colour(v["colours"]["foot"], join(colours, "foot"), &out->foot);
}

bool readFrame(Reader& r, const json& v, const std::string& path, int version, FrameSpec* out) {
  return r.fields(v, path, {"name", "z", "halfExtents", "mass", "aboveHips", "colour", "legs"}) &&
         r.text(v["name"], join(path, "name"), 1, &out->name) &&
         r.number(v["z"], join(path, "z"), -5, 5, &out->z) &&
         r.vector(v["halfExtents"], join(path, "halfExtents"), kMinSize, 1, &out->half) &&
         r.number(v["mass"], join(path, "mass"), kMinMass, kMaxMass, &out->mass) &&
         r.number(v["aboveHips"], join(path, "aboveHips"), -1, 1, &out->aboveHips) &&
         r.colour(v["colour"], join(path, "colour"), &out->colour) &&
         readLegs(r, v["legs"], join(path, "legs"), version, &out->legs);
}

bool readSpine(Reader& r, const json& v, const std::string& path, SpineSpec* out) {
  return r.fields(v, path, {"from", "to", "links", "halfWidth", "halfHeight", "mass", "limit", "colour"}) &&
         r.number(v["from"], join(path, "from"), -5, 5, &out->from) &&
         r.number(v["to"], join(path, "to"), -5, 5, &out->to) &&
         r.integer(v["links"], join(path, "links"), 1, kMaxSpineLinks, &out->links) &&
         r.number(v["halfWidth"], join(path, "halfWidth"), kMinSize, 1, &out->halfWidth) &&
         r.number(v["halfHeight"], join(path, "halfHeight"), kMinSize, 1, &out->halfHeight) &&
         r.number(v["mass"], join(path, "mass"), kMinMass, kMaxMass, &out->mass) &&
         r.number(v["limit"], join(path, "limit"), 0, kPi / 2, &out->limit) &&
         r.colour(v["colour"], join(path, "colour"), &out->colour);
}

Joint hinge(const Vector3d& pivot, double lo, double hi) {
  Joint j;
  j.type = JointType::Hinge;
  j.pivot = pivot;
  j.axes = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  j.lower = {lo, 0, 0};
  j.upper = {hi, 0, 0};
  return j;
}

// Sagittal pitch (about x) then roll (about z).
Joint universal(const Vector3d& pivot, double pitch, double roll) {
  Joint j;
  j.type = JointType::Universal;
  j.pivot = pivot;
  j.axes = {Vector3d::UnitX(), Vector3d::UnitZ(), Vector3d::UnitY()};
  j.lower = {-pitch, -roll, 0};
  j.upper = {pitch, roll, 0};
  return j;
}

Joint ball(const Vector3d& pivot, const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  Joint j;
  j.type = JointType::Ball;
  j.pivot = pivot;
  j.lower = lo;
  j.upper = hi;
  return j;
}

// The height of a leg frame's hips: its legs hanging straight down, feet flat on y = 0.
double hipHeight(const LegsSpec& d) {
  return 2 * d.footHalf.y() + d.ankleAboveFoot + d.tarsus.length + d.lower.length + d.upper.length;
}

// Appends upper leg, lower leg, the tarsus if it has one, and foot hanging straight down from
// `hip`; returns the Leg.
Leg addLeg(Morphology& m, const std::string& name, int legFrame, const Vector3d& hip, const LegsSpec& d,
           unsigned rgba) {
  const double hockY = hip.y() - d.upper.length - d.lower.length;
  const double ankleY = hockY - d.tarsus.length;  // for two segments, hockY itself
  const Vector3d knee(hip.x(), hip.y() - d.upper.length, hip.z());
  const Vector3d ankle(hip.x(), ankleY, hip.z());
  Leg leg;
  leg.name = name;
  leg.legFrame = legFrame;
  leg.kneeBend = d.kneeForward ? +1.0 : -1.0;

  Joint hj = ball(hip, d.hipLower, d.hipUpper);
  leg.upper = static_cast<int>(m.segments.size());
  m.segments.push_back({name + ".upper", {d.upper.halfThickness, d.upper.length / 2, d.upper.halfThickness},
                        d.upper.mass, {hip.x(), hip.y() - d.upper.length / 2, hip.z()}, legFrame, hj, rgba});
  // Knee flexion: a positive angle about +x swings the lower leg backwards (a knee that points
  // forward, as a human's); a knee that points backward mirrors the range.
  const double flexLo = d.kneeForward ? -d.hyperextension : -d.flexion;
  const double flexHi = d.kneeForward ? d.flexion : d.hyperextension;
  leg.lower = static_cast<int>(m.segments.size());
  m.segments.push_back({name + ".lower", {d.lower.halfThickness, d.lower.length / 2, d.lower.halfThickness},
                        d.lower.mass, {hip.x(), hockY + d.lower.length / 2, hip.z()}, leg.upper,
                        hinge(knee, flexLo, flexHi), rgba});
  if (d.tarsus.length > 0) {
    // The hock bends the other way to the knee: its flexion is the knee's mirrored.
    const double hockLo = d.kneeForward ? -d.hockFlexion : -d.hockHyperextension;
    const double hockHi = d.kneeForward ? d.hockHyperextension : d.hockFlexion;
    leg.tarsus = static_cast<int>(m.segments.size());
    m.segments.push_back({name + ".tarsus", {d.tarsus.halfThickness, d.tarsus.length / 2, d.tarsus.halfThickness},
                          d.tarsus.mass, {hip.x(), ankleY + d.tarsus.length / 2, hip.z()}, leg.lower,
                          hinge({hip.x(), hockY, hip.z()}, hockLo, hockHi), rgba});
  }
  leg.foot = static_cast<int>(m.segments.size());
  m.segments.push_back({name + ".foot", d.footHalf, d.footMass, {hip.x(), d.footHalf.y(), hip.z() + d.footForward},
                        leg.aboveAnkle(), universal(ankle, d.anklePitch, d.ankleRoll), d.foot});
  return leg;
}

Morphology build(const std::string& name, double armature, const std::vector<FrameSpec>& frames,
                 const std::vector<SpineSpec>& spine) {
  Morphology m;
  m.name = name;
  m.armature = armature;
  std::vector<double> centreY;
  for (const FrameSpec& f : frames) centreY.push_back(hipHeight(f.legs) + f.aboveHips);
  m.segments.push_back({frames[0].name, frames[0].half, frames[0].mass, {0, centreY[0], frames[0].z}, -1, Joint{},
                        frames[0].colour});
  m.legFrames = {0};
  int links = 0;
  for (size_t k = 0; k + 1 < frames.size(); ++k) {
    const SpineSpec& s = spine[k];
    const double link = (s.from - s.to) / s.links, lim = s.limit;
    int parent = m.legFrames.back();
    for (int i = 0; i < s.links; ++i) {
      const double zFront = s.from - i * link;
      m.segments.push_back({"spine." + std::to_string(links++), {s.halfWidth, s.halfHeight, link / 2}, s.mass,
                            {0, centreY[k], zFront - link / 2}, parent,
                            ball({0, centreY[k], zFront}, {-lim, -lim, -lim}, {lim, lim, lim}), s.colour});
      parent = static_cast<int>(m.segments.size()) - 1;
      m.spine.push_back(parent);
    }
    const FrameSpec& f = frames[k + 1];
    m.legFrames.push_back(static_cast<int>(m.segments.size()));
    m.segments.push_back({f.name, f.half, f.mass, {0, centreY[k + 1], f.z}, parent,
                          ball({0, centreY[k + 1], s.to}, {-lim, -lim, -lim}, {lim, lim, lim}), f.colour});
  }
  for (size_t k = 0; k < frames.size(); ++k) {
    const LegsSpec& d = frames[k].legs;
    const double hipY = hipHeight(d);
    const std::string prefix = d.name.empty() ? "" : d.name + ".";
    m.legs.push_back(addLeg(m, prefix + "left", m.legFrames[k], {d.hipSpacing, hipY, frames[k].z}, d, d.left));
    m.legs.push_back(addLeg(m, prefix + "right", m.legFrames[k], {-d.hipSpacing, hipY, frames[k].z}, d, d.right));
  }
  return m;
}

}  // namespace

std::optional<CreatureError> parseCreatureFile(const std::string& text, Morphology* out) {
  if (auto e = gait::checkJsonText(text)) return CreatureError{e->field, e->message};
  const json doc = json::parse(text, nullptr, false);
  if (doc.is_discarded()) return CreatureError{"", "not valid JSON"};
  Reader r;
  if (!r.fields(doc, "", {"format", "version", "name", "armature", "legFrames", "spine"})) return r.error;
  if (doc["format"] != kCreatureFormat)
    return CreatureError{"format", "expected \"" + std::string(kCreatureFormat) + "\", got " + gait::jsonShown(doc["format"])};
  int version = 0;
  std::string name;
  double armature = 0;
  if (!r.integer(doc["version"], "version", 1, kCreatureFormatVersion, &version) ||
      !r.text(doc["name"], "name", 1, &name) || !r.number(doc["armature"], "armature", 0, 1, &armature))
    return r.error;
  const json& fj = doc["legFrames"];
  if (!fj.is_array() || fj.empty() || fj.size() > kMaxCreatureLegFrames)
    return CreatureError{"legFrames", "expected an array of 1 to " + std::to_string(kMaxCreatureLegFrames) +
                                          " leg frames, got " + gait::jsonTypeName(fj)};
  std::vector<FrameSpec> frames(fj.size());
  for (size_t k = 0; k < fj.size(); ++k) {
    if (!readFrame(r, fj[k], at("legFrames", k), version, &frames[k])) return r.error;
    if (k > 0 && !(frames[k].z < frames[k - 1].z))
      return CreatureError{join(at("legFrames", k), "z"), "leg frames go front to back: expected less than " +
                                                              json(frames[k - 1].z).dump()};
  }
  const json& sj = doc["spine"];
  if (!sj.is_array() || sj.size() != frames.size() - 1)
    return CreatureError{"spine", "expected an array of " + std::to_string(frames.size() - 1) +
                                      " sections (one between each two leg frames), got " + gait::jsonTypeName(sj)};
  std::vector<SpineSpec> spine(sj.size());
  for (size_t k = 0; k < sj.size(); ++k) {
    const std::string path = at("spine", k);
    if (!readSpine(r, sj[k], path, &spine[k])) return r.error;
    // The section hangs between its two leg frames: it starts at or behind the front one's centre
    // and ends at or ahead of the back one's.
    if (!(spine[k].from <= frames[k].z)) return CreatureError{join(path, "from"), "ahead of legFrames[" + std::to_string(k) + "].z"};
    if (!(spine[k].to >= frames[k + 1].z)) return CreatureError{join(path, "to"), "behind legFrames[" + std::to_string(k + 1) + "].z"};
    if (!(spine[k].to < spine[k].from)) return CreatureError{join(path, "to"), "expected less than spine[" + std::to_string(k) + "].from"};
  }
  *out = build(name, armature, frames, spine);
  return std::nullopt;
}

std::optional<CreatureError> loadCreatureFile(const std::string& path, Morphology* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return CreatureError{"", "cannot read " + path};
  std::string text;
  text.resize(static_cast<size_t>(limits::kMaxJsonBytes) + 1);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<size_t>(in.gcount()));
  return parseCreatureFile(text, out);
}

}  // namespace gaitlab::body
