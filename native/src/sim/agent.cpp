#include "sim/agent.h"

#include "gait/defaults.h"

namespace gaitlab::sim {

Agent::Agent(physics::World& w, const body::Morphology& m, const Eigen::Vector3d& origin,
             double heading)
    : body(std::make_unique<physics::Character>(w, m, origin, heading)),
      controller(m, gait::defaultParams(m), heading),  // then the preset's whole gait, below
      state(m.segments.size()),
      torques(m.segments.size(), Eigen::Vector3d::Zero()),
      world(&w) {
  for (size_t l = 0; l < m.legs.size(); ++l) body->setFootContactFlag(static_cast<int>(l), &footContact[l]);
  lastGood = body->segmentState(m.legFrames[0]).position;
  lastGoodHeading = heading;
  controller.setGait(gait::defaultGait(gait::characterOf(m)));
  body->setHipForwardStop(hipStop = controller.hipForwardStop());  // before the first step
}

void Agent::control() {
  if (broken) {  // a state that is not finite gives no torques worth applying
    ++updates;
    return;
  }
  body->readState(state.data());
  gait::CharacterState cs;
  cs.segments = state.data();
  cs.footContact = footContact;
  cs.ground.context = world;
  cs.ground.height = [](const void* w, double x, double z) {
    return static_cast<const physics::World*>(w)->terrainHeight(x, z);
  };
  controller.update(physics::kFixedStep, cs, torques.data());
  body->applyJointTorques(torques.data());
  if (controller.standing() != feetHeld) body->holdFeet(feetHeld = controller.standing());
  const double stop = controller.hipForwardStop();
  if (stop != hipStop) body->setHipForwardStop(hipStop = stop);
  ++updates;
}

}  // namespace gaitlab::sim
