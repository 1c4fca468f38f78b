// Default gait parameters of the two characters: the shipped presets (public/presets/*.json),
// embedded into the binary at build time (native/CMakeLists.txt generates presets.cpp from
// them) and read through the same validating loader as any gait file (params_io.h). The preset
// files are the single source of default values; this code holds no numbers.
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

// The embedded preset file's text (the gait file format), as shipped.
const char* presetText(Character c);

}  // namespace gaitlab::gait
