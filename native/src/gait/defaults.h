// Default gait parameters of the two characters: the shipped presets (public/presets/*.json),
// embedded into the binary at build time (native/CMakeLists.txt generates presets.cpp from
// them) and read through the same validating loader as any gait file (params_io.h). The preset
// files are the single source of default values; this code holds no numbers.
#pragma once
#include "body/morphology.h"
#include "gait/params.h"
#include "gait/schema.h"

namespace gaitlab::gait {

GaitParams defaultParams(Character c);
GaitParams defaultParams(const body::Morphology& morphology);

// The embedded preset file's text (the gait file format), as shipped.
const char* presetText(Character c);

}  // namespace gaitlab::gait
