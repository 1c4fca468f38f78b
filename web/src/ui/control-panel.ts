// The control panel (lil-gui, top right): simulation (pause, step, slow motion, new scene), the
// crowd (add, remove, reset, fallen characters), steering, ground (flat, slope, bumps), and the
// gait's share/export buttons. It only sends commands; what it shows follows the worker's reports.
import GUI, { type Controller } from 'lil-gui';
import { guardNumberController } from './field-check';
import { CHARACTER_TYPES } from '../gait/character';
import { TIME_SCALES, type CharacterType, type TimeScale } from '../sim/protocol';
import { TERRAIN_KINDS, type TerrainKind } from '../sim/terrain-grid';

/**
 * The goal speeds the sliders offer until the module says which its presets walk (the `ready`
 * event's speedRanges: from 0 to each preset's fastest speed key, gl_top_speed): the speeds
 * both are benchmarked at (README, Walking).
 */
export const WALKING_SPEEDS: Record<CharacterType, { min: number; max: number }> = {
  biped: { min: 0.5, max: 1.0 },
  quadruped: { min: 0.4, max: 0.8 },
  hexapod: { min: 0.4, max: 0.8 },
  octopod: { min: 0.4, max: 0.8 },
};
/** What the steering's speed sliders call each kind. */
const SPEED_NAMES: Record<CharacterType, string> = {
  biped: 'biped speed (m/s)',
  quadruped: 'dog speed (m/s)',
  hexapod: 'six-legged speed (m/s)',
  octopod: 'eight-legged speed (m/s)',
};
/** The panel's value each kind's speed slider edits. */
export type SpeedValue = `${CharacterType}Speed`;
export const speedValue = (type: CharacterType): SpeedValue => `${type}Speed`;
/** The turn rates both presets are measured to follow (README, Walking: ±0.3 rad/s), in °/s. */
export const MAX_TURN_DEGREES = 17;

/** Who the steering acts on: the selected character, or every character (per type). */
export type SteerTarget = { id: number; type: CharacterType } | 'all';

export interface PanelActions {
  togglePause(): void;
  step(): void;
  timeScale(scale: TimeScale): void;
  newScene(): void;
  add(kind: CharacterType, count: number): void;
  removeSelected(): void;
  resetSelected(): void;
  resetFallen(): void;
  autoReset(seconds: number): void;
  /** A goal for `target` (for 'all': each type at its own speed, the same turn rate). */
  steer(target: SteerTarget, goal: { speed: Record<CharacterType, number>; turn: number }): void;
  /** Arena wandering on or off: of the crowd, or of the selected character. */
  wander(on: boolean, target: SteerTarget): void;
  follow(on: boolean): void;
  deselect(): void;
  /** The ground: flat, a ±5° slope, or 3 cm bumps. */
  terrain(kind: TerrainKind): void;
}

export class ControlPanel {
  readonly gui: GUI;
  /** Values the controllers edit (lil-gui binds to object properties). */
  readonly values = {
    slowMotion: 1 as TimeScale,
    addType: 'biped' as CharacterType,
    addCount: 1,
    autoResetSeconds: 0,
    bipedSpeed: 1.0,
    quadrupedSpeed: 0.4,
    hexapodSpeed: 0.4,
    octopodSpeed: 0.4,
    turnDegrees: 0,
    /** What the steering acts on, as the panel says it. */
    steering: 'everyone',
    wander: true,
    follow: true,
    terrain: 'flat' as TerrainKind,
  };
  private readonly pause: Controller;
  private readonly stepButton: Controller;
  private readonly selectionButtons: Controller[];
  private readonly steerLabel: Controller;
  private readonly speedControls: Record<CharacterType, Controller>;
  /** The goal speeds each type's slider spans (setSpeedRanges). */
  private ranges: Record<CharacterType, { min: number; max: number }> = structuredClone(WALKING_SPEEDS);
  private readonly turnControl: Controller;
  private readonly wanderControl: Controller;
  /** The selection the steering acts on, or 'all'. */
  private target: SteerTarget = 'all';
  /** The crowd's wandering as last reported (the switch shows the selection's when one is selected). */
  private crowdWanders = true;
  private readonly terrainControl: Controller;
  readonly gaitFolder: GUI;
  /** Beside "Add characters": why an add was refused (the crowd's limit). */
  private readonly limitNote: HTMLElement;

