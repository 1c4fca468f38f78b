#include "gait/defaults.h"

#include <cstdio>
#include <cstdlib>

#include "gait/params_io.h"

namespace gaitlab::gait {

namespace {

// The embedded preset, parsed once per character through the validating loader. A preset that
// fails validation is a build defect (the presets test catches it first): stop loudly rather
// than walk with half-set parameters.
Gait loadPreset(Character c) {
  GaitFile file;
  if (const auto error = parseGaitFile(presetText(c), c, &file)) {
    std::fprintf(stderr, "gaitlab: embedded preset public/presets/%s.json: %s\n", characterName(c),
                 error->describe().c_str());
    std::abort();
  }
  return file.gait;
}

}  // namespace

const Gait& defaultGait(Character c) {
  static const Gait biped = loadPreset(Character::Biped);
  static const Gait quadruped = loadPreset(Character::Quadruped);
  return c == Character::Biped ? biped : quadruped;
}

GaitParams defaultParams(Character c) { return defaultGait(c).primaryParams(); }

GaitParams defaultParams(const body::Morphology& m) { return defaultParams(characterOf(m)); }

}  // namespace gaitlab::gait
