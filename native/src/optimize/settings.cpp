#include "optimize/settings.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace gaitlab::optimize {

namespace {

using nlohmann::json;

// "a,b,c" -> {"a", "b", "c"}; "" -> {""}.
std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  size_t begin = 0;
  for (;;) {
    const size_t comma = text.find(',', begin);
    parts.push_back(text.substr(begin, comma - begin));
    if (comma == std::string::npos) return parts;
    begin = comma + 1;
  }
}

// A finite decimal number, the whole of `text`.
bool parseNumber(const std::string& text, double* out) {
  char* end = nullptr;
  *out = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && std::isfinite(*out);
}

// -5 rather than -5.0: bounds as people write them.
std::string shortNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::string readSpeeds(const json& value, std::vector<double>* out) {
  if (!value.is_array() || value.empty()) return "speeds: expected a non-empty array of numbers";
  out->clear();
  for (const json& v : value) {
    if (!v.is_number()) return "speeds: expected numbers";
    const double speed = v.get<double>();
    if (!(speed >= kMinGoalSpeed && speed <= kMaxGoalSpeed))
      return "speeds: " + v.dump() + " is outside [" + shortNumber(kMinGoalSpeed) + ", " +
             shortNumber(kMaxGoalSpeed) + "] m/s";
    out->push_back(speed);
  }
  return "";
}

std::string readGrounds(const json& value, std::vector<Ground>* out) {
  if (!value.is_array() || value.empty()) return "grounds: expected a non-empty array of strings";
  out->clear();
  for (const json& v : value) {
    if (!v.is_string()) return "grounds: expected strings such as \"slope@3.14159\"";
    Ground g;
    const std::string error = parseGround(v.get<std::string>(), &g);
    if (!error.empty()) return error;
    out->push_back(g);
  }
  return "";
}

}  // namespace

std::string readObjectiveSettings(const json& object, ObjectiveSettings* out) {
  if (!object.is_object()) return "objective settings: expected a JSON object";
  ObjectiveSettings s = *out;
  for (const auto& item : object.items()) {
    std::string error;
    if (item.key() == "speeds") {
      error = readSpeeds(item.value(), &s.speeds);
    } else if (item.key() == "grounds") {
      error = readGrounds(item.value(), &s.grounds);
    } else if (item.value().is_number()) {
      error = setSetting(s, item.key(), item.value().get<double>());
    } else {
      error = item.key() + ": expected a number";
    }
    if (!error.empty()) return error;
  }
  *out = s;
  return "";
}

std::string readObjectiveOptions(const std::optional<std::string>& speeds,
                                 const std::optional<std::string>& grounds,
                                 const std::optional<std::string>& objective, ObjectiveSettings* out) {
  ObjectiveSettings s = *out;
  if (speeds) {
    json list = json::array();
    for (const std::string& part : split(*speeds)) {
      double v;
      if (!parseNumber(part, &v)) return "--speeds: '" + part + "' is not a speed in [" + shortNumber(kMinGoalSpeed) + ", " +
                                      shortNumber(kMaxGoalSpeed) + "] m/s";
      list.push_back(v);
    }
    // readSpeeds names its field "speeds: ...".
    if (std::string error = readObjectiveSettings({{"speeds", list}}, &s); !error.empty()) return "--" + error;
  }
  if (grounds) {
    json list = json::array();
    for (const std::string& part : split(*grounds)) list.push_back(part);
    if (std::string error = readObjectiveSettings({{"grounds", list}}, &s); !error.empty()) return "--" + error;
  }
  if (objective) {
    json values = json::object();
    for (const std::string& part : split(*objective)) {
      const size_t eq = part.find('=');
      double v;
      if (eq == std::string::npos || !parseNumber(part.substr(eq + 1), &v))
        return "--objective: '" + part + "' is not NAME=NUMBER";
      // In the order given, so the first bad one is the one reported.
      if (std::string error = readObjectiveSettings({{part.substr(0, eq), v}}, &s); !error.empty())
        return "--objective: " + error;
    }
  }
  *out = s;
  return "";
}

std::string objectiveSettingsTableJson() {
  ObjectiveSettings defaults;
  nlohmann::ordered_json settings = nlohmann::ordered_json::array();
  forEachSetting(defaults, [&](const SettingSpec& spec, double& value) {
    settings.push_back({{"name", spec.name}, {"min", spec.min}, {"max", spec.max}, {"default", value},
                        {"unit", spec.unit}, {"description", spec.description}, {"integer", spec.integer}});
  });
  const nlohmann::ordered_json j = {
      {"settings", settings},
      {"speeds", {{"min", kMinGoalSpeed}, {"max", kMaxGoalSpeed}, {"default", defaults.speeds}, {"unit", "m/s"},
                  {"description", "goal speeds: every candidate walks an episode at each"}}},
      {"grounds", {{"default", nlohmann::ordered_json::array({"flat"})},
                   {"terrains", nlohmann::ordered_json::array({"flat", "slope", "bumps"})},
                   {"description", "grounds: every candidate walks an episode on each, written TERRAIN or "
                                   "TERRAIN@HEADING (rad it starts facing)"}}}};
  return j.dump();
}

}  // namespace gaitlab::optimize