  constructor(actions: PanelActions) {
    const v = this.values;
    this.gui = new GUI({ title: 'gaitlab', width: 250 });

    const sim = this.gui.addFolder('Simulation');
    this.pause = sim.add({ pause: () => actions.togglePause() }, 'pause').name('Pause');
    this.stepButton = sim.add({ step: () => actions.step() }, 'step').name('Step').disable();
    sim
      .add(v, 'slowMotion', Object.fromEntries(TIME_SCALES.map((s) => [s === 1 ? 'off (1×)' : `${s}×`, s])))
      .name('slow motion')
      .onChange((s: TimeScale) => actions.timeScale(s));
    sim.add({ reset: () => actions.newScene() }, 'reset').name('Reset');

    const crowd = this.gui.addFolder('Crowd');
    crowd.add(v, 'addType', [...CHARACTER_TYPES]).name('type to add');
    guardNumberController(crowd.add(v, 'addCount', 1, 16, 1).name('how many'), 1, 16, 'how many');
    const addButton = crowd.add({ add: () => actions.add(v.addType, v.addCount) }, 'add').name('Add characters');
    this.limitNote = document.createElement('div');
    this.limitNote.className = 'panel-limit';
    this.limitNote.setAttribute('role', 'status');
    this.limitNote.hidden = true;
    addButton.domElement.after(this.limitNote);
    const resetOne = crowd.add({ reset: () => actions.resetSelected() }, 'reset').name('Reset selected');
    const removeOne = crowd.add({ remove: () => actions.removeSelected() }, 'remove').name('Remove selected');
    const deselect = crowd.add({ deselect: () => actions.deselect() }, 'deselect').name('Deselect');
    crowd.add({ reset: () => actions.resetFallen() }, 'reset').name('Reset fallen');
    crowd
      .add(v, 'autoResetSeconds', 0, 10, 0.5)
      .name('auto-reset after (s)')
      .onFinishChange((s: number) => actions.autoReset(s));
    guardNumberController(crowd.controllers[crowd.controllers.length - 1], 0, 10, 'auto-reset');
    this.selectionButtons = [resetOne, removeOne, deselect];

    const steer = this.gui.addFolder('Steering');
    this.steerLabel = steer.add(v, 'steering').name('steers').disable().listen();
    this.steerLabel.domElement.classList.add('steer-target');
    const send = () => actions.steer(this.target, { speed: this.speeds(), turn: (v.turnDegrees * Math.PI) / 180 });
    this.speedControls = Object.fromEntries(
      CHARACTER_TYPES.map((type) => {
        const { min, max } = WALKING_SPEEDS[type];
        const control = steer.add(v, speedValue(type), min, max, 0.05).name(SPEED_NAMES[type]).onChange(send).listen();
        guardNumberController(control, () => this.ranges[type].min, () => this.ranges[type].max, SPEED_NAMES[type].replace(' (m/s)', ''));
        return [type, control];
      }),
    ) as Record<CharacterType, Controller>;
    this.setSpeedRanges(this.ranges);
    this.turnControl = steer.add(v, 'turnDegrees', -MAX_TURN_DEGREES, MAX_TURN_DEGREES, 1).name('turn (°/s)').onChange(send).listen();
    guardNumberController(this.turnControl, -MAX_TURN_DEGREES, MAX_TURN_DEGREES, 'turn');
    this.turnControl.domElement.title = 'the turn rates the gaits are measured to follow: ±0.3 rad/s; while wandering, wandering chooses it';
    this.wanderControl = steer
      .add(v, 'wander')
      .name('wander in the arena')
      .onChange((on: boolean) => {
        actions.wander(on, this.target);
        this.updateSteering();
      })
      .listen();
    steer.add(v, 'follow').name('camera follows selected').onChange((on: boolean) => actions.follow(on)).listen();

    const ground = this.gui.addFolder('Ground');
    this.terrainControl = ground
      .add(v, 'terrain', [...TERRAIN_KINDS])
      .name('terrain')
      .onChange((kind: TerrainKind) => actions.terrain(kind))
      .listen();
    this.terrainControl.domElement.title =
      'flat; slope: ridges and valleys of ±5° across +z (the crowd walks up and down); bumps: smooth random bumps 2–3 cm high, 0.5 m apart';

    this.gaitFolder = this.gui.addFolder('Gait');
    this.setSelection(null);
  }


