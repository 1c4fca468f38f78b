#include "gait/params_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "api/limits.h"

namespace gaitlab::gait {

namespace {

using nlohmann::json;

// The limits of api/limits.h, checked in one pass over the text before any document is built:
// nlohmann's SAX parser is iterative, so this pass holds one counter per level however deep the
// text goes, and stops at the first breach. Only text that passes is parsed into a DOM (whose
// copies and dump() recurse, and so must never see untrusted depth). nlohmann's DOM parser,
// with exceptions compiled out, only says "discarded": this pass also recovers its message (line
// and column) for a file that is not JSON at all.
struct LimitCheck : json::json_sax_t {
  std::string error;
  std::vector<long> counts;  // elements so far of each open array or object, innermost last
  bool value() {
    if (!counts.empty() && ++counts.back() > limits::kMaxJsonArray)
      return fail("an array or object has more than " + std::to_string(limits::kMaxJsonArray) + " elements");
    return true;
  }
  bool fail(std::string message) {
    error = std::move(message);
    return false;
  }
  bool text(const string_t& s) {
    if (static_cast<long>(s.size()) > limits::kMaxJsonString)
      return fail("a string is longer than " + std::to_string(limits::kMaxJsonString) + " bytes");
    return true;
  }
  bool open() {
    if (!value()) return false;
    if (static_cast<int>(counts.size()) >= limits::kMaxJsonDepth)
      return fail("nested deeper than " + std::to_string(limits::kMaxJsonDepth) + " levels");
    counts.push_back(0);
    return true;
  }
  bool close() {
    counts.pop_back();
    return true;
  }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t& s) override { return text(s) && value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(); }
  // A key is counted with its value, not on its own.
  bool key(string_t& s) override { return text(s); }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    std::string what = e.what();  // its "last read" may quote a long token
    if (what.size() > 200) what = what.substr(0, 197) + "...";
    return fail("not valid JSON: " + what);
  }
};

std::string typeName(const json& v) {
  if (v.is_number()) return "a number";
  if (v.is_array()) return "an array of " + std::to_string(v.size());
  if (v.is_string()) return "a string";
  if (v.is_object()) return "an object";
  if (v.is_boolean()) return "a boolean";
  return "null";
}

std::string num(double v) { return json(v).dump(); }

// A value as it appears in a message: at most 80 characters of its JSON (a refused field may be
// a long string or a large object).
std::string shown(const json& v) {
  std::string text = v.dump(-1, ' ', false, json::error_handler_t::replace);
  if (text.size() > 80) text = text.substr(0, 77) + "...";
  return text;
}

// One value of a field: a finite number within the spec's bounds.
std::optional<std::string> checkNumber(const json& v, const ParamSpec& s, double* out) {
  if (!v.is_number()) return "expected a number, got " + typeName(v);
  const double x = v.get<double>();
  if (!std::isfinite(x)) return std::string("not finite");
  if (x < s.min || x > s.max)
    return num(x) + " is outside [" + num(s.min) + ", " + num(s.max) + "]";
  *out = x;
  return std::nullopt;
}

// All knots of one parameter, checked: a number for a scalar, an array of `knots` numbers for a
// motion graph. A knot out of bounds is named with its index ("legFrame.pitch[2]").
std::optional<ParamsError> readValue(const json& v, const ParamSpec& s, double* values) {
  if (s.knots == 1) {
    if (auto e = checkNumber(v, s, &values[0])) return ParamsError{s.name, *e};
    return std::nullopt;
  }
  if (!v.is_array() || static_cast<int>(v.size()) != s.knots)
    return ParamsError{s.name, "expected an array of " + std::to_string(s.knots) +
                                   " numbers (motion graph knots), got " + typeName(v)};
  for (int k = 0; k < s.knots; ++k) {
    if (auto e = checkNumber(v[k], s, &values[k])) return ParamsError{s.name + "[" + std::to_string(k) + "]", *e};
  }
  return std::nullopt;
}

