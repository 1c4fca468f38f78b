// A morphology (body/morphology.h) as JSON, for another engine to build the same ragdoll: the
// peer benchmark's reference scene (peers/reference_scene.h) made in Jolt Physics by
// bench/peers/jolt-scene.mjs. Everything in the character frame of the rest pose (y up, +z
// forward, feet on y = 0), SI units:
//
//   {"name", "armature", "segments": [{"name", "halfExtents", "mass", "center", "parent",
//    "motor": {"kp", "kd"}, "joint": {"type": "root|hinge|universal|ball", "pivot",
//    "axes": [[x,y,z] ... one per degree of freedom], "lower": [...], "upper": [...]}}]}
//
// "motor" is the segment's joint motor (peers/reference_scene.h holdingMotors), zero for the root.
#pragma once
#include <string>

#include "gait/schema.h"

namespace gaitlab::peers {

std::string morphologyJson(gait::Character character);

}  // namespace gaitlab::peers
