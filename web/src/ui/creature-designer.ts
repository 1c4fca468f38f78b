// The creature designer: a folder of the control panel where a body is drawn up from a few
// settings (creature/design.ts) and seen walking at once. Each change, after a pause in the
// editing, replaces the preview character beside the crowd by the new body; a body the model
// refuses is not sent, and one the module refuses is said here with the field named. The thesis
// (Larsson 2015, §7.5) ends with characters of any leg count that a player designs and then sees
// come to life under physics; this is that, for bodies of 1 to 4 leg pairs.
import type GUI from 'lil-gui';
import type { Controller } from 'lil-gui';
import { guardNumberController } from './field-check';
import { DesignBlueprint } from './design-blueprint';
import { totalMass, type CreatureFile } from '../creature/creature-file';
import {
  DEFAULT_DESIGN,
  designCreature,
  designFromFile,
  KNEE_CHOICES,
  SETTING_RANGES,
  type CreatureDesign,
  type DesignProblem,
  type NumericSetting,
} from '../creature/design';
import type { CharacterStatus, SceneCommand } from '../sim/protocol';
import type { OptimizeForm } from '../optimize/options';

/** The shipped creatures a design can start from (public/creatures/NAME.json). */
export const DESIGN_PRESETS = ['insect', 'spider', 'dragon', 'bird', 'quadruped', 'biped'] as const;
export type DesignPreset = (typeof DESIGN_PRESETS)[number];

/** A pause in the editing this long (ms) sends the body: a slider dragged respawns once, not 30 times. */
const DEBOUNCE_MS = 300;
/** The preview's goal speed at first, m/s: the walking criteria's slow speed, as `?creature=` walks. */
const PREVIEW_SPEED = 0.4;
/** The preview's speeds: standing (it steps in place: the derived gait has no stand) to the criteria's fast 0.8 m/s. */
const PREVIEW_SPEEDS = { min: 0, max: 0.8 };
/** Beside the crowd: this far right of its rightmost character (m), clear of its legs' reach. */
const BESIDE_CROWD = 2.5;
/** It starts this far behind the crowd's middle (m), so its first metres of walking pass beside it. */
const BEHIND_CROWD = 2;
/** Walked this far from its start (m), it starts over there, so it stays beside the crowd. */
const LOOP_DISTANCE = 8;
/** Down this long (s of simulated time, the worker's fallenSeconds), it starts over: falling is shown, not kept. */
const RESTART_FALLEN = 3;
/** lil-gui's folder opening animation, ms (its CSS transition is 0.3 s), with a margin. */
const OPENING_MS = 400;

export interface DesignerHost {
  send(command: SceneCommand): void;
  /** Spawns a creature (SimClient.spawnCreature): resolves with its id, rejects with the refusal. */
  spawn(command: Omit<Extract<SceneCommand, { type: 'spawnCreature' }>, 'type' | 'request'>): Promise<number>;
  /** Selects a character; the camera follows the selection. */
  select(id: number | null): void;
  /** Where the shipped creature file NAME is served. */
  creatureUrl(name: string): URL;
  /**
   * Searches a gait for `file`'s body in the optimize panel (its teaching settings, `values` of
   * its form over them); resolves when the search ends.
   */
  teach(file: CreatureFile, values?: OptimizeForm): Promise<unknown>;
}

/** The spawn the designer waits for the worker to answer. */
interface PendingSpawn {
  /** Told apart from a spawn it replaced (one answered after it is dropped). */
  serial: number;
  x: number;
  z: number;
}

export class CreatureDesigner {
  readonly folder: GUI;
  /** The settings the controls edit (lil-gui binds to object properties). */
  private readonly values: CreatureDesign & { preset: DesignPreset | 'custom'; previewSpeed: number; show: boolean };
  private readonly controls = new Map<keyof CreatureDesign, Controller>();
  private readonly status: HTMLElement;
  /** The side and top views, with handles to drag. */
  readonly blueprint: DesignBlueprint;
  private timer: ReturnType<typeof setTimeout> | undefined;
  /** The preview character's id once the worker has reported it. */
  private previewId: number | null = null;
  /** Where the preview started (m), for its loop. */
  private start: { x: number; z: number } | null = null;
  private pending: PendingSpawn | null = null;
  private spawns = 0;
  /** Counts scenes (Reset): a spawn answered after a new scene began is not removed from it. */
  private scene = 0;
  /** The worker's newest character list; null until the first report of a scene. */
  private characters: CharacterStatus[] | null = null;
  /** The module's refusal of the last body sent, if it refused it. */
  private refusal: string | null = null;
  private restarts = 0;