// Parses JSON text within api/limits.h's limits, or says where it stops being JSON or which
// limit it breaks.
std::optional<ParamsError> parseJson(const std::string& text, json* out) {
  if (auto error = checkJsonText(text)) return error;
  *out = json::parse(text, nullptr, false);
  if (out->is_discarded()) return ParamsError{"", "not valid JSON"};  // the check said it was
  return std::nullopt;
}

// Brings the parameters of a file for `c` made against schema `version` up to kSchemaVersion,
// one version at a time. The only migrations there are: the web page and the CLI both read gait
// files through parseGaitFile.
void migrateParams(Character c, int version, json* params) {
  if (version < 2) {
    // 2: the quadruped's whole-body stance replaced the per-leg-frame support gain, and the swing
    // PDs may follow their targets' velocity (gains.swingTargetRate; 0 is the old behaviour).
    for (auto it = params->begin(); it != params->end();) {
      const std::string& key = it.key();
      const std::string suffix = ".supportGain";
      if (key.size() > suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0)
        it = params->erase(it);
      else
        ++it;
    }
    if (!params->contains("gains.swingTargetRate")) (*params)["gains.swingTargetRate"] = 0.0;
  }
  if (version < 3) {
    // 3: inverted-pendulum foot placement at low speed (capturePlacement per leg frame; weight 0
    // places the feet as version 2 did) and speed tracking (speedIntegralGain; 0 is F_v as before).
    if (!params->contains("speedIntegralGain")) (*params)["speedIntegralGain"] = 0.0;
    for (const char* frame : {"legFrame", "front", "back"}) {
      const std::string weight = std::string(frame) + ".capturePlacement";
      if (!params->contains(std::string(frame) + ".footPlacementScale") || params->contains(weight)) continue;
      (*params)[weight] = 0.0;
      (*params)[std::string(frame) + ".captureBlendSpeed"] = 0.5;
      (*params)[std::string(frame) + ".captureSideways"] = 0.05;
    }
  }
  // 4: speed keys ("speed" and "keys" beside "params", gait/speed_keys.h); the parameters are
  // unchanged, and a file without keys walks as before.
  if (version < 5) {
    // 5: speed tracking's proportional term on the stride-mean speed error
    // (speedProportionalGain; 0 is F_v as before).
    if (!params->contains("speedProportionalGain")) (*params)["speedProportionalGain"] = 0.0;
  }
  if (version < 6) {
    // 6: standing on planted feet at goal 0 (standSpeed; 0 steps in place as before).
    if (!params->contains("standSpeed")) (*params)["standSpeed"] = 0.0;
  }
  if (version < 7) {
    // 7: speed tracking's trim bound per key (maxSpeedTrim; 0.5 m/s is the old constant).
    if (!params->contains("maxSpeedTrim")) (*params)["maxSpeedTrim"] = 0.5;
  }
  if (version < 8) {
    // 8: where speed tracking starts, per key (speedTrackedFrom; 0.15 m/s is the old constant).
    if (!params->contains("speedTrackedFrom")) (*params)["speedTrackedFrom"] = 0.15;
  }
  if (version < 9) {
    // 9: where in its cycle a key's gait is left for another footfall pattern (transitionPhase;
    // 0, the cycle's start, is where every change was taken).
    if (!params->contains("transitionPhase")) (*params)["transitionPhase"] = 0.0;
  }
  if (version < 10) {
    // 10: how far a turn's heading may lead the body's path, per key (maxTurnSlip; 5 m/s bounds
    // nothing, as before).
    if (!params->contains("maxTurnSlip")) (*params)["maxTurnSlip"] = kNoTurnSlipBound;
  }
  if (version < 11) {
    // 11: strike points moved outwards from a turn, per key (turnPlacement; 0 places them as if
    // going straight, as before).
    if (!params->contains("turnPlacement")) (*params)["turnPlacement"] = 0.0;
  }
  if (version < 12) {
    // 12: the roll moment of a turn's sideways force left to the stance, per key
    // (turnRollMoment; 0 cancels it, as before).
    if (!params->contains("turnRollMoment")) (*params)["turnRollMoment"] = 0.0;
  }
  if (version < 13 && c == Character::Biped) {
    // 13: turnRollMoment only where it acts, in the whole-body stance of several leg frames; a
    // body of one leg frame was given it by 12 and never read it, so dropping it changes nothing.
    params->erase("turnRollMoment");
  }
  if (version < 14 && c == Character::Biped) {
    // 14: the body of one leg frame flexes its hips 2 rad; its gaits, all searched on a hip that
    // stopped at 0.7 rad, keep that stop as the walking controller's (hipForwardStop).
    if (!params->contains("hipForwardStop")) (*params)["hipForwardStop"] = 0.7;
  }
}

