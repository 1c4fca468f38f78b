// Default gait parameters of each kind of character. The biped's and the quadruped's are the
// shipped presets (public/presets/*.json), embedded into the binary at build time
// (native/CMakeLists.txt generates presets.cpp from them) and read through the same validating
// loader as any gait file (params_io.h). The kinds of more than two leg frames have no tuned
// preset: theirs is the gait derived from their shipped body (gait/derived_gait.h), itself made
// from the quadruped's preset. This code holds no numbers.
#pragma once
#include "body/morphology.h"
#include "gait/params.h"
#include "gait/schema.h"
#include "gait/speed_keys.h"

namespace gaitlab::gait {

// The preset's gait: all its speed keys (gait/speed_keys.h).
const Gait& defaultGait(Character c);
// The preset's primary parameter set ("params" of the file).
GaitParams defaultParams(Character c);
GaitParams defaultParams(const body::Morphology& morphology);

// The default gait as a gait file: the embedded preset file's text as shipped, or for a kind
// that derives its gait, the derived gait written out (params_io.h).
const char* presetText(Character c);
// The embedded preset file's text; nullptr for a kind that derives its gait (derivesGait).
const char* embeddedPresetText(Character c);

}  // namespace gaitlab::gait
