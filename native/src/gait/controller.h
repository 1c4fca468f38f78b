// The locomotion controller of one character (thesis §3.1, Algorithm 1): reads the character's
// state, writes one torque per joint. Physics-free: it sees the character only through
// CharacterState, and asks for ground heights through a callback, so it can be tested without
// Bullet and run for many characters in parallel (no heap allocation in update()).
#pragma once
#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "body/morphology.h"
#include "gait/gait_player.h"
#include "gait/get_up_two_legs.h"
#include "gait/ik.h"
#include "gait/params.h"
#include "gait/speed_keys.h"
#include "gait/support_polygon.h"
#include "gait/virtual_force.h"

namespace gaitlab::gait {

struct BodyState {
  Eigen::Vector3d position;  // centre of mass, world
  Eigen::Quaterniond orientation;
  Eigen::Vector3d linearVelocity;   // m/s
  Eigen::Vector3d angularVelocity;  // rad/s
};

// Ground height under a point; the physics side answers it by ray casts against the terrain.
struct GroundQuery {
  double (*height)(const void* context, double x, double z) = nullptr;
  const void* context = nullptr;
  double at(double x, double z) const { return height ? height(context, x, z) : 0.0; }
};

struct CharacterState {
  const BodyState* segments = nullptr;  // morphology order
  const bool* footContact = nullptr;    // per leg, this step
  GroundQuery ground;
};

// What the user asks for (beyond the thesis: steering).
struct Goal {
  double speed = 0;     // m/s, forward in the heading frame (negative walks backwards)
  double turnRate = 0;  // rad/s about +y
};

class Controller {
 public:
  Controller(const body::Morphology& morphology, const GaitParams& params, double heading);

  // The parameters in effect this step: the gait's keys blended at the desired speed.
  const GaitParams& params() const { return params_; }
  // A gait of one key: these parameters at every speed.
  void setParams(const GaitParams& params);
  // The gait: its keys by speed (gait/speed_keys.h), blended at the desired speed from now on.
  const Gait& gait() const { return gait_; }
  void setGait(const Gait& gait);
  void setGoal(const Goal& goal) { goal_ = goal; }
  const Goal& goal() const { return goal_; }

  // One fixed step (Algorithm 1). torques[segment] is the torque of the joint between `segment`
  // and its parent, world frame, exerted on the segment; the physics side applies its opposite
  // to the parent (an equal and opposite pair: defect 3 of the original implementation, docs/original-implementation.md). Root entries are zero.
  void update(double dt, const CharacterState& state, Eigen::Vector3d* torques);

  const GaitPlayer& player() const { return player_; }
  // Restarts the gait at phase Φ (a crowd whose members start out of step).
  void setPhase(double phase) { player_.reset(phase); }
  // Changes of footfall pattern (gait transitions, gait/gait_transition.h) since the spawn.
  int gaitChanges() const { return gaitChanges_; }
  double desiredHeading() const { return desiredHeading_; }
  const Eigen::Vector3d& desiredVelocity() const { return desiredVelocity_; }  // heading frame
  // Speed tracking's integral trim (m/s): how much faster than v_d F_v aims.
  double speedTrim() const { return speedTrim_; }
  // Standing on planted feet (gait/standing.cpp): every foot down, the gait clock stopped.
  bool standing() const { return stand_ == Stand::Planted; }
  // Down after a fall and getting up (gait/get_up.cpp): the gait waits until it is on its feet.
  bool down() const { return stand_ == Stand::Down; }
  // Where the body's hips are to stop a thigh's forward swing (rad; GaitParams::hipForwardStop,
  // set on the physics by physics::Character::setHipForwardStop): the gait's stop, released while
  // it gets up, which folds the legs as far as the body lets them.
  double hipForwardStop() const { return down() ? kNoHipForwardStop : params_.hipForwardStop; }
  // The routine a body on two legs gets up by when it lies so (gait/get_up_two_legs.h; the
  // defaults unless set: the get-up search tries others). The keys must outlive the controller.
  void setGetUpRoutine(Lying lying, const GetUpRoutine& routine) { getUpRoutines_[static_cast<int>(lying)] = routine; }
  const GetUpRoutine& getUpRoutine(Lying lying) const { return getUpRoutines_[static_cast<int>(lying)]; }

 private:
  struct LegGeometry {
    double thigh, shin;          // hip→knee, knee→ankle (three segments: knee→hock) lengths
    double tarsus;               // hock→ankle length; 0 for a leg of two segments
    double ankleHeight;          // ankle pivot above the sole
    double side;                 // +1 left (+x), −1 right
    // The sole around the ankle, in the foot's frame: how far the centre of pressure can move
    // before the foot tips (toe and heel along +z/−z, half the width along x).
    double toe, heel, halfWidth;
    // The joints' limits the get-up's poses press against (gait/get_up.cpp): the hip's swing that
    // folds the foot over the back (signed as the knee bends), the hip's sideways swing either
    // way, and the knee's flexion.
    double hipFold, hipSideways, kneeFlexion;
  };

