// The control panel (lil-gui, top right): simulation (pause, step, slow motion, new scene), the
// crowd (add, remove, reset, fallen characters), steering, ground (flat, slope, bumps), and the
// gait's share/export buttons. It only sends commands; what it shows follows the worker's reports.
import GUI, { type Controller } from 'lil-gui';
import { CHARACTER_TYPES } from '../gait/character';
import { TIME_SCALES, type CharacterType, type TimeScale } from '../sim/protocol';
import { TERRAIN_KINDS, type TerrainKind } from '../sim/terrain-grid';

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
  steer(speed: number, turn: number, target: 'selected' | 'all'): void;
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
    speed: 1.0,
    turnDegrees: 0,
    steer: 'all' as 'selected' | 'all',
    follow: false,
    terrain: 'flat' as TerrainKind,
  };
  private readonly pause: Controller;
  private readonly stepButton: Controller;
  private readonly selectionButtons: Controller[];
  private readonly steerTarget: Controller;
  private readonly terrainControl: Controller;
  readonly gaitFolder: GUI;

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
    crowd.add(v, 'addCount', 1, 16, 1).name('how many');
    crowd.add({ add: () => actions.add(v.addType, v.addCount) }, 'add').name('Add characters');
    const resetOne = crowd.add({ reset: () => actions.resetSelected() }, 'reset').name('Reset selected');
    const removeOne = crowd.add({ remove: () => actions.removeSelected() }, 'remove').name('Remove selected');
    const deselect = crowd.add({ deselect: () => actions.deselect() }, 'deselect').name('Deselect');
    crowd.add({ reset: () => actions.resetFallen() }, 'reset').name('Reset fallen');
    crowd
      .add(v, 'autoResetSeconds', 0, 10, 0.5)
      .name('auto-reset after (s)')
      .onFinishChange((s: number) => actions.autoReset(s));
    this.selectionButtons = [resetOne, removeOne, deselect];

    const steer = this.gui.addFolder('Steering');
    const send = () => actions.steer(v.speed, (v.turnDegrees * Math.PI) / 180, v.steer);
    steer.add(v, 'speed', -0.5, 2, 0.05).name('speed (m/s)').onChange(send).listen();
    steer.add(v, 'turnDegrees', -60, 60, 1).name('turn (°/s)').onChange(send).listen();
    this.steerTarget = steer.add(v, 'steer', ['selected', 'all']).name('steer').listen();
    steer.add(v, 'follow').name('follow selected').onChange((on: boolean) => actions.follow(on)).listen();

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

  /** Enables what needs a selected character; the steering shows that character's goal. */
  setSelection(selected: { goal: { speed: number; turn: number } } | null): void {
    for (const c of this.selectionButtons) {
      if (selected) c.enable();
      else c.disable();
    }
    if (!selected) {
      this.values.steer = 'all';
      this.steerTarget.disable();
    } else {
      this.steerTarget.enable();
      this.values.speed = selected.goal.speed;
      this.values.turnDegrees = Math.round((selected.goal.turn * 180) / Math.PI);
    }
  }
}