// A key's speed: a finite number of m/s within the goal speeds a character may be given.
std::optional<ParamsError> readSpeed(const json& v, const std::string& field, double* out) {
  if (!v.is_number()) return ParamsError{field, "expected a number of m/s, got " + typeName(v)};
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < 0 || x > limits::kMaxGoalSpeed)
    return ParamsError{field, num(x) + " is outside [0, " + num(limits::kMaxGoalSpeed) + "] m/s"};
  *out = x;
  return std::nullopt;
}

// Whether `speed` is one a key already has (within 1e-9 m/s, as Gait::keyAt): the refusal for
// `field`, or nullopt.
std::optional<ParamsError> speedTaken(double speed, const std::vector<double>& taken, const std::string& field) {
  for (double other : taken) {
    if (std::abs(other - speed) <= 1e-9) return ParamsError{field, "another key is already tuned at " + num(speed) + " m/s"};
  }
  return std::nullopt;
}

// One complete parameter set ("params" of a file or of one of its keys): every schema field of
// the character, migrated from `version`, nothing else. `prefix` goes before the field names in
// messages ("keys[0].params."). Fills *params only where the schema visits; returns the first
// problem.
std::optional<ParamsError> readParams(Character c, const json& given, int version, const std::string& prefix,
                                      GaitParams* params) {
  const std::string self = prefix.empty() ? "params" : prefix.substr(0, prefix.size() - 1);
  if (!given.is_object()) return ParamsError{self, "expected an object, got " + typeName(given)};
  json pj = given;
  migrateParams(c, version, &pj);
  GaitParams copy = *params;
  std::optional<ParamsError> error;
  std::set<std::string> known;
  forEachParam(c, copy, [&](const ParamField& f) {
    known.insert(f.spec.name);
    if (error) return;
    const auto it = pj.find(f.spec.name);
    if (it == pj.end()) {
      error = ParamsError{prefix + f.spec.name, "missing"};
      return;
    }
    error = readValue(*it, f.spec, f.values);
    if (error) error->field = prefix + error->field;
  });
  if (error) return error;
  for (const auto& item : pj.items()) {
    if (!known.count(item.key()))
      return ParamsError{prefix + item.key(), std::string("unknown parameter for a ") + characterName(c)};
  }
  *params = copy;
  return std::nullopt;
}