  // `load`: the weight this stance leg carries (N), for the support limit of its ankle.
  // `supported`: the force is this foot's ground force in the whole-body stance (bodyStance).
  void stanceLeg(int leg, const CharacterState& s, double yaw, const Eigen::Vector3d& force,
                 double load, bool supported, Eigen::Vector3d* torques);
  // `dt`: the step, for the swing targets' rates (swingTargetRate).
  void swingLeg(int leg, const CharacterState& s, double dt, double yaw,
                const Eigen::Vector3d& velocity, Eigen::Vector3d* torques);
  int legFrameIndex(const body::Leg& leg) const;  // its leg frame's place in m_.legFrames, front first
  Eigen::Vector3d jointPivot(int segment, const CharacterState& s) const;  // world, now
  DofChain legChain(int leg, const CharacterState& s) const;
  // The leg's inverse kinematics for an ankle target (solveLegIk), its knee bent the way it points.
  LegIk legIk(int leg, const Eigen::Vector3d& hip, const Eigen::Vector3d& ankle, const Eigen::Vector3d& forward) const;
  // The knee's PD, and a three-segment leg's hock's, which follows the knee.
  void kneePd(int leg, const CharacterState& s, double flexionWanted, Eigen::Vector3d* torques,
              double rateWanted = 0.0);
  // A knee or hock now: the child's rotation about the parent's x axis, signed by `bend` so that
  // bending the way the joint bends is positive.
  struct Hinge {
    int child;
    double bend;
    Eigen::Vector3d axis;  // world
    double flexion, rate;
  };
  Hinge hinge(int parent, int child, double bend, const CharacterState& s) const;
  void hingePd(const Hinge& h, double flexionWanted, double rateWanted, Eigen::Vector3d* torques) const;
  void footPd(int leg, const CharacterState& s, double yaw, double pitch, double kp, double kd,
              Eigen::Vector3d* torques);
  void limitToSupport(int leg, const CharacterState& s, double load, Eigen::Vector3d* torques) const;
  void spine(const CharacterState& s, Eigen::Vector3d* torques);
  // Characters with more than one leg frame: stance forces for the whole body (stance_forces.h).
  void bodyStance(const CharacterState& s, double yaw, const Eigen::Vector3d& com,
                  const Eigen::Vector3d& comVelocity, double phase, Eigen::Vector3d* torques);
  // maxTurnSlip (params.h): holds the goal heading at most asin(maxTurnSlip / v) ahead of the
  // path of the centre of mass while the goal turns.
  void boundTurnLead(const Eigen::Vector3d& comVelocity);
  // Leg frame f's orientation PD (eq. 3.4) and height force F_h (§3.1.4), world.
  Eigen::Vector3d frameOrientationPd(int f, const CharacterState& s, double phase) const;
  Eigen::Vector3d heightForce(int f, const CharacterState& s, double phase) const;
  // Height of the centre of mass above the ground under it (m, at least 0.1): the inverted
  // pendulum's length in the capture-point and turn placements.
  double comHeight(const CharacterState& s) const;
  // Standing on planted feet (gait/standing.cpp, beyond the thesis). Walking → Settling (goal 0
  // and slow: the gait player holds every foot that lands) → Planted (every foot down: the
  // body held in a pose over its feet) → Walking (the goal moves, or the capture point leaves
  // the support polygon: a step is the only way to catch the body).
  // Down (gait/get_up.cpp): fallen, rolling and rising onto its feet, then Settling.
  enum class Stand { Walking, Settling, Planted, Down };
  void updateStand(const CharacterState& s, const Eigen::Vector3d& comVelocity);
  void release(const CharacterState& s, int leg);  // stepping again, `leg` first
  // A body on several leg frames stands as a table (plantedTable), one on a single leg frame
  // balances on its ankles (plantedStance).
  bool standsAsTable() const { return m_.legFrames.size() > 1; }
  void plantedStance(const CharacterState& s, Eigen::Vector3d* torques);
  void plantedTable(const CharacterState& s, Eigen::Vector3d* torques);
  // The body's weight as one ground force per foot (every foot, at its sole: points, forces),
  // by the whole-body least squares (stance_forces.h); returns the number of feet.
  int shareWeight(const CharacterState& s, Eigen::Vector3d* points, Eigen::Vector3d* forces) const;
  SupportPolygon supportPolygon(const CharacterState& s) const;  // of the stance feet's soles
  // Getting up after a fall (gait/get_up.cpp). isDown: the walking criteria's fall test
  // (gait/fall.h) on every leg frame. getsUp notes a fall and, while down, writes the get-up's
  // torques (getUp, or getUpOnTwoLegs) and returns true.
  bool isDown(const CharacterState& s) const;
  bool getsUp(const CharacterState& s, double dt, Eigen::Vector3d* torques);
  void getUp(const CharacterState& s, double dt, Eigen::Vector3d* torques);
  // A body on one leg frame with two legs (gait/get_up_two_legs.cpp): rolls onto its back, kips up.
  void getUpOnTwoLegs(const CharacterState& s, double dt, Eigen::Vector3d* torques);
  // A joint PD (pd.h, jointPd) holding `segment` at `relative` to its parent, added to its torque.
  void jointHold(int segment, const CharacterState& s, const Eigen::Quaterniond& relative, double kp,
                 double kd, Eigen::Vector3d* torques) const;
  // Swing-hip twist scaling and the torque limit, last in every update.
  void finishTorques(const CharacterState& s, Eigen::Vector3d* torques) const;
  void clampTorques(Eigen::Vector3d* torques) const;  // each joint's to maxTorque

