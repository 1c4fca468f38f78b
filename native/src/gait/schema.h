// The parameter schema: one table naming, grouping, bounding and documenting every field of
// GaitParams (thesis §3.3 lists what is optimised: per controller, per leg frame, per leg).
//
// It is written once, as a visitor over a GaitParams (forEachParam), so that everything built on
// it agrees by construction: reading and writing gait files (params_io.h), validation, the
// optimiser's flat parameter vector, the schema exported to the web page (`gaitlab schema`,
// gl_schema_json) and the share-link codec. Defaults are not in this table: they are the
// shipped presets (public/presets/*.json, see defaults.h), loaded through the same schema.
//
// Names are dotted: controller fields bare (`period`), joint gains under `gains.`, leg-frame
// fields under the leg frame's name (biped `legFrame.`; quadruped `front.`, `back.`) and leg
// fields under the leg's name (biped `left.`, `right.`; quadruped `frontLeft.`, `frontRight.`,
// `backLeft.`, `backRight.`), in the morphology's leg order (body/morphology.cpp).
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "body/morphology.h"
#include "gait/params.h"

namespace gaitlab::gait {

// The kinds of character: the one list of them. Their numbers are the C ABI's GL_KIND_BIPED and
// GL_KIND_QUADRUPED (native/src/api/c_api.cpp checks it); the simulation uses this enum too; the
// page reads them from the exported schema ("morphologies": {name: {"kind": n, ...}}).
enum class Character { Biped = 0, Quadruped = 1 };
constexpr Character kCharacters[] = {Character::Biped, Character::Quadruped};

const char* characterName(Character c);                            // "biped", "quadruped"
std::optional<Character> characterFromName(const std::string& name);
// The character of a kind number (GL_KIND_*), or nullopt for a number that is not a character.
std::optional<Character> characterFromKind(int kind);
Character characterOf(const body::Morphology& morphology);  // by its number of leg frames

// The names parameters use for a character's leg frames and legs, in morphology order
// (body/morphology.cpp): biped {legFrame} and {left, right}; quadruped {front, back} and
// {frontLeft, frontRight, backLeft, backRight}.
const std::vector<std::string>& legFrameNames(Character c);
const std::vector<std::string>& legNames(Character c);

// One schema entry: what a parameter is. `knots` is 1 for a scalar and MotionGraph::kKnots (4)
// for a motion graph, whose knots all share the bounds. A per-leg-frame parameter names its leg
// frame and a per-leg one its leg (indices in morphology order, -1 otherwise), so that nothing
// downstream has to take names apart to find them; `field` is the name within that leg or leg
// frame ("dutyFactor"), or the whole name.
struct ParamSpec {
  std::string name;
  const char* group;
  double min, max;
  const char* unit;  // SI; "" for a plain number, "1" for a fraction
  const char* description;
  int knots;
  std::string field;
  int legFrame = -1;
  int leg = -1;
};

// Looks a parameter up by name; nullptr if the character has no such parameter.
const ParamSpec* findParam(Character c, const std::string& name);

// A parameter of one particular GaitParams: its spec and where its knots live.
struct ParamField {
  const ParamSpec& spec;
  double* values;  // spec.knots consecutive doubles inside the visited GaitParams
};

// Calls visit(field) for every parameter the character uses, in schema order (the order of the
// exported schema and of gait files). Fields a character does not use (the biped's second leg
// frame, legs 2 and 3, and spine gains) are not visited.
void forEachParam(Character c, GaitParams& params, const std::function<void(const ParamField&)>& visit);

// The specs alone, in schema order.
const std::vector<ParamSpec>& paramSpecs(Character c);

// Total number of doubles (knots counted) the character's parameters hold: the dimension of
// the optimiser's search space.
int paramDimension(Character c);

// Flat vector <-> GaitParams, in schema order, knots consecutive (the optimiser's view).
std::vector<double> toVector(Character c, const GaitParams& params);
void fromVector(Character c, const std::vector<double>& values, GaitParams* params);
// Per-dimension bounds, in the same order.
void bounds(Character c, std::vector<double>* lo, std::vector<double>* hi);

// The schema as JSON: {"version":5,"characters":{"biped":[entries],"quadruped":[entries]},
// "morphologies":{"biped":{"kind","legFrames":[{"index","name"}],"legs":[{"index","name",
// "legFrame","side"}]},...}}, entry = {"name","group","min","max","default","unit",
// "description","knots","field"} and, per leg frame or leg, "legFrame" or "leg": {"index","name"};
// `default` is the shipped preset's value (a number, or an array of knots). With `only`, one
// character.
std::string schemaJson(std::optional<Character> only = std::nullopt);

constexpr int kSchemaVersion = 8;

}  // namespace gaitlab::gait