// "keys" of a file or a patch: at most kMaxSpeedKeys - 1 complete parameter sets, each at its own
// speed, none at `primarySpeed`, into *keys in the file's order (Gait::of orders them by speed).
// A key's fields not visited by the schema start from `base`.
std::optional<ParamsError> readKeys(Character c, const json& kj, int version, const GaitParams& base,
                                    double primarySpeed, std::vector<SpeedKey>* keys) {
  if (!kj.is_array()) return ParamsError{"keys", "expected an array, got " + typeName(kj)};
  if (static_cast<int>(kj.size()) > kMaxSpeedKeys - 1)
    return ParamsError{"keys", "at most " + std::to_string(kMaxSpeedKeys - 1) + " keys besides \"params\", got " +
                                   std::to_string(kj.size())};
  std::vector<SpeedKey> read;
  std::vector<double> speeds = {primarySpeed};
  for (size_t i = 0; i < kj.size(); ++i) {
    const std::string where = "keys[" + std::to_string(i) + "]";
    const json& key = kj[i];
    if (!key.is_object()) return ParamsError{where, "expected an object, got " + typeName(key)};
    for (const auto& item : key.items()) {
      if (item.key() != "speed" && item.key() != "params") return ParamsError{where + "." + item.key(), "unknown field"};
    }
    SpeedKey k;
    k.params = base;
    if (!key.contains("speed")) return ParamsError{where + ".speed", "missing"};
    if (auto error = readSpeed(key["speed"], where + ".speed", &k.speed)) return error;
    if (auto error = speedTaken(k.speed, speeds, where + ".speed")) return error;
    speeds.push_back(k.speed);
    if (!key.contains("params")) return ParamsError{where + ".params", "missing"};
    if (auto error = readParams(c, key["params"], version, where + ".params.", &k.params)) return error;
    read.push_back(k);
  }
  *keys = std::move(read);
  return std::nullopt;
}

}  // namespace

std::string jsonTypeName(const nlohmann::json& v) { return typeName(v); }
std::string jsonShown(const nlohmann::json& v) { return shown(v); }

std::optional<ParamsError> checkJsonText(const std::string& text) {
  if (static_cast<long>(text.size()) > limits::kMaxJsonBytes)
    return ParamsError{"", "the text is " + std::to_string(text.size()) + " bytes long; at most " +
                               std::to_string(limits::kMaxJsonBytes) + " are accepted"};
  LimitCheck check;
  if (!json::sax_parse(text, &check) || !check.error.empty())
    return ParamsError{"", check.error.empty() ? "not valid JSON" : check.error};
  return std::nullopt;
}

std::optional<ParamsError> parseGaitFile(const std::string& text, std::optional<Character> expected,
                                         GaitFile* out) {
  json doc;
  if (auto error = parseJson(text, &doc)) return error;
  if (!doc.is_object()) return ParamsError{"", "expected a JSON object, got " + typeName(doc)};
  static const std::set<std::string> kTopLevel = {"format", "version", "character", "speed",
                                                  "params", "keys", "meta"};
  for (const auto& item : doc.items()) {
    if (!kTopLevel.count(item.key())) return ParamsError{item.key(), "unknown field"};
  }
  if (!doc.contains("format")) return ParamsError{"format", "missing"};
  if (doc["format"] != kGaitFormat)
    return ParamsError{"format", "expected \"" + std::string(kGaitFormat) + "\", got " + shown(doc["format"])};
  if (!doc.contains("version")) return ParamsError{"version", "missing"};
  if (!doc["version"].is_number_integer() || doc["version"].get<long long>() < 1 ||
      doc["version"].get<long long>() > kGaitFormatVersion)
    return ParamsError{"version", "expected 1 to " + std::to_string(kGaitFormatVersion) + ", got " +
                                      shown(doc["version"])};
  const int version = static_cast<int>(doc["version"].get<long long>());
  if (!doc.contains("character")) return ParamsError{"character", "missing"};
  const json& cj = doc["character"];
  const std::optional<Character> character =
      cj.is_string() ? characterFromName(cj.get<std::string>()) : std::nullopt;
  if (!character) {
    std::string names;
    for (Character c : kCharacters) names += std::string(names.empty() ? "" : " or ") + "\"" + characterName(c) + "\"";
    return ParamsError{"character", "expected " + names + ", got " + shown(cj)};
  }
  if (expected && *expected != *character)
    return ParamsError{"character", std::string("the file is for a ") + characterName(*character) +
                                        ", not a " + characterName(*expected)};
  if (doc.contains("meta") && !doc["meta"].is_object())
    return ParamsError{"meta", "expected an object, got " + typeName(doc["meta"])};
  for (const char* key : {"speed", "keys"}) {
    if (doc.contains(key) && version < 4)
      return ParamsError{key, "speed keys need a file of version 4 or later, this one is version " +
                                  std::to_string(version)};
  }

  // Parse into a copy of the target: a refused file leaves *out as it was.
  GaitFile file;
  file.character = *character;
  SpeedKey primary{0.0, out->gait.primaryParams()};
  std::vector<SpeedKey> others;
  if (doc.contains("speed")) {
    if (auto error = readSpeed(doc["speed"], "speed", &primary.speed)) return error;
  }
  if (!doc.contains("params")) return ParamsError{"params", "missing"};
  if (auto error = readParams(*character, doc["params"], version, "", &primary.params)) return error;
  if (doc.contains("keys")) {
    if (auto error = readKeys(*character, doc["keys"], version, primary.params, primary.speed, &others)) return error;
  }
  if (doc.contains("meta")) file.meta = doc["meta"];
  file.gait = Gait::of(std::move(primary), std::move(others));
  *out = std::move(file);
  return std::nullopt;
}

