// Getting up on two legs (gait/get_up_two_legs.cpp): the routines of keyframes a body on one leg
// frame with one pair of legs (the biped) gets up by, one for each way it can lie.
#pragma once

namespace gaitlab::gait {

// One keyframe: every leg joint held at a pose by a PD (pd.h) for `seconds`. Per leg, [0] is the
// left leg's, or, in a routine named by sides (GetUpRoutine::bySide), the leg nearer the ground.
struct GetUpKey {
  double seconds;   // held for
  double gain;      // the PDs' stiffness times this, their damping times its square root
  double hip[2];    // the hip's flexion (forwards positive), rad
  double knee[2];   // the knee's flexion, rad
  double ankle[2];  // the foot's rotation about the shin's x axis, rad (toes down positive)
  double twist[2];  // the hip's twist about the thigh, rad (mirrored between the legs)
  double outwards[2];  // the hip's sideways swing away from the body, rad
};

struct GetUpRoutine {
  const GetUpKey* keys = nullptr;
  int count = 0;
  bool bySide = false;  // legs named by the side nearer the ground, not left and right
};

// How a fallen body lies: what picks the routine.
enum class Lying { OnBack, OnFront, OnSide };

// The routines the biped was tuned with (gait/get_up_two_legs.cpp): from its back a kip-up onto
// its feet; from its front (or face down, hips raised) or a side a roll onto its back.
GetUpRoutine defaultGetUpRoutine(Lying lying);

}  // namespace gaitlab::gait
