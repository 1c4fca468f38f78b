// The two shipped characters' bodies are creature files (public/creatures/biped.json and
// quadruped.json, body/creature.h), with real-world proportions and masses (not the original
// implementation's "scale 2" boxes, docs/original-implementation.md): a 59 kg human-sized biped
// (hip height 0.91 m) and a 33 kg dog-sized quadruped (shoulder height 0.49 m, leg frames 0.8 m
// apart, a 4-link spine of ±0.05π per axis as in the thesis, §3.1).
// The biped's proportions: thigh ≈ shin ≈ 0.245 × stature (Winter, Biomechanics of Human
// Movement); segment masses ≈ 10 % (thigh), 4.7 % (shank), 1.5 % (foot) of body mass, trunk, head
// and arms lumped into the leg frame, which is what the thesis's biped does as well. The
// quadruped's front knees (elbow and carpus) point backwards, its hind knees (stifle) forwards.
#include "body/morphology.h"

#include <cstdio>
#include <cstdlib>

#include "body/creature.h"

namespace gaitlab::body {

// They are embedded at build time and read by the tests, so a refusal here is a broken build, not
// bad input.
Morphology shippedCreature(const std::string& name) {
  const char* text = shippedCreatureText(name);
  if (!text) {
    std::fprintf(stderr, "gaitlab: no shipped creature file %s.json\n", name.c_str());
    std::abort();
  }
  Morphology m;
  if (auto error = parseCreatureFile(text, &m)) {
    std::fprintf(stderr, "gaitlab: the shipped creature file %s.json is refused: %s\n", name.c_str(),
                 error->describe().c_str());
    std::abort();
  }
  return m;
}

double Morphology::totalMass() const {
  double m = 0;
  for (const Segment& s : segments) m += s.mass;
  return m;
}

double Morphology::standingHeight() const { return segments[legFrames[0]].center.y(); }

Morphology makeBiped() {
  static const Morphology m = shippedCreature("biped");
  return m;
}

Morphology makeQuadruped() {
  static const Morphology m = shippedCreature("quadruped");
  return m;
}

}  // namespace gaitlab::body