  constructor(parent: GUI, private readonly host: DesignerHost) {
    this.values = { ...DEFAULT_DESIGN, preset: 'insect', previewSpeed: PREVIEW_SPEED, show: false };
    const v = this.values;
    this.folder = parent.addFolder('Design a creature').close();
    this.folder.domElement.classList.add('designer');
    this.status = document.createElement('div');
    this.status.className = 'designer-status';
    this.status.setAttribute('role', 'status');
    this.status.setAttribute('data-testid', 'designer-status');
    this.blueprint = new DesignBlueprint((change) => this.set(change));
    // The drawing above the status line: a refusal that lengthens the line does not move a handle from under the pointer.
    this.folder.$children.prepend(this.blueprint.element, this.status);

    const f = this.folder;
    f.add(v, 'preset', [...DESIGN_PRESETS, 'custom'])
      .name('start from')
      .onChange((name: DesignPreset | 'custom') => {
        if (name !== 'custom') void this.loadPreset(name);
      });
    const number = (folder: GUI, key: NumericSetting) => {
      const r = SETTING_RANGES[key];
      const c = folder.add(v, key, r.min, r.max, r.step).name(r.unit ? `${r.label} (${r.unit})` : r.label).onChange(() => this.edited());
      // A preset's values are shown to the slider's step (the insect's leg mass share is 12/37).
      c.decimals(Math.max(0, Math.ceil(-Math.log10(r.step) - 1e-9)));
      guardNumberController(c, r.min, r.max, r.label);
      this.controls.set(key, c);
    };
    number(f, 'pairs');
    const legs = f.addFolder('Legs');
    for (const key of ['upperLength', 'lowerLength', 'tarsusLength', 'legThickness', 'hipSpacing', 'legShare'] as const) number(legs, key);
    this.controls.get('tarsusLength')!.domElement.title =
      'a third segment below the lower leg, whose joint (the hock) bends the other way to the knee, as a bird\'s or a dog\'s hind leg; 0: legs of two segments';
    this.controls.set('knees', legs.add(v, 'knees', [...KNEE_CHOICES]).name('knees').onChange(() => this.edited()));
    this.controls.get('knees')!.domElement.title =
      'mixed: the front half bend backward (as a dog\'s front legs), the rest forward; forward: as a human\'s; backward: all of them (a bird\'s knee points forward: its backward joint is the hock of a third segment)';
    this.controls.get('legShare')!.domElement.title = 'the legs\' share of a leg frame with its two legs, by mass';
    const joints = f.addFolder('Joints');
    for (const key of ['kneeFlexion', 'hipSwing'] as const) number(joints, key);
    this.controls.get('kneeFlexion')!.domElement.title = 'how far each knee (and hock) bends from straight, at most';
    this.controls.get('hipSwing')!.domElement.title = 'how far each hip swings forward and back, at most (a single pair: further forward than back, as the biped\'s)';
    const body = f.addFolder('Body');
    for (const key of ['frameSpacing', 'bodyWidth', 'bodyHeight', 'frameMass'] as const) number(body, key);
    this.controls.get('frameSpacing')!.domElement.title = 'the spacing of neighbouring leg frames, centre to centre';
    const colours = f.addFolder('Colours').close();
    for (const [key, name] of [['bodyColour', 'body'], ['spineColour', 'spine'], ['leftColour', 'left legs'], ['rightColour', 'right legs']] as const) {
      this.controls.set(key, colours.addColor(v, key).name(name).onChange(() => this.edited()));
    }
    const speed = f.add(v, 'previewSpeed', PREVIEW_SPEEDS.min, PREVIEW_SPEEDS.max, 0.05).name('walks at (m/s)').onChange((s: number) => {
      if (this.previewId !== null) this.host.send({ type: 'setGoal', id: this.previewId, speed: s, turn: 0 });
    });
    guardNumberController(speed, PREVIEW_SPEEDS.min, PREVIEW_SPEEDS.max, 'walks at');
    f.add(v, 'show').name('show in the scene').listen().onChange((on: boolean) => (on ? this.schedule(0) : this.removePreview()));
    f.add({ look: () => this.previewId !== null && this.host.select(this.previewId) }, 'look').name('Look at it');
    f.add({ teach: () => void this.teach().catch(() => {}) }, 'teach').name('Teach it to walk');
    f.add({ save: () => this.save() }, 'save').name('Save creature file');
    // Opening the folder first shows the preview: the designer is in use.
    f.onOpenClose((gui) => {
      if (gui !== f || gui._closed) return;
      // The folder is the panel's last: bring it into the panel's scrolled view once lil-gui's
      // opening animation has given it its height.
      setTimeout(() => f.domElement.scrollIntoView({ block: 'start' }), OPENING_MS);
      if (!v.show) this.setShown(true);
    });
    this.showStatus();
    this.blueprint.show(this.design());
  }