  // params_ from the gait's keys at |v_d|, and the gait player's period and schedule from them;
  // with `restart` (a gait set before the first step) the player starts again from the schedule,
  // at the phase it has. Once walking, a change of footfall pattern waits for the gait phase to
  // reach the current key's transitionPhase: until then the parameters stay as they are and the
  // change is pending (update() takes it up there, `atTransitionPhase`).
  void blendAt(double speed, bool restart = false, bool atTransitionPhase = false);

  const body::Morphology& m_;
  Character character_;
  Gait gait_;
  GaitParams params_;
  double blendedAt_ = 0;  // the |v_d| params_ was blended at (m/s)
  int gaitChanges_ = 0;
  bool transitionPending_ = false;  // a change of footfall pattern waits for transitionPhase
  Goal goal_;
  GaitPlayer player_;
  std::vector<LegGeometry> geometry_;
  std::vector<Eigen::Vector3d> liftOff_;  // per leg: foot position at lift-off (P0)
  bool started_ = false;                  // liftOff_ set from the feet on the first update
  // Per swing leg: last step's IK targets, to track the swing trajectory's velocity too.
  struct SwingTargets {
    Eigen::Quaterniond thigh = Eigen::Quaterniond::Identity();
    double knee = 0;
    bool valid = false;  // false on the first step of a swing
  };
  std::vector<SwingTargets> swingTargets_;
  double desiredHeading_;
  Eigen::Vector3d desiredVelocity_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d gravity_{0, -9.81, 0};
  double weight_ = 0;  // N, the whole character's
  Eigen::Vector3d com_ = Eigen::Vector3d::Zero();  // centre of mass this step (swing placement)
  double forwardSpeed_ = 0;  // m/s, the centre of mass's forward speed this step (heading frame)
  double speedTrim_ = 0;  // m/s, speed tracking's correction of v_d in F_v (speedIntegralGain)
  double meanSpeedError_ = 0;   // m/s, v_d − v averaged over about a stride (speedProportionalGain)
  double speedCorrection_ = 0;  // m/s, the proportional term's correction of v_d in F_v
  // Standing: the spot held (world), whether one is, the hold's integral term (world) and the
  // velocity towards the spot (heading frame).
  Eigen::Vector3d anchor_ = Eigen::Vector3d::Zero();
  bool anchored_ = false;
  Eigen::Vector3d holdIntegral_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d hold_ = Eigen::Vector3d::Zero();
  Stand stand_ = Stand::Walking;
  int lifted_ = 0;        // steps in a row a planted foot has been off the ground
  int calm_ = 0;          // steps in a row it has been slow enough to come to a stand
  // Getting up (gait/get_up.cpp): steps in a row it has been fallen while walking; each leg frame
  // rolled up; steps since every one was; steps in a row it has stood straightened on its feet.
  int downSteps_ = 0;
  bool frameUp_[kMaxLegFrames] = {};
  int risenSteps_ = 0;
  int onFeetSteps_ = 0;
  // Getting up on two legs: the way it lies whose routine is running (none: waiting to lie still),
  // the routine's steps, and the stillness test's clock and the torso's axes at its last sample.
  GetUpRoutine getUpRoutines_[3] = {defaultGetUpRoutine(Lying::OnBack), defaultGetUpRoutine(Lying::OnFront),
                                    defaultGetUpRoutine(Lying::OnSide)};
  std::optional<Lying> lying_;
  int routineSteps_ = 0;
  int stillSteps_ = 0;
  Eigen::Vector3d stillForward_ = Eigen::Vector3d::Zero(), stillUp_ = Eigen::Vector3d::Zero();
  double standYaw_ = 0;  // the heading it stands facing (set as it comes to a stand)
  // Per segment: a leg joint's orientation relative to its parent as it came to a stand (the
  // table's pose; identity for the other segments).
  std::vector<Eigen::Quaterniond> standPose_;
  double standHeight_[kMaxLegFrames] = {};  // m, each leg frame above the ground as it came to a stand
  Eigen::Vector3d trimmedVelocity() const {
    return desiredVelocity_ + hold_ + Eigen::Vector3d(0, 0, speedTrim_ + speedCorrection_);
  }
};

}  // namespace gaitlab::gait
