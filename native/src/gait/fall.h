// The fall test of the walking criteria, on one leg frame: sunk below half its standing height
// above the ground, or tipped more than 60° from upright. The walking trials judge a fall with it
// (sim/walk_trial.h, hasFallen) and the controller notices one with it to get up
// (gait/get_up.cpp), so that the two never disagree about what a fall is.
#pragma once
#include <Eigen/Geometry>
#include <cmath>

#include "body/morphology.h"

namespace gaitlab::gait {

inline bool legFrameFallen(const body::Segment& legFrame, const Eigen::Vector3d& position,
                           const Eigen::Quaterniond& orientation, double groundHeight) {
  if (position.y() - groundHeight < 0.5 * legFrame.center.y()) return true;
  const double cos60 = 0.5;
  return (orientation * Eigen::Vector3d::UnitY()).y() < cos60;
}

}  // namespace gaitlab::gait