  /** The settings now. */
  design(): CreatureDesign {
    const { preset: _preset, previewSpeed: _speed, show: _show, ...design } = this.values;
    return design;
  }

  /**
   * Changes some settings, as the controls would (then the preview follows, after the pause).
   * Unknown names are an error: a test that misspells one should not pass.
   */
  set(changes: Partial<CreatureDesign>): void {
    for (const key of Object.keys(changes)) {
      if (!(key in DEFAULT_DESIGN)) throw new Error(`the designer has no setting '${key}' (it has ${Object.keys(DEFAULT_DESIGN).join(', ')})`);
    }
    Object.assign(this.values, changes);
    for (const c of this.controls.values()) c.updateDisplay();
    this.values.show = true;
    this.edited();
  }

  /** The settings of shipped creature `name` (its file fetched), then the preview of it. */
  async loadPreset(name: DesignPreset): Promise<void> {
    try {
      const response = await fetch(this.host.creatureUrl(name));
      if (!response.ok) throw new Error(`creatures/${name}.json: ${response.status}`);
      const design = designFromFile((await response.json()) as CreatureFile);
      this.set(design);
      this.values.preset = name;
      this.folder.controllers[0].updateDisplay();
    } catch (error) {
      this.refusal = `the ${name} could not be loaded: ${error instanceof Error ? error.message : String(error)}`;
      this.showStatus();
    }
  }

  /**
   * The designed creature's file, or null while the settings are refused (by the checks, or by
   * the module for the body last sent): nothing else gets an impossible body.
   */
  creatureJson(): CreatureFile | null {
    const { file, problems } = designCreature(this.design(), this.name());
    return problems.length > 0 || this.refusal !== null ? null : file;
  }

  /** Why the design is refused (every reason, one a line), or null. */
  error(): string | null {
    const problems = designCreature(this.design()).problems;
    if (problems.length > 0) return problems.map((p) => p.message).join('\n');
    return this.refusal;
  }

  /** The preview character's id, or null when there is none (yet). */
  preview(): number | null {
    return this.previewId;
  }

  /** The worker's report (4 a second): finds a new preview, keeps it beside the crowd. */
  tick(characters: CharacterStatus[]): void {
    const first = this.characters === null;
    this.characters = characters;
    if (first && this.values.show) this.respawn();
    if (this.pending || this.previewId === null) return;
    const me = characters.find((c) => c.id === this.previewId);
    if (!me) {
      // Removed from outside (the Delete key, the panel): the designer stops showing it.
      this.previewId = null;
      this.values.show = false;
      this.showStatus();
      return;
    }
    const walked = this.start ? Math.hypot(me.position[0] - this.start.x, me.position[2] - this.start.z) : 0;
    if (walked > LOOP_DISTANCE || me.fallenSeconds > RESTART_FALLEN) {
      if (me.fallenSeconds > RESTART_FALLEN) this.restarts++;
      this.respawn();
    }
  }

  /** A new scene (Reset): the old preview is gone with it; a new one comes with the scene's first report. */
  sceneReset(): void {
    this.previewId = null;
    this.pending = null;
    this.characters = null;
    this.scene++;
  }

  /**
   * Sends the body and waits for the worker's answer: its id makes it the preview (the worker's
   * reports after the answer all have it), a refusal is the module's verdict on the body, shown
   * here. An answer to a spawn since replaced is dropped, and that character removed.
   */
  private spawn(file: CreatureFile, x: number, z: number): void {
    const pending: PendingSpawn = { serial: ++this.spawns, x, z };
    const scene = this.scene;
    this.pending = pending;
    this.host.spawn({ json: JSON.stringify(file), x, z, heading: 0, speed: this.values.previewSpeed }).then(
      (id) => {
        if (this.pending !== pending) {
          if (this.scene === scene) this.host.send({ type: 'remove', id });
          return;
        }
        this.pending = null;
        this.previewId = id;
        this.start = { x, z };
        this.showStatus();
      },
      (error: unknown) => {
        if (this.pending !== pending) return;
        const message = error instanceof Error ? error.message : String(error);
        this.pending = null;
        this.refusal = `the module refused the body: ${message}`;
        this.showStatus();
      },
    );
  }

