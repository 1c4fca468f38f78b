#include "gait/defaults.h"

#include <cstdio>
#include <cstdlib>

#include "gait/derived_gait.h"
#include "gait/params_io.h"

namespace gaitlab::gait {

namespace {

// The embedded preset, parsed once per character through the validating loader. A preset that
// fails validation is a build defect (the presets test catches it first): stop loudly rather
// than walk with half-set parameters.
Gait loadPreset(Character c) {
  GaitFile file;
  if (const auto error = parseGaitFile(embeddedPresetText(c), c, &file)) {
    std::fprintf(stderr, "gaitlab: embedded preset public/presets/%s.json: %s\n", characterName(c),
                 error->describe().c_str());
    std::abort();
  }
  return file.gait;
}

// A kind of more than two leg frames: the gait derived from its shipped body, as one key at the
// speed it was taken from.
Gait derivedDefault(Character c) { return Gait::single(derivedGait(shippedBody(c)), kDerivedFromSpeed); }

}  // namespace

const Gait& defaultGait(Character c) {
  // Each its own static: the derived gaits read the quadruped's preset while they are made.
  static const Gait biped = loadPreset(Character::Biped);
  static const Gait quadruped = loadPreset(Character::Quadruped);
  if (c == Character::Biped) return biped;
  if (c == Character::Quadruped) return quadruped;
  static const Gait hexapod = derivedDefault(Character::Hexapod);
  static const Gait octopod = derivedDefault(Character::Octopod);
  return c == Character::Hexapod ? hexapod : octopod;
}

const char* presetText(Character c) {
  if (!derivesGait(c)) return embeddedPresetText(c);
  static const std::string hexapod = gaitFileJson(Character::Hexapod, defaultGait(Character::Hexapod));
  static const std::string octopod = gaitFileJson(Character::Octopod, defaultGait(Character::Octopod));
  return (c == Character::Hexapod ? hexapod : octopod).c_str();
}

GaitParams defaultParams(Character c) { return defaultGait(c).primaryParams(); }

GaitParams defaultParams(const body::Morphology& m) { return defaultParams(characterOf(m)); }

}  // namespace gaitlab::gait
