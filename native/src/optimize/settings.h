// The objective settings of a search as its two front ends give them, read by one function.
//
// The optimize panel hands gl_opt_create a JSON object ({"seconds":4,"speeds":[0.5,1],
// "grounds":["flat","slope@3.14159"],"wr":2}); `gaitlab optimize` takes the same settings as
// comma-separated options (--speeds 0.5,1 --grounds flat,slope@3.14159 --objective wr=2), which
// readObjectiveOptions turns into that object. Either way readObjectiveSettings checks every
// field against the table of objective.h (forEachSetting, kMinGoalSpeed, parseGround), so the
// bounds and the messages are the same in the browser and on the command line.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "optimize/objective.h"

namespace gaitlab::optimize {

// Reads an object of objective settings over `out`: keys are the scalar settings of
// forEachSetting (numbers), "speeds" (a non-empty array of goal speeds, m/s) and "grounds" (a
// non-empty array of strings, parseGround). Returns the first problem as "FIELD: WHAT" (or
// "unknown objective setting 'NAME'"), empty on success; `out` is unchanged on a problem.
std::string readObjectiveSettings(const nlohmann::json& object, ObjectiveSettings* out);

// The command line's options, as typed (each absent when not given): --speeds A,B,...,
// --grounds G,..., --objective NAME=V,.... Read through readObjectiveSettings; a problem is
// named by its option ("--speeds: 'fast' is not a speed in [-5, 5] m/s", "--objective: wr: -1.0
// is outside [0, 1000]").
std::string readObjectiveOptions(const std::optional<std::string>& speeds,
                                 const std::optional<std::string>& grounds,
                                 const std::optional<std::string>& objective, ObjectiveSettings* out);

// The table forms check their input against before a search (gl_opt_settings_json):
// {"settings":[{"name","min","max","default","unit","description","integer"},...],
//  "speeds":{"min","max","default","unit","description"},
//  "grounds":{"default","terrains","description"}}.
std::string objectiveSettingsTableJson();

}  // namespace gaitlab::optimize
