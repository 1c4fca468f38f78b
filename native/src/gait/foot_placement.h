// Foot placement and the stance-leg forces that depend on velocity and foot progress
// (thesis §3.1.4 eq. 3.6–3.8, §3.1.6).
//
// Frames: "heading" vectors are in the character's heading frame (heading.h: +z forward, +x left,
// +y up); positions without that word are world. Velocities entering the feedback must be true
// velocities in m/s (defect 1 of the original implementation, docs/original-implementation.md: the original never divided by dt).
#pragma once
#include <Eigen/Dense>

#include "gait/graph.h"

namespace gaitlab::gait {

// §3.1.6: the desired velocity v_d moves towards the user's goal velocity by at most
// maxAccel·dt per step (a bound on the norm of the change, so a diagonal change is not faster
// than a straight one). Frame-agnostic; the controller keeps v_d in the heading frame so that a
// desired forward speed stays forward while the character turns.
Eigen::Vector3d rampDesiredVelocity(const Eigen::Vector3d& desired, const Eigen::Vector3d& goal,
                                    double maxAccel, double dt);

// Nominal foot position relative to the leg frame, heading frame, from the step-length
// parameters: `side` = +1 for a leg on the character's left (+x), −1 on its right.
inline Eigen::Vector3d nominalFootOffset(double side, double stepSideways, double stepForward) {
  return Eigen::Vector3d(side * stepSideways, 0.0, stepForward);
}

// §3.1.6: P1 = P_legframe + (v − v_d)·s. P_legframe = the leg frame's position plus the nominal
// foot offset (heading frame), on the ground: P1.y = groundY (the ground height under the target,
// supplied by the caller, never assumed 0: defect 7). Only the horizontal parts of the velocities
// count. Moving faster than desired puts the foot further ahead, which brakes (and vice versa).
Eigen::Vector3d footPlacementTarget(const Eigen::Vector3d& legFramePos, double yaw,
                                    const Eigen::Vector3d& nominalOffsetHeading,
                                    const Eigen::Vector3d& velocityHeading,
                                    const Eigen::Vector3d& desiredVelocityHeading, double scale,
                                    double groundY);

// §3.1.6 swing trajectory from the lift-off position p0 to the placement target p1 at swing
// progress ϕ: horizontally the fraction t_sw(ϕ) of the way, vertically the ground line between
// p0.y and p1.y (same fraction) plus the step height h_sw(ϕ), minus the late-strike offset
// (gait_player.h: the target sinks while a late foot searches for the ground). The controller
// re-evaluates it every step with the current p1 (defect 8: the original froze it at lift-off).
// With t_sw(0) = 0, t_sw(1) = 1 and h_sw(0) = h_sw(1) = 0 the path runs from p0 to p1.
Eigen::Vector3d swingFootTarget(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, double phi,
                                const MotionGraph& tSw, const MotionGraph& hSw,
                                double lateStrikeOffset = 0.0);

// Eq. 3.6: F_v = K_v (v_d − v), horizontal only (height is F_h's job). Any frame with +y up.
inline Eigen::Vector3d velocityForce(double kv, const Eigen::Vector3d& desiredVelocity,
                                     const Eigen::Vector3d& velocity) {
  Eigen::Vector3d f = kv * (desiredVelocity - velocity);
  f.y() = 0.0;
  return f;
}

// Eq. 3.7: D, the forward progress of the foot in the leg frame's reference: the displacement
// leg frame → foot projected on the ground plane, signed along the heading's forward axis
// (positive while the foot is ahead of the leg frame: at touch-down; negative behind: at
// lift-off). We take the forward component rather than |P_legframe − P_foot|: the magnitude
// never drops below the hip's sideways offset and has no sign, so F_D could not tell the start
// of stance from its end.
double footProgress(const Eigen::Vector3d& legFramePos, const Eigen::Vector3d& footPos, double yaw);

struct PhaseForceCoefficients {
  double c0 = 0.0, c1 = 0.0;  // vertical:   c0 + c1·D
  double c2 = 0.0, c3 = 0.0;  // horizontal: c2 + c3·D, along the heading's forward axis
};

// Eq. 3.8: F_D(D), world. Like F_h and F_v it is the force wanted ON THE LEG FRAME; the
// controller applies its opposite at the stance foot with the leg frame as base (§3.1.4).
Eigen::Vector3d phaseForce(const PhaseForceCoefficients& c, double D, double yaw);

// §3.1.4: the swing-foot virtual force F_sw, a PD with proportional gain k_ft(ϕ) (a graph) and
// derivative gain 10 % of it, driving the foot towards its target. World. (Defect 2: the
// original's F_sw was always zero.)
inline Eigen::Vector3d swingFootForce(double kft, const Eigen::Vector3d& footPos,
                                      const Eigen::Vector3d& footVel,
                                      const Eigen::Vector3d& target,
                                      const Eigen::Vector3d& targetVel = Eigen::Vector3d::Zero()) {
  return kft * (target - footPos) + 0.1 * kft * (targetVel - footVel);
}

}  // namespace gaitlab::gait
