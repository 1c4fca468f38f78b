// Creature files: a body plan as JSON, from which a Morphology (body/morphology.h) is built. The
// shipped biped and quadruped are two such files (public/creatures/), embedded in the binary, so
// that a character's body, like its gait, is data. The thesis (Larsson 2015, §7.5) ends with
// creatures of any leg count designed by their players; this is the format they are written in.
//
//   {"format": "gaitlab-creature", "version": 1, 2 or 3, "name": "...", "armature": kg·m²,
//    "legFrames": [{                          front to back, 1 to 4
//      "name", "z": m (its centre, forward of the body's middle), "halfExtents": [x, y, z] m,
//      "mass": kg, "aboveHips": m (its centre above its hips), "colour": "#rrggbb",
//      "legs": {                              one pair, left (+x) and right (−x)
//        "name" (prefix of the legs' names, may be ""), "hipSpacing": m (each hip from the midline),
//        "hip": {"lower": [3 rad], "upper": [3 rad]},   swing about x (− forwards), twist (y), sideways (z)
//        "knee": {"points": "forward" | "backward", "flexion": rad, "hyperextension": rad},
//        "ankle": {"pitch": rad, "roll": rad},           symmetric ranges
//        "upper": {"length": m, "halfThickness": m, "mass": kg}, "lower": {the same},
//        "tarsus": {the same, "hock": {"flexion": rad, "hyperextension": rad}},   version 2, optional
//        "foot": {"halfExtents": [3 m], "forward": m (centre ahead of the ankle), "mass": kg,
//                 "ankleAboveFoot": m (the ankle's pivot above the top of the foot's box)},
//        "colours": {"left", "right", "foot"}}}],
//    "spine": [{                              one section between each two leg frames
//      "from": m, "to": m (z of its first and last joint), "links": 1 to 8, "halfWidth": m,
//      "halfHeight": m, "mass": kg (each link), "limit": rad (each axis of each joint),
//      "colour"}]}
//
// A leg has two segments (upper, lower) or, with a "tarsus" (version 2), three: as a dog's hind
// leg (femur, tibia, metatarsus) or a bird's, whose hock, between lower and tarsus, bends the other
// way to the knee. Version 1 is version 2 without the tarsus; both are read. Version 3 reads the
// hip's range as it is written; files of versions 1 and 2 were simulated with it mirrored (the
// physics read every ball joint's range the wrong way round, docs/controller-notes.md §76), so
// they are read mirrored, lower = −upper and upper = −lower, and walk as they did.
//
// Legs hang straight down from their hips at rest: a leg frame's hips sit at the height its legs
// reach, 2·foot half height + ankleAboveFoot + tarsus + lower + upper, and its centre `aboveHips` higher. Spine
// links lie at the height of the leg frame in front of them; the leg frame behind a section hangs
// from its last link by a ball joint at "to". Segments are numbered leg frames and spine links
// front to back, then the legs, each leg frame's left leg before its right.
//
// Like gait files (gait/params_io.h), a file is refused whole, with the field named, when anything
// is missing, unknown, of the wrong type or outside its range; nothing is built from it then.
#pragma once
#include <optional>
#include <string>

#include "body/morphology.h"

namespace gaitlab::body {

constexpr const char* kCreatureFormat = "gaitlab-creature";
constexpr int kCreatureFormatVersion = 3;
constexpr int kMaxCreatureLegFrames = 4;

// Why a creature file was refused: `field` the offending key as a path ("legFrames[1].legs.upper
// .mass"; empty when the text is not JSON at all), `message` what is wrong with it.
struct CreatureError {
  std::string field;
  std::string message;
  std::string describe() const { return field.empty() ? message : field + ": " + message; }
};

// Parses and validates `text` and builds its body. On success fills *out and returns nullopt; on
// failure returns the error and leaves *out as it was.
std::optional<CreatureError> parseCreatureFile(const std::string& text, Morphology* out);

// The same, reading a file from disk (an unreadable file is an error with an empty field).
std::optional<CreatureError> loadCreatureFile(const std::string& path, Morphology* out);

// The shipped creature files' text (public/creatures/<name>.json, embedded at configure time),
// or nullptr for another name.
const char* shippedCreatureText(const std::string& name);

}  // namespace gaitlab::body
