// The parameters of one character's gait (thesis §3.3: per controller, per leg frame, per leg).
// The schema that names, bounds and documents every field lives in gait/schema.h; this is the
// plain data the controller reads each step.
#pragma once
#include "gait/graph.h"

namespace gaitlab::gait {

// The most leg frames and legs a body may have (creature files, body/creature.h: up to four pairs
// of legs, each pair on its own leg frame). The gait schema names the biped's one leg frame and the
// quadruped's two (gait/schema.h).
constexpr int kMaxLegFrames = 4;
constexpr int kMaxLegs = 8;

struct LegFrameParams {
  // Motion graphs over the gait phase Φ (§3.1.3): the leg frame's desired orientation in the
  // heading frame (radians) and its height above its standing height (metres).
  MotionGraph pitch, roll, yaw, heightOffset;
  // Over swing progress ϕ (§3.1.4, §3.1.6): foot-tracking gain k_ft (N/m), step height h_sw (m),
  // swing easing t_sw (fraction of the way from lift-off to strike point).
  MotionGraph footTrackingGain, stepHeight, swingEase;
  double heightKp = 0, heightKd = 0;  // F_h PD gains (N/m, N·s/m)
  double velocityGain = 0;            // K_v of F_v = K_v (v_d − v) (eq. 3.6), N·s/m
  double fd[4] = {0, 0, 0, 0};        // c0..c3 of F_D(D) (eq. 3.8)
  double footPlacementScale = 0;      // s of P1 = P_lf + (v − v_d)·s (§3.1.6), seconds
  double footPlacementLead = 0;       // s: the nominal offset grows by v_d × this
  double stepSideways = 0;            // nominal foot offset from the leg frame's centre, m
  double stepForward = 0;             // m
  // Inverted-pendulum foot placement at low speed (Coros et al. 2010; beyond the thesis): the
  // strike point moves towards the capture point x + v·√(h/g) of the centre of mass, plus
  // captureSideways to the leg's side, by capturePlacement × (1 − |v_d| / captureBlendSpeed).
  double capturePlacement = 0;        // weight at v_d = 0, 0 = the thesis's placement only
  double captureBlendSpeed = 0.5;     // m/s: from this desired speed up, the thesis's only
  double captureSideways = 0.05;      // m
  double toeOffAngle = 0;             // foot pitch at lift-off, rad (+ = toes down)
  double strikeAngle = 0;             // foot pitch at strike, rad (− = toes up)
  double orientationKp = 0, orientationKd = 0;  // leg-frame orientation PD (§3.1.3)
};

struct LegParams {
  double stepTrigger = 0;  // gait phase of lift-off (§3.1.1)
  double dutyFactor = 0;   // fraction of the cycle in stance
  double toeOffTime = 0;   // stance progress after which the foot pitches to toeOffAngle
  double strikeTime = 0;   // swing progress after which the foot pitches to strikeAngle
};

// Joint PD gains (§3.1.7) and limits shared by all legs of a character.
struct JointGains {
  double hipKp = 0, hipKd = 0;
  double kneeKp = 0, kneeKd = 0;
  double ankleKp = 0, ankleKd = 0;          // swing foot, world frame (§3.1.6)
  double stanceAnkleKp = 0, stanceAnkleKd = 0;  // stance foot relative to its shin (§3.1.7)
  double spineKp = 0, spineKd = 0;
  double stanceKneeFlexion = 0;  // rad, the stance knee's PD target
  // Share of the hip torque kept about the thigh's long axis. A limb's inertia about its own
  // axis is ~20× smaller than about the hip, so at 120 Hz the gains that hold the thigh's swing
  // would make its twist unstable (explicit PD: k_d·dt/I must stay below ~1).
  double hipTwistScale = 1;
  // Share of the swing IK targets' rate that the swing hip and knee PDs track (0: the thesis's
  // PD towards a position only, which lags a moving target by k_d/k_p; 1: the target's velocity
  // too). Controller::swingLeg.
  double swingTargetRate = 0;
  double maxTorque = 0;          // N·m, clamp per joint
};

// maxTurnSlip at or above this bounds nothing: no character is given a goal faster than 5 m/s.
constexpr double kNoTurnSlipBound = 5.0;
// hipForwardStop at this holds nothing: no hip swings a thigh forwards by π.
constexpr double kNoHipForwardStop = 3.14159265358979323846;

struct GaitParams {
  double period = 1;        // T, seconds (§3.1.1)
  double maxAcceleration = 1;  // m/s², bound on the desired-velocity ramp (§3.1.6)
  // Speed tracking (beyond the thesis): the velocity F_v (eq. 3.6) aims at is v_d plus the
  // integral of the speed error (v_d − v, bounded to ±0.15 m/s: kMaxTrimError, controller.cpp)
  // at this rate, 1/s; 0 = F_v towards v_d as in the thesis.
  double speedIntegralGain = 0;
  // And a proportional term on the speed error averaged over about a stride (kSpeedMeanWindow):
  // F_v aims at v_d plus this gain times that mean error (bounded), so a walk that runs 10 % fast
  // for a second is pulled back within the second, while the error within one stride (the
  // velocity's own swing, a push) moves it little. 0 = no such term (schemas before 5).
  double speedProportionalGain = 0;
  // Standing (gait/standing.cpp, beyond the thesis): once the goal is 0 and the centre of mass
  // has moved slower than this (m/s) for half a second, the character stands on planted feet,
  // stepping only to recover; 0 = it steps in place at goal 0 (schemas before 6).
  double standSpeed = 0;
  // Speed tracking's bound on the integral trim (m/s): |trim| ≤ this (schemas before 7 had 0.5
  // for every gait). The quadruped's canter lags its goal by 0.75–1 m/s with 0.5 and needs more;
  // a trim of 1.0 unsettled it (docs/controller-notes.md §42).
  double maxSpeedTrim = 0.5;
  // Speed tracking acts from this desired speed up (m/s); below it the trim fades and the
  // low-speed capture-point placement governs (schemas before 8 had 0.15 for every gait).
  // Standing (v_d = 0) is always below it. The biped's walk with double support steps at about
  // 0.45 m/s unless the trim slows it, and needs it down to 0.05 (docs/controller-notes.md §48).
  double speedTrackedFrom = 0.15;
  // Turning (beyond the thesis): while the goal turns, its heading is held at most
  // asin(maxTurnSlip / v) ahead of the direction the centre of mass travels at speed v, so the
  // body slides sideways past its own heading at most this fast (m/s). A body told to turn yaws
  // at once but its velocity turns only as fast as its stance feet can push it round; the canter,
  // mostly on one foot, could not, and slid out of the turn until it rolled over
  // (docs/controller-notes.md §59). kNoTurnSlipBound (schemas before 10): no bound.
  double maxTurnSlip = kNoTurnSlipBound;
  // Turning (beyond the thesis): the strike points move outwards from the turn by
  // turnPlacement · h v ω / g, where h is the centre of mass's height, v its speed and ω the goal's
  // turn rate. On its stance foot the body is an inverted pendulum: the ground force that turns
  // it (centripetal, m v ω) without a moment about the centre of mass passes through it, so the
  // foot lies h v ω / g outside it (1 is that lean exactly). Feet landing under the body could
  // push it round only by rolling it, and the whole-body stance (stance_forces.h) gave that force
  // up to the roll: the canter turned at a third of its goal (docs/controller-notes.md §60).
  // 0 (schemas before 11): feet placed as if going straight.
  double turnPlacement = 0.0;
  // Turning, bodies of several leg frames (beyond the thesis): the whole-body stance's wanted
  // torque (stance_forces.h) takes on turnRollMoment times m v ω h about the heading's forward
  // axis, the roll moment the turn's sideways ground force (m v ω, towards the turn's centre)
  // exerts about the centre of mass from the ground, h below it. Asked for none, the stance
  // cancels that moment with the feet's vertical forces, which a canter on one or two feet near
  // the midline cannot: it gave up sideways force instead, and turned at 0.23 rad/s when told
  // 0.3 at 3.5 m/s (docs/controller-notes.md §77). 0 (schemas before 12): cancelled. Not in the
  // schema of bodies of one leg frame (from 13), whose stance has no such fit.
  double turnRollMoment = 0.0;
  // The gait's forward stop at the hip, bodies of one leg frame (beyond the thesis): while it
  // walks or stands, the hip joint stops a thigh swinging forwards of the leg frame's down axis
  // beyond this (rad), a limit of the joint as stiff as the body's own (sim::Agent sets it,
  // physics::Character::setHipForwardStop; a get-up releases it). The biped's gaits were searched
  // on a hip that stopped at 0.7 rad and press their swing thighs onto that stop; its body now
  // flexes 2 rad, as a person's does, so that getting up can fold it, and the gaits keep their
  // stop here (docs/controller-notes.md §76, §78). Files before 14 were all tuned on it and read
  // 0.7. kNoHipForwardStop: none.
  double hipForwardStop = kNoHipForwardStop;
  // Where in this key's gait cycle a change to another footfall pattern is taken up: the gait
  // phase Φ, in cycles (gait/gait_transition.h; 1 is 0 again). 0 is where the cycle starts, the
  // one place every change was taken in schemas before 9. The quadruped's canter falls in the
  // trot after it far less often when it is left just after its leading front foot lifts off,
  // with only the hind foot that leads the canter down (0.45; docs/controller-notes.md §52).
  double transitionPhase = 0;
  JointGains gains;
  LegFrameParams legFrames[kMaxLegFrames];
  LegParams legs[kMaxLegs];
};

}  // namespace gaitlab::gait
