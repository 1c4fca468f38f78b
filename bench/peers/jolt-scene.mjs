// The peer benchmark's reference scene (native/src/peers/reference_scene.h) built in Jolt Physics
// (Rouwé 2022; the `jolt-physics` npm package, JoltPhysics.js): the same ragdolls from the same
// morphology JSON (gl_morphology_json), the same grid, step and collision rules.
//
// How each part maps:
//  - segments: dynamic boxes of the same half extents and mass; gaitlab raises every principal
//    moment of inertia to the morphology's armature (body/morphology.h), so the inertia is given
//    explicitly, as the solid box Jolt computes the same diagonal for (sGetEquivalentSolidBoxSize);
//  - joints: gaitlab's 1-DOF joints are Bullet hinges, so here HingeConstraint; its 2- and 3-DOF
//    joints are Bullet 6-DOF constraints with locked translation, so here SixDOFConstraint with
//    the translation fixed and each rotation axis limited as gaitlab limits it (a 2-DOF joint's
//    third axis fixed);
//  - motors: position motors towards the rest pose (the identity relative rotation) whose springs
//    have the same stiffness and damping as gaitlab's explicit PD torques (the preset's joint
//    gains, "motor" in the JSON); Jolt solves them implicitly, inside its constraint solver;
//  - collision: two object layers, ground and characters, with character-character pairs off:
//    characters touch the ground only, as in gaitlab's worlds (physics/world.h);
//  - time: Step(1/120, 2), two collision and integration sub-steps of 1/240 s per fixed step.
//
// The solver iteration counts are Jolt's defaults (10 velocity, 2 position steps); gaitlab uses
// Bullet's 10 sequential-impulse iterations (physics/world.h).
//
// The ragdolls never sleep, as gaitlab's characters never do (physics/world.cpp disables Bullet's
// deactivation): with Jolt's default (sleep after 0.5 s below 0.03 m/s) the standing quadrupeds
// all fell asleep about 1.05 s into the scene, inside the benchmark's timed window, and every
// step after that cost Jolt nothing.
//
// `physicsSettings` overrides fields of Jolt's PhysicsSettings (Jolt/Physics/PhysicsSettings.h),
// e.g. { mNumVelocitySteps: 5, mUseLargeIslandSplitter: false }: the peer benchmark's --jolt
// option, for measuring what Jolt's design choices are worth.

const GROUND = 0;
const MOVING = 1;

/** A Jolt physics system holding `characters` ragdolls of `morphology`, stepped with `threads`. */
export class JoltScene {
  constructor(Jolt, morphology, characters, threads, { spacing = 2.5, physicsSettings = {} } = {}) {
    this.Jolt = Jolt;
    const settings = new Jolt.JoltSettings();
    settings.mMaxWorkerThreads = Math.max(0, threads - 1);  // the caller works too
    const bodiesNeeded = characters * morphology.segments.length + 1;
    settings.mMaxBodies = bodiesNeeded + 16;
    settings.mMaxBodyPairs = Math.max(1024, bodiesNeeded * 4);
    settings.mMaxContactConstraints = Math.max(1024, bodiesNeeded * 4);
    const pairs = new Jolt.ObjectLayerPairFilterTable(2);
    pairs.EnableCollision(GROUND, MOVING);  // and not MOVING with MOVING: ground-only contact
    const broadPhase = new Jolt.BroadPhaseLayerInterfaceTable(2, 2);
    broadPhase.MapObjectToBroadPhaseLayer(GROUND, new Jolt.BroadPhaseLayer(0));
    broadPhase.MapObjectToBroadPhaseLayer(MOVING, new Jolt.BroadPhaseLayer(1));
    settings.mObjectLayerPairFilter = pairs;
    settings.mBroadPhaseLayerInterface = broadPhase;
    settings.mObjectVsBroadPhaseLayerFilter = new Jolt.ObjectVsBroadPhaseLayerFilterTable(broadPhase, 2, pairs, 2);
    this.jolt = new Jolt.JoltInterface(settings);
    Jolt.destroy(settings);
    this.system = this.jolt.GetPhysicsSystem();
    this.system.SetGravity(new Jolt.Vec3(0, -9.81, 0));
    if (Object.keys(physicsSettings).length) {
      const ps = this.system.GetPhysicsSettings();
      for (const [key, value] of Object.entries(physicsSettings)) {
        if (!(key in ps)) throw new Error(`Jolt's PhysicsSettings has no field ${key}`);
        ps[key] = value;
      }
      this.system.SetPhysicsSettings(ps);
    }
    this.bodies = this.system.GetBodyInterface();

    // The ground: a large static box whose top is y = 0 (friction 1, as gaitlab's plane).
    const groundShape = new Jolt.BoxShape(new Jolt.Vec3(500, 1, 500), 0.05);
    const ground = new Jolt.BodyCreationSettings(groundShape, new Jolt.RVec3(0, -1, 0), Jolt.Quat.prototype.sIdentity(),
      Jolt.EMotionType_Static, GROUND);
    ground.mFriction = 1;
    this.bodies.CreateAndAddBody(ground, Jolt.EActivation_DontActivate);

    this.roots = [];
    const columns = Math.ceil(Math.sqrt(characters));
    for (let i = 0; i < characters; ++i) {
      // The crowd benchmark's grid (sim/scene_layout.h benchmarkPlace), all facing +z.
      const x = ((i % columns) - (columns - 1) / 2) * spacing;
      const z = (Math.floor(i / columns) - (columns - 1) / 2) * spacing;
      this.roots.push(this.addRagdoll(morphology, x, z)[0]);
    }
    this.system.OptimizeBroadPhase();
  }

