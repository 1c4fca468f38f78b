#include "gait/params_io.h"

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

// Brings the parameters of a file made against schema `version` up to kSchemaVersion, one
// version at a time. The only migrations there are: the web page and the CLI both read gait
// files through parseGaitFile.
void migrateParams(int version, json* params) {
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
}

}  // namespace

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
  static const std::set<std::string> kTopLevel = {"format", "version", "character", "params", "meta"};
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
  if (!doc.contains("params")) return ParamsError{"params", "missing"};
  if (!doc["params"].is_object()) return ParamsError{"params", "expected an object, got " + typeName(doc["params"])};
  json pj = doc["params"];
  migrateParams(version, &pj);

  // Parse into a copy of the target: a refused file leaves *out as it was.
  GaitFile file;
  file.character = *character;
  file.params = out->params;
  std::optional<ParamsError> error;
  std::set<std::string> known;
  forEachParam(*character, file.params, [&](const ParamField& f) {
    known.insert(f.spec.name);
    if (error) return;
    const auto it = pj.find(f.spec.name);
    if (it == pj.end()) {
      error = ParamsError{f.spec.name, "missing"};
      return;
    }
    error = readValue(*it, f.spec, f.values);
  });
  if (error) return error;
  for (const auto& item : pj.items()) {
    if (!known.count(item.key()))
      return ParamsError{item.key(), std::string("unknown parameter for a ") + characterName(*character)};
  }
  if (doc.contains("meta")) file.meta = doc["meta"];
  *out = std::move(file);
  return std::nullopt;
}

std::optional<ParamsError> normalizeGaitFile(const std::string& text, std::string* out) {
  GaitFile file;
  if (auto error = parseGaitFile(text, std::nullopt, &file)) return error;
  *out = gaitFileJson(file.character, file.params, file.meta, -1);
  return std::nullopt;
}

std::optional<ParamsError> applyParamsPatch(Character c, const std::string& text, GaitParams* params) {
  json patch;
  if (auto error = parseJson(text, &patch)) return error;
  if (!patch.is_object())
    return ParamsError{"", "expected a JSON object of parameter values, got " + typeName(patch)};
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

std::string gaitFileJson(Character c, const GaitParams& params, const nlohmann::json& meta, int indent) {
  using ordered = nlohmann::ordered_json;
  ordered p = ordered::object();
  GaitParams copy = params;
  forEachParam(c, copy, [&](const ParamField& f) {
    if (f.spec.knots == 1) {
      p[f.spec.name] = f.values[0];
    } else {
      p[f.spec.name] = std::vector<double>(f.values, f.values + f.spec.knots);
    }
  });
  ordered doc = {{"format", kGaitFormat}, {"version", kGaitFormatVersion},
                 {"character", characterName(c)}, {"params", p}};
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
  std::string out = "{\n";
  bool firstKey = true;
  for (const auto& item : doc.items()) {
    out += (firstKey ? "" : ",\n") + pad + ordered(item.key()).dump() + ": ";
    firstKey = false;
    if (item.key() != "params") {
      out += item.value().dump(-1, ' ', false, kReplace);
      continue;
    }
    out += "{\n";
    bool firstParam = true;
    for (const auto& param : item.value().items()) {
      out += (firstParam ? "" : ",\n") + pad + pad + ordered(param.key()).dump() + ": " +
             param.value().dump();
      firstParam = false;
    }
    out += "\n" + pad + "}";
  }
  return out + "\n}\n";
}

}  // namespace gaitlab::gait
