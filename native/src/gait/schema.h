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

enum class Character { Biped = 0, Quadruped = 1 };

const char* characterName(Character c);                            // "biped", "quadruped"
std::optional<Character> characterFromName(const std::string& name);
Character characterOf(const body::Morphology& morphology);  // by its number of leg frames

// One schema entry: what a parameter is. `knots` is 1 for a scalar and MotionGraph::kKnots (4)
// for a motion graph, whose knots all share the bounds.
struct ParamSpec {
  std::string name;
  const char* group;
  double min, max;
  const char* unit;  // SI; "" for a plain number, "1" for a fraction
  const char* description;
  int knots;
};

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

// The schema as JSON: {"version":1,"characters":{"biped":[entries],"quadruped":[entries]}},
// entry = {"name","group","min","max","default","unit","description","knots"}; `default` is the
// shipped preset's value (a number, or an array of knots). With `only`, one character.
std::string schemaJson(std::optional<Character> only = std::nullopt);

constexpr int kSchemaVersion = 2;

}  // namespace gaitlab::gait
