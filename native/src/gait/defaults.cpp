#include "gait/defaults.h"

namespace gaitlab::gait {

namespace {

LegFrameParams bipedLegFrame() {
  LegFrameParams p;
  p.pitch = MotionGraph::constant(0.05);
  p.roll = MotionGraph::constant(0);
  p.yaw = MotionGraph::constant(0);
  p.heightOffset = MotionGraph::constant(-0.03);
  p.footTrackingGain = MotionGraph::of(100, 100, 100, 100);
  p.stepHeight = MotionGraph::of(0, 0.08, 0.05, 0);
  p.swingEase = MotionGraph::of(0, 1.0 / 3, 2.0 / 3, 1);
  p.heightKp = 2000;
  p.heightKd = 200;
  p.velocityGain = 100;
  p.footPlacementScale = 0.2;
  p.stepSideways = 0.09;
  p.stepForward = 0.05;
  p.toeOffAngle = 0.2;
  p.strikeAngle = -0.1;
  p.orientationKp = 800;
  p.orientationKd = 40;
  return p;
}

LegFrameParams quadrupedLegFrame() {
  LegFrameParams p;
  p.pitch = MotionGraph::constant(0);
  p.roll = MotionGraph::constant(0);
  p.yaw = MotionGraph::constant(0);
  p.heightOffset = MotionGraph::constant(-0.02);
  p.footTrackingGain = MotionGraph::of(40, 40, 40, 40);
  p.stepHeight = MotionGraph::of(0, 0.05, 0.03, 0);
  p.swingEase = MotionGraph::of(0, 1.0 / 3, 2.0 / 3, 1);
  p.heightKp = 500;
  p.heightKd = 50;
  p.velocityGain = 60;
  p.footPlacementScale = 0.15;
  p.stepSideways = 0.09;
  p.stepForward = 0.0;
  p.toeOffAngle = 0.0;
  p.strikeAngle = 0.0;
  p.orientationKp = 150;
  p.orientationKd = 6;
  return p;
}

}  // namespace

GaitParams defaultParams(const body::Morphology& m) {
  GaitParams g;
  if (m.legs.size() == 2) {
    g.period = 1.0;
    g.maxAcceleration = 1.0;
    g.gains = {300, 10, 300, 6, 8, 0.1, 1000, 10, 0, 0, 0.1, 0.1, 400};
    g.legFrames[0] = bipedLegFrame();
    g.legs[0] = {0.0, 0.6, 0.7, 0.7};
    g.legs[1] = {0.5, 0.6, 0.7, 0.7};
  } else {
    g.period = 0.7;
    g.maxAcceleration = 1.0;
    g.gains = {60, 3, 60, 3, 2, 0.02, 200, 4, 150, 5, 0.1, 0.1, 100};
    g.legFrames[0] = quadrupedLegFrame();
    g.legFrames[1] = quadrupedLegFrame();
    // Trot pairing (REFERENCE.md): FL with BR, FR with BL.
    g.legs[0] = {0.0, 0.6, 0.7, 0.7};
    g.legs[1] = {0.5, 0.6, 0.7, 0.7};
    g.legs[2] = {0.5, 0.6, 0.7, 0.7};
    g.legs[3] = {0.0, 0.6, 0.7, 0.7};
  }
  return g;
}

}  // namespace gaitlab::gait