std::optional<ParamsError> normalizeGaitFile(const std::string& text, std::string* out) {
  GaitFile file;
  if (auto error = parseGaitFile(text, std::nullopt, &file)) return error;
  *out = gaitFileJson(file.character, file.gait, file.meta, -1);
  return std::nullopt;
}

namespace {

// applyParamsPatch on a parsed patch object; every name in it must be a parameter's.
std::optional<ParamsError> applyParamValues(Character c, const json& patch, GaitParams* params) {
  // Every value is read into a copy first: a refused patch changes nothing.
  GaitParams copy = *params;
  std::optional<ParamsError> error;
  for (const auto& item : patch.items()) {
    if (!findParam(c, item.key()))
      return ParamsError{item.key(), std::string("unknown parameter for a ") + characterName(c)};
  }
  forEachParam(c, copy, [&](const ParamField& f) {
    if (error) return;
    const auto it = patch.find(f.spec.name);
    if (it != patch.end()) error = readValue(*it, f.spec, f.values);
  });
  if (error) return error;
  *params = copy;
  return std::nullopt;
}

}  // namespace

std::optional<ParamsError> applyParamsPatch(Character c, const std::string& text, GaitParams* params) {
  json patch;
  if (auto error = parseJson(text, &patch)) return error;
  if (!patch.is_object())
    return ParamsError{"", "expected a JSON object of parameter values, got " + typeName(patch)};
  return applyParamValues(c, patch, params);
}

std::optional<ParamsError> applyGaitPatch(Character c, const std::string& text, Gait* gait) {
  json patch;
  if (auto error = parseJson(text, &patch)) return error;
  if (!patch.is_object())
    return ParamsError{"", "expected a JSON object of parameter values, got " + typeName(patch)};
  // The primary key and the others, as a file has them; the gait is rebuilt from them at the end.
  SpeedKey primary = gait->keys[gait->primary];
  std::vector<SpeedKey> others;
  for (size_t i = 0; i < gait->keys.size(); ++i)
    if (static_cast<int>(i) != gait->primary) others.push_back(gait->keys[i]);
  if (patch.contains("speed")) {
    if (auto error = readSpeed(patch["speed"], "speed", &primary.speed)) return error;
  }
  json params = patch;
  params.erase("speed");
  params.erase("keys");
  if (auto error = applyParamValues(c, params, &primary.params)) return error;
  if (patch.contains("keys")) {
    if (auto error = readKeys(c, patch["keys"], kGaitFormatVersion, primary.params, primary.speed, &others)) return error;
  } else {
    std::vector<double> taken;
    for (const SpeedKey& other : others) taken.push_back(other.speed);
    if (auto error = speedTaken(primary.speed, taken, "speed")) return error;
  }
  *gait = Gait::of(std::move(primary), std::move(others));
  return std::nullopt;
}

