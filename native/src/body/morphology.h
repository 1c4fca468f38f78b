// Character morphology as data (thesis §3.1, Figures 3.1 and 3.2): rigid segments joined by
// joints, grouped into leg frames, legs and a spine. The controller (gait/) and the Bullet
// adapter (physics/) both read a character only through this description, so bipeds and
// quadrupeds run the same code.
//
// Frame convention: character frame at heading 0, y up, +z forward, +x to the character's left,
// feet resting on y = 0. Units: metres, kilograms, radians.
#pragma once
#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

namespace gaitlab::body {

using Eigen::Vector3d;

enum class JointType {
  Root,       // the segment has no parent (the first leg frame)
  Hinge,      // 1 DOF about axes[0]
  Universal,  // 2 DOF about axes[0], axes[1]
  Ball,       // 3 DOF about axes[0..2]
};

inline int dofCount(JointType t) {
  switch (t) {
    case JointType::Root: return 0;
    case JointType::Hinge: return 1;
    case JointType::Universal: return 2;
    case JointType::Ball: return 3;
  }
  return 0;
}

struct Joint {
  JointType type = JointType::Root;
  Vector3d pivot = Vector3d::Zero();  // rest pose, character frame
  // DOF axes in the parent's frame at rest (= character frame: segments start unrotated).
  std::array<Vector3d, 3> axes = {Vector3d::UnitX(), Vector3d::UnitY(), Vector3d::UnitZ()};
  std::array<double, 3> lower = {0, 0, 0};  // joint limits per DOF, radians
  std::array<double, 3> upper = {0, 0, 0};
};

struct Segment {
  std::string name;
  Vector3d halfExtents;  // box, metres
  double mass;           // kilograms
  Vector3d center;       // rest pose centre of mass, character frame
  int parent;            // index of the parent segment, -1 for the root
  Joint joint;           // joint to the parent
  unsigned rgba;         // display colour
};

// One leg: a chain leg frame -> upper -> lower -> foot (hip, knee, ankle joints), or of three
// segments, leg frame -> upper -> lower -> tarsus -> foot (hip, knee, hock, ankle), as a dog's
// hind leg (femur, tibia, metatarsus) or a bird's. The hock bends the other way to the knee.
struct Leg {
  std::string name;
  int legFrame;  // segment index of the leg frame this leg hangs from
  int upper, lower, foot;
  double kneeBend;  // +1: the knee points forward (human, quadruped hind leg points back: -1)
  int tarsus = -1;  // the third segment, between lower and foot; -1: a leg of two segments

  // The segment the foot hangs from (the ankle's parent).
  int aboveAnkle() const { return tarsus >= 0 ? tarsus : lower; }
  // The leg's segments from the hip down, and how many (3 or 4).
  int segments(int out[4]) const {
    int n = 0;
    out[n++] = upper;
    out[n++] = lower;
    if (tarsus >= 0) out[n++] = tarsus;
    out[n++] = foot;
    return n;
  }
};

// The most links a spine section between two leg frames may have (creature files, body/creature.h).
constexpr int kMaxSpineLinks = 8;

struct Morphology {
  std::string name;
  std::vector<Segment> segments;
  std::vector<int> legFrames;  // segment indices; [0] is the root. Quadruped: {front, back}
  std::vector<Leg> legs;
  std::vector<int> spine;  // segment indices from legFrames[0] towards legFrames[1]
  // Joint armature (kg·m²): the least principal moment of inertia any segment is simulated with.
  // The controller's PD torques are explicit and held for a 1/120 s control step, which is stable
  // only while k_d·dt/I < ~1 and √(k_p/I)·dt < ~1; a 1 kg foot (I ≈ 0.005) would need ankle gains
  // far too weak to hold the body up. Adding rotor-like inertia to light segments is what robotics
  // simulators call armature (MuJoCo's `armature`); its effect on the motion is measured in
  // docs/controller-notes.md.
  double armature = 0;

  double totalMass() const;
  double standingHeight() const;  // rest-pose height of legFrames[0]'s centre
  // The thesis's fall criterion is on the leg frame; ours: below half standing height.
};

// The shipped characters, built from their creature files (public/creatures/, body/creature.h).
Morphology makeBiped();
Morphology makeQuadruped();
// Any shipped creature file by name ("insect", "spider", "dragon", ...): built from the text
// embedded at build time (body/creature.h, shippedCreatureText).
Morphology shippedCreature(const std::string& name);

}  // namespace gaitlab::body
