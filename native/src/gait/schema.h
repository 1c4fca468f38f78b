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

// The kinds of character: the one list of them. A kind is a layout of legs, one pair on each of
// one to four leg frames (body/creature.h), and names its leg frames and legs, so that a gait
// file, the optimiser's vector and a share link mean the same on every body of that layout.
// Each kind also has a shipped body (shippedBody): the biped, the quadruped, the insect and the
// spider (public/creatures/). Their numbers are the C ABI's GL_KIND_* (native/src/api/c_api.cpp
// checks it); the simulation uses this enum too; the page reads them from the exported schema
// ("morphologies": {name: {"kind": n, ...}}). The enum's values index tables (0 to
// kCharacterCount − 1); the C ABI's numbers are kindNumber's (2 and 3 were taken by the box and
// the alternating layout before there were more kinds than two).
enum class Character { Biped = 0, Quadruped = 1, Hexapod = 2, Octopod = 3 };
constexpr Character kCharacters[] = {Character::Biped, Character::Quadruped, Character::Hexapod,
                                     Character::Octopod};
constexpr int kCharacterCount = 4;

// "biped", "quadruped", "hexapod", "octopod"
const char* characterName(Character c);
std::optional<Character> characterFromName(const std::string& name);
// The C ABI's number of a kind (GL_KIND_BIPED 0, GL_KIND_QUADRUPED 1, GL_KIND_HEXAPOD 4,
// GL_KIND_OCTOPOD 5), and the character of such a number, or nullopt for a number that is not a
// character (GL_KIND_BOX is 2, GL_LAYOUT_ALTERNATING 3).
constexpr int kindNumber(Character c) {
  return c == Character::Biped ? 0 : c == Character::Quadruped ? 1 : c == Character::Hexapod ? 4 : 5;
}
std::optional<Character> characterFromKind(int kind);
// By its number of leg frames: 1 biped, 2 quadruped, 3 hexapod, 4 octopod.
Character characterOf(const body::Morphology& morphology);
// The kind's shipped body (public/creatures/{biped,quadruped,insect,spider}.json), built once.
const body::Morphology& shippedBody(Character c);
// Whether the kind's gait is derived from its body (gait/derived_gait.h) rather than a tuned
// preset (public/presets/): the kinds of more than two leg frames.
bool derivesGait(Character c);

// The names parameters use for a character's leg frames and legs, in morphology order
// (body/morphology.cpp): biped {legFrame} and {left, right}; quadruped {front, back} and
// {frontLeft, frontRight, backLeft, backRight}; hexapod {front, middle, back} and its legs
// {frontLeft, frontRight, middleLeft, middleRight, backLeft, backRight}; octopod {front,
// frontMiddle, backMiddle, back} and its eight legs named the same way.
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

// Where a character's parameters lie in a GaitParams: runs of consecutive doubles, `first`
// counted in doubles from the struct's start, in the order they lie there, adjacent fields merged
// into one run. They hold exactly the doubles forEachParam visits. For loops over every
// parameter that run in each control step, where a visitor call per field costs more than the
// work: blending speed keys (gait/speed_keys.cpp) while the desired speed ramps.
struct ParamRun {
  int first;
  int count;
};
const std::vector<ParamRun>& paramRuns(Character c);

// Total number of doubles (knots counted) the character's parameters hold: the dimension of
// the optimiser's search space.
int paramDimension(Character c);

// Flat vector <-> GaitParams, in schema order, knots consecutive (the optimiser's view).
std::vector<double> toVector(Character c, const GaitParams& params);
void fromVector(Character c, const std::vector<double>& values, GaitParams* params);
// Per-dimension bounds, in the same order.
void bounds(Character c, std::vector<double>* lo, std::vector<double>* hi);
// Brings each value of a flat vector (toVector's order) within its bounds.
void clampToBounds(Character c, std::vector<double>* values);

// The schema as JSON: {"version":5,"characters":{"biped":[entries],"quadruped":[entries]},
// "morphologies":{"biped":{"kind","legFrames":[{"index","name"}],"legs":[{"index","name",
// "legFrame","side"}]},...}}, entry = {"name","group","min","max","default","unit",
// "description","knots","field"} and, per leg frame or leg, "legFrame" or "leg": {"index","name"};
// `default` is the shipped preset's value (a number, or an array of knots). With `only`, one
// character.
std::string schemaJson(std::optional<Character> only = std::nullopt);

// The kinds of more than two leg frames came without a new version: they add files no older
// reader had, and change none it had.
constexpr int kSchemaVersion = 14;

}  // namespace gaitlab::gait
