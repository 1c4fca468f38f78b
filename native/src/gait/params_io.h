// Gait files: a character's GaitParams as JSON, the one format used by the CLI (`--params`),
// the web page (export, import, share links), the optimiser's output and the shipped presets:
//
//   {"format": "gaitlab-gait", "version": 4, "character": "biped" | "quadruped",
//    "speed": m/s,                                          (optional, default 0)
//    "params": {"<schema name>": number | [4 numbers], ...},
//    "keys": [{"speed": m/s, "params": {...}}, ...],        (optional, default none)
//    "meta": {...optional: source, command, seed, objective, date, ...}}
//
// "params" is the gait's key parameter set tuned at "speed"; "keys" are more key sets tuned at
// other speeds, every one complete. The parameters in effect are blended by the desired speed
// (gait/speed_keys.h); a file without "keys" walks with "params" at every speed.
//
// Every schema field must be present, and nothing else; values finite and within the schema's
// bounds. A file that breaks any rule is refused with the field named, and the target is left
// untouched (the file is parsed into a copy, committed only when all of it is valid). A file of
// an older schema version is migrated first; this is the only place that knows how (the web page
// sends what it reads to normalizeGaitFile through gl_gait_normalize).
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "gait/params.h"
#include "gait/schema.h"
#include "gait/speed_keys.h"

namespace gaitlab::gait {

constexpr const char* kGaitFormat = "gaitlab-gait";
// The parameter schema's version (kSchemaVersion); files of older versions are migrated.
constexpr int kGaitFormatVersion = kSchemaVersion;

// Why a file was refused: `field` is the offending key (a schema name such as
// "legFrame.pitch", or a top-level key such as "version"; empty when the text is not JSON at
// all), `message` what is wrong with it.
struct ParamsError {
  std::string field;
  std::string message;
  std::string describe() const { return field.empty() ? message : field + ": " + message; }
};

struct GaitFile {
  Character character = Character::Biped;
  // Every key in speed order; the primary is the file's "speed" and "params", the others its "keys".
  Gait gait = Gait::single(GaitParams{});
  nlohmann::json meta = nlohmann::json::object();
};

// Whether `text` is JSON within the limits of api/limits.h (bytes, nesting depth, string and
// array lengths), checked in one iterative pass that builds nothing: every JSON text from outside
// goes through this before it is parsed. Returns the problem (empty field), or nullopt.
std::optional<ParamsError> checkJsonText(const std::string& text);

// For other formats read the way gait files are (body/creature.h): what a JSON value is ("a
// number", "an array of 3"), and a value as it appears in a message (at most 80 characters).
std::string jsonTypeName(const nlohmann::json& v);
std::string jsonShown(const nlohmann::json& v);

// Parses and validates `text`. With `expected`, a file for another character is refused.
// On success fills *out and returns nullopt; on failure returns the error and leaves *out as it
// was.
std::optional<ParamsError> parseGaitFile(const std::string& text, std::optional<Character> expected,
                                         GaitFile* out);

// The same, reading a file from disk (an unreadable file is an error with an empty field). It
// reads no more than api/limits.h's kMaxJsonBytes + 1 bytes, so an endless file returns too.
std::optional<ParamsError> loadGaitFile(const std::string& path, std::optional<Character> expected,
                                        GaitFile* out);

// Any gait file (any schema version) as the current version in canonical form: every parameter,
// in schema order, on one line, "meta" kept. On success fills *out; on failure returns the error.
std::optional<ParamsError> normalizeGaitFile(const std::string& text, std::string* out);

// A patch: {"<schema name>": number | [knots], ...}, some parameters of a character and their new
// values, each checked as in a gait file (a known name, finite, within bounds, the right number
// of knots). All or nothing: on success sets them in *params; on failure returns the first
// problem, naming the parameter, and leaves *params as it was.
std::optional<ParamsError> applyParamsPatch(Character c, const std::string& patch, GaitParams* params);
// The same for a whole gait: parameter names edit its primary key, "speed" (m/s) the speed that
// key is tuned at, and "keys" ([{"speed", "params"}, ...], as in a gait file) replaces its other
// keys. All or nothing, as above. A patch of every parameter with "speed" and "keys" sets the gait
// exactly (the page's undo, redo and imports).
std::optional<ParamsError> applyGaitPatch(Character c, const std::string& patch, Gait* gait);

// Serialises params in schema order; doubles print with enough digits to read back bit-exactly.
std::string gaitFileJson(Character c, const GaitParams& params,
                         const nlohmann::json& meta = nlohmann::json::object(), int indent = 2);
// The same for a gait of several keys: its primary key as "speed" and "params", the others as
// "keys" (with one key, exactly the file above).
std::string gaitFileJson(Character c, const Gait& gait,
                         const nlohmann::json& meta = nlohmann::json::object(), int indent = 2);

}  // namespace gaitlab::gait