  /** Each kind's goal speed, as its slider has it. */
  speeds(): Record<CharacterType, number> {
    return Object.fromEntries(CHARACTER_TYPES.map((type) => [type, this.values[speedValue(type)]])) as Record<CharacterType, number>;
  }

  /** The goal speeds a type's slider spans. */
  speedRange(type: CharacterType): { min: number; max: number } {
    return this.ranges[type];
  }

  /**
   * The goal speeds each type walks (from the module: 0 to its preset's fastest speed key); a
   * slider beyond its new range is brought inside it.
   */
  setSpeedRanges(ranges: Record<CharacterType, { min: number; max: number }>): void {
    this.ranges = structuredClone(ranges);
    for (const type of CHARACTER_TYPES) {
      const { min, max } = this.ranges[type];
      const control = this.speedControls[type];
      control.min(min).max(max);
      if (Number(control.getValue()) > max) control.setValue(max);
      if (Number(control.getValue()) < min) control.setValue(min);
      control.domElement.title = `the goal speeds the ${type}'s gait walks: ${min}–${max} m/s (at 0 it stops and stands, or steps in place if its gait's standSpeed is 0; the top is its fastest speed key)`;
      control.updateDisplay();
    }
  }
  /** A refusal beside "Add characters" (null clears it). */
  showCrowdLimit(text: string | null): void {
    this.limitNote.textContent = text ?? '';
    this.limitNote.hidden = text === null;
  }

  /** Shows the ground the simulation has (after a change it confirmed, or a new scene). */
  setTerrain(kind: TerrainKind): void {
    this.values.terrain = kind;
    this.terrainControl.updateDisplay();
  }

  /** Follows the worker's pause state (the button says what a click will do). */
  setPaused(paused: boolean): void {
    this.pause.name(paused ? 'Resume' : 'Pause');
    if (paused) this.stepButton.enable();
    else this.stepButton.disable();
  }

  /**
   * Enables what needs a selected character. Steering acts on the selected character when there
   * is one (the panel names it, shows its goal and offers only its type's speed), else on
   * everyone.
   */
  setSelection(selected: { id: number; type: CharacterType; goal: { speed: number; turn: number }; wanders?: boolean } | null): void {
    for (const c of this.selectionButtons) {
      if (selected) c.enable();
      else c.disable();
    }
    const v = this.values;
    if (!selected) {
      this.target = 'all';
      v.wander = this.crowdWanders;
    } else {
      this.target = { id: selected.id, type: selected.type };
      v[speedValue(selected.type)] = selected.goal.speed;
      v.turnDegrees = Math.round((selected.goal.turn * 180) / Math.PI);
      v.wander = selected.wanders ?? false;
    }
    this.updateSteering();
  }

  /** Follows the worker's report of the crowd's wandering (the switch, when nobody is selected). */
  setCrowdWander(on: boolean): void {
    this.crowdWanders = on;
    if (this.target === 'all' && this.values.wander !== on) {
      this.values.wander = on;
      this.updateSteering();
    }
  }

  /** The target the steering acts on now. */
  get steerTarget(): SteerTarget {
    return this.target;
  }

  /** The label, and which controls act: a selection's own type only; turning is wandering's while it wanders. */
  private updateSteering(): void {
    const t = this.target;
    const v = this.values;
    v.steering = t === 'all' ? 'everyone' : `${t.type} #${t.id} only`;
    for (const type of CHARACTER_TYPES) {
      if (t === 'all' || t.type === type) this.speedControls[type].enable();
      else this.speedControls[type].disable();
    }
    // Wandering chooses the crowd's turn rate; a selected character steered by hand leaves it.
    if (t === 'all' && v.wander) this.turnControl.disable();
    else this.turnControl.enable();
    this.steerLabel.updateDisplay();
    this.wanderControl.updateDisplay();
  }
}