  addRagdoll(m, x, z) {
    const J = this.Jolt;
    const bodies = m.segments.map((s) => {
      const [hx, hy, hz] = s.halfExtents;
      const shape = new J.BoxShape(new J.Vec3(hx, hy, hz), Math.min(0.05, 0.5 * Math.min(hx, hy, hz)));
      const c = new J.BodyCreationSettings(shape, new J.RVec3(x + s.center[0], s.center[1], z + s.center[2]),
        J.Quat.prototype.sIdentity(), J.EMotionType_Dynamic, MOVING);
      c.mFriction = 1;
      c.mLinearDamping = 0;
      c.mAngularDamping = 0;
      c.mMaxAngularVelocity = 1e4;
      c.mAllowSleeping = false;
      // Box inertia raised to the armature, as physics/character.cpp does.
      const box = (a, b) => (s.mass / 3) * (a * a + b * b);
      const inertia = [box(hy, hz), box(hx, hz), box(hx, hy)].map((v) => Math.max(v, m.armature));
      const props = new J.MassProperties();
      const size = J.MassProperties.prototype.sGetEquivalentSolidBoxSize(s.mass, new J.Vec3(...inertia));
      props.SetMassAndInertiaOfSolidBox(size, s.mass / (size.GetX() * size.GetY() * size.GetZ()));
      c.mOverrideMassProperties = J.EOverrideMassProperties_MassAndInertiaProvided;
      c.mMassPropertiesOverride = props;
      const body = this.bodies.CreateBody(c);
      this.bodies.AddBody(body.GetID(), J.EActivation_Activate);
      J.destroy(c);
      return body;
    });
    m.segments.forEach((s, i) => {
      if (s.parent < 0) return;
      const parent = bodies[s.parent];
      const child = bodies[i];
      const pivot = new J.RVec3(x + s.joint.pivot[0], s.joint.pivot[1], z + s.joint.pivot[2]);
      const axis = (k) => new J.Vec3(...s.joint.axes[k]);
      const spring = (motor) => {
        motor.mSpringSettings.mMode = J.ESpringMode_StiffnessAndDamping;
        motor.mSpringSettings.mStiffness = s.motor.kp;
        motor.mSpringSettings.mDamping = s.motor.kd;
      };
      if (s.joint.type === 'hinge') {
        const h = new J.HingeConstraintSettings();
        h.mSpace = J.EConstraintSpace_WorldSpace;
        h.mPoint1 = pivot;
        h.mPoint2 = pivot;
        h.mHingeAxis1 = axis(0);
        h.mHingeAxis2 = axis(0);
        // Any axis perpendicular to the hinge's: the angle is measured from the rest pose.
        const [ax, ay, az] = s.joint.axes[0];
        const [ux, uy, uz] = Math.abs(ax) < 0.9 ? [1, 0, 0] : [0, 1, 0];
        const n = [ay * uz - az * uy, az * ux - ax * uz, ax * uy - ay * ux];
        const length = Math.hypot(...n);
        h.mNormalAxis1 = new J.Vec3(n[0] / length, n[1] / length, n[2] / length);
        h.mNormalAxis2 = new J.Vec3(n[0] / length, n[1] / length, n[2] / length);
        h.mLimitsMin = s.joint.lower[0];
        h.mLimitsMax = s.joint.upper[0];
        spring(h.mMotorSettings);
        const c = J.castObject(h.Create(parent, child), J.HingeConstraint);
        c.SetMotorState(J.EMotorState_Position);
        c.SetTargetAngle(0);
        this.system.AddConstraint(c);
      } else {
        const d = new J.SixDOFConstraintSettings();
        d.mSpace = J.EConstraintSpace_WorldSpace;
        d.mPosition1 = pivot;
        d.mPosition2 = pivot;
        d.mAxisX1 = axis(0);
        d.mAxisX2 = axis(0);
        d.mAxisY1 = axis(1);
        d.mAxisY2 = axis(1);
        for (const t of ['TranslationX', 'TranslationY', 'TranslationZ'])
          d.MakeFixedAxis(J[`SixDOFConstraintSettings_EAxis_${t}`]);
        const rotations = ['RotationX', 'RotationY', 'RotationZ'].map((r) => J[`SixDOFConstraintSettings_EAxis_${r}`]);
        rotations.forEach((r, k) => {
          if (k < s.joint.axes.length) {
            d.SetLimitedAxis(r, s.joint.lower[k], s.joint.upper[k]);
            spring(d.get_mMotorSettings(r));
          } else d.MakeFixedAxis(r);
        });
        const c = J.castObject(d.Create(parent, child), J.SixDOFConstraint);
        rotations.forEach((r, k) => {
          if (k < s.joint.axes.length) c.SetMotorState(r, J.EMotorState_Position);
        });
        c.SetTargetOrientationCS(J.Quat.prototype.sIdentity());
        this.system.AddConstraint(c);
      }
    });
    return bodies;
  }

  /** `steps` fixed steps of 1/120 s, each two sub-steps of 1/240 s. */
  step(steps) {
    for (let k = 0; k < steps; ++k) this.jolt.Step(1 / 120, 2);
  }

  /** Mean height of the root segments, m (the counterpart of gl_peer_scene_root_height). */
  rootHeight() {
    let sum = 0;
    for (const b of this.roots) sum += b.GetPosition().GetY();
    return sum / this.roots.length;
  }

  destroy() {
    this.Jolt.destroy(this.jolt);
  }
}