std::optional<ParamsError> loadGaitFile(const std::string& path, std::optional<Character> expected,
                                        GaitFile* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return ParamsError{"", "cannot be read"};
  // At most one byte more than a gait file may have: a huge file, or an endless one such as
  // /dev/zero or a FIFO that never closes its end, is refused after reading no more than that.
  std::string text(static_cast<size_t>(limits::kMaxJsonBytes) + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) return ParamsError{"", "cannot be read"};
  text.resize(static_cast<size_t>(in.gcount()));
  if (static_cast<long>(text.size()) > limits::kMaxJsonBytes)
    return ParamsError{"", "the file is longer than " + std::to_string(limits::kMaxJsonBytes) +
                               " bytes, more than any gait file"};
  return parseGaitFile(text, expected, out);
}

namespace {

using ordered = nlohmann::ordered_json;

ordered paramsObject(Character c, const GaitParams& params) {
  ordered p = ordered::object();
  GaitParams copy = params;
  forEachParam(c, copy, [&](const ParamField& f) {
    if (f.spec.knots == 1) {
      p[f.spec.name] = f.values[0];
    } else {
      p[f.spec.name] = std::vector<double>(f.values, f.values + f.spec.knots);
    }
  });
  return p;
}

}  // namespace

std::string gaitFileJson(Character c, const GaitParams& params, const nlohmann::json& meta, int indent) {
  return gaitFileJson(c, Gait::single(params), meta, indent);
}

std::string gaitFileJson(Character c, const Gait& gait, const nlohmann::json& meta, int indent) {
  const SpeedKey& primary = gait.keys[gait.primary];
  ordered doc = {{"format", kGaitFormat}, {"version", kGaitFormatVersion}, {"character", characterName(c)}};
  // A gait of one key tuned at 0 (any file before speed keys) is written as before them.
  const bool keyed = gait.keys.size() > 1 || primary.speed != 0;
  if (keyed) doc["speed"] = primary.speed;
  doc["params"] = paramsObject(c, primary.params);
  if (keyed) {
    ordered keys = ordered::array();
    for (size_t i = 0; i < gait.keys.size(); ++i) {
      if (static_cast<int>(i) == gait.primary) continue;
      keys.push_back(ordered{{"speed", gait.keys[i].speed}, {"params", paramsObject(c, gait.keys[i].params)}});
    }
    doc["keys"] = keys;
  }
  // Strings of "meta" may come from outside (a command line in another encoding): any byte that is
  // not UTF-8 is written as U+FFFD rather than stopping the program (dump() aborts on it
  // otherwise, exceptions being compiled out).
  constexpr auto kReplace = json::error_handler_t::replace;
  if (!meta.empty()) doc["meta"] = ordered::parse(meta.dump(-1, ' ', false, kReplace), nullptr, false);
  if (indent < 0) return doc.dump(-1, ' ', false, kReplace);
  // Readable layout for files people edit and diff: one parameter per line, a motion graph's
  // knots together on its line. Every value is still written by nlohmann (shortest text that
  // reads back to the same double).
  const std::string pad(indent, ' ');
  const auto paramLines = [&](const ordered& params, const std::string& at) {
    std::string text = "{\n";
    bool first = true;
    for (const auto& param : params.items()) {
      text += (first ? "" : ",\n") + at + pad + ordered(param.key()).dump() + ": " + param.value().dump();
      first = false;
    }
    return text + "\n" + at + "}";
  };
  std::string out = "{\n";
  bool firstKey = true;
  for (const auto& item : doc.items()) {
    out += (firstKey ? "" : ",\n") + pad + ordered(item.key()).dump() + ": ";
    firstKey = false;
    if (item.key() == "params") {
      out += paramLines(item.value(), pad);
    } else if (item.key() == "keys") {
      out += "[";
      bool firstEntry = true;
      for (const auto& key : item.value()) {
        out += std::string(firstEntry ? "\n" : ",\n") + pad + pad + "{\"speed\": " + key["speed"].dump() +
               ", \"params\": " + paramLines(key["params"], pad + pad) + "}";
        firstEntry = false;
      }
      out += item.value().empty() ? "]" : "\n" + pad + "]";
    } else {
      out += item.value().dump(-1, ' ', false, kReplace);
    }
  }
  return out + "\n}\n";
}

}  // namespace gaitlab::gait