  private name(): string {
    return this.values.preset === 'custom' ? 'designed' : `designed-${this.values.preset}`;
  }

  private setShown(on: boolean): void {
    this.values.show = on;
    if (on) this.schedule(0);
    else this.removePreview();
  }

  /** A control changed: the design is the user's own now, and is sent after the pause. */
  private edited(): void {
    this.blueprint.show(this.design());
    this.values.preset = 'custom';
    this.folder.controllers[0].updateDisplay();
    this.refusal = null;
    this.restarts = 0;
    this.showStatus();
    if (this.values.show) this.schedule(DEBOUNCE_MS);
  }

  private schedule(ms: number): void {
    clearTimeout(this.timer);
    this.timer = setTimeout(() => this.respawn(), ms);
  }

  /** Replaces the preview by the body the settings describe, if the checks let it through. */
  private respawn(): void {
    clearTimeout(this.timer);
    this.timer = undefined;
    if (!this.values.show) return;
    const { file, problems } = designCreature(this.design(), this.name());
    this.showStatus();
    // An impossible body is not sent: the last one that could be built keeps walking.
    if (problems.length > 0) return;
    // Until the scene's first report, what is there (to tell the new body apart) is not known.
    if (this.characters === null) return;
    const old = this.previewId;
    if (old !== null) this.host.send({ type: 'remove', id: old });
    const others = this.characters.filter((c) => c.id !== old);
    const x = others.length === 0 ? 0 : Math.max(...others.map((c) => c.position[0])) + BESIDE_CROWD;
    const z = others.length === 0 ? -BEHIND_CROWD : others.reduce((s, c) => s + c.position[2], 0) / others.length - BEHIND_CROWD;
    this.previewId = null;
    this.refusal = null;
    this.spawn(file, x, z);
    this.showStatus();
  }

  private removePreview(): void {
    clearTimeout(this.timer);
    this.timer = undefined;
    if (this.previewId !== null) this.host.send({ type: 'remove', id: this.previewId });
    this.previewId = null;
    this.pending = null;
    this.showStatus();
  }

  /**
   * "Teach it to walk": the optimize panel searches a gait for this body (from the gait derived
   * from it), and its learner shows the best so far. Rejects when the body is refused (as the
   * status line says) or the search cannot start (as the optimize panel says).
   */
  async teach(values?: OptimizeForm): Promise<unknown> {
    const file = this.creatureJson();
    if (!file) throw new Error(this.error() ?? 'the body is refused');
    return this.host.teach(file, values);
  }

  /** Downloads the design as a creature file (for `gaitlab walk --creature FILE` and the like). */
  private save(): void {
    const file = this.creatureJson();
    if (!file) return;
    const link = document.createElement('a');
    link.href = URL.createObjectURL(new Blob([`${JSON.stringify(file, null, 2)}\n`], { type: 'application/json' }));
    link.download = `${file.name}.json`;
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 1000);
  }

  /** The line under the folder's title: the body and its preview, or why it is refused; refused settings marked. */
  private showStatus(): void {
    const design = this.design();
    const { file, problems } = designCreature(design, this.name());
    const refused = new Set<keyof CreatureDesign>(problems.map((p: DesignProblem) => p.setting));
    for (const [key, c] of this.controls) c.domElement.classList.toggle('designer-refused', refused.has(key));
    const lines: string[] = [];
    let problem = true;
    if (problems.length > 0) {
      lines.push('Not built:', ...problems.map((p) => `• ${p.message}`));
    } else if (this.refusal !== null) {
      lines.push(this.refusal);
    } else {
      problem = false;
      const summary = `${2 * design.pairs} legs, ${totalMass(file).toFixed(1)} kg`;
      if (!this.values.show) lines.push(`${summary}. Tick "show in the scene" to see it walk.`);
      else if (this.pending || (this.timer !== undefined && this.previewId === null)) lines.push(`${summary}: spawning beside the crowd…`);
      else if (this.previewId !== null) {
        lines.push(`${summary}: #${this.previewId} walks beside the crowd${this.restarts > 0 ? ` (started over after ${this.restarts} fall${this.restarts > 1 ? 's' : ''})` : ''}.`);
      } else lines.push(`${summary}.`);
    }
    this.status.textContent = lines.join('\n');
    this.status.classList.toggle('designer-problem', problem);
  }
}
