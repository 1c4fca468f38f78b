// Two-link inverse kinematics by the law of cosines (thesis §3.1.4): the virtual forces do not
// place the knee, so the knee position is solved from the hip and the foot target, and joint
// PD controllers then drive the leg towards it.
#pragma once
#include <Eigen/Dense>

namespace gaitlab::gait {

struct TwoLinkIk {
  Eigen::Vector3d knee;      // knee position, world
  Eigen::Vector3d foot;      // where the shin ends: the target if reachable, else the closest point
  Eigen::Vector3d thighDir;  // unit, hip → knee
  Eigen::Vector3d shinDir;   // unit, knee → foot
  double kneeAngle;          // interior angle hip–knee–foot: π = straight leg, 0 = fully folded
  double kneeFlexion;        // π − kneeAngle: 0 = straight (the joint angle a PD usually tracks)
  bool reachable;            // |l1 − l2| ≤ |target − hip| ≤ l1 + l2
};

// Solves the leg hip → knee → foot for a foot target. The knee is placed on the side of the
// hip→target line that `bendDir` points to (bipeds: the knee points forward, bendDir = heading
// forward; quadruped legs whose knee points backwards: bendDir = −forward). Only the part of
// bendDir perpendicular to hip→target matters; if none is left, a fixed perpendicular is used.
// Out of reach (> l1 + l2): the leg is straight, pointing at the target. Closer than |l1 − l2|:
// fully folded. Every output is finite for any finite-length input, including target == hip,
// zero lengths and a zero bendDir; a non-finite target is treated as the hip.
TwoLinkIk solveTwoLinkIk(const Eigen::Vector3d& hip, const Eigen::Vector3d& target, double thigh,
                         double shin, const Eigen::Vector3d& bendDir);

// A leg of two or three segments (body::Leg): hip → knee → [hock →] ankle. The two-link solution
// of the chain (for three segments its knee and foot are the virtual chain's, thigh + tarsus long),
// and the direction of the segment the foot hangs from.
struct LegIk : TwoLinkIk {
  Eigen::Vector3d ankleLimb;  // unit: the shin's (two segments) or the tarsus's (= thighDir)
};

// Solves a leg for an ankle target. Two segments (tarsus = 0): solveTwoLinkIk, bit for bit. Three:
// as a pantograph, the tarsus held parallel to the thigh, as the pantograph legs of Cheetah-cub
// (Sprowitz et al. 2013) hold their lowest segment and a trotting dog's hind leg nearly does; the
// hock then bends the other way by the knee's flexion, and hip → ankle is thigh·u + shin·v +
// tarsus·u = (thigh + tarsus)·u + shin·v: the two-link leg of lengths thigh + tarsus and shin,
// solved by the law of cosines. One redundant joint, resolved by one rule, with the same knee
// targets and gains as a two-segment leg.
LegIk solveLegIk(const Eigen::Vector3d& hip, const Eigen::Vector3d& target, double thigh, double shin,
                 double tarsus, const Eigen::Vector3d& bendDir);

// Orientation whose −y axis points along `down` (a limb hanging from its joint, as every leg
// segment does at rest) and whose +z axis is as close as possible to `forward`: the desired
// orientation of a thigh or shin from the IK's directions.
Eigen::Quaterniond limbOrientation(const Eigen::Vector3d& down, const Eigen::Vector3d& forward);

}  // namespace gaitlab::gait
