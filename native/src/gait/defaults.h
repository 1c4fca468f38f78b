// Starting gait parameters for the two characters, before tuning and optimization. The shipped
// presets (public/presets/*.json) are the tuned values; these are the hand-set starting points.
#pragma once
#include "body/morphology.h"
#include "gait/params.h"

namespace gaitlab::gait {

GaitParams defaultParams(const body::Morphology& morphology);

}  // namespace gaitlab::gait
