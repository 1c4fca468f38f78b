// The page's test hook, `window.gaitlab`: what the end-to-end tests (tests/e2e) and the
// benchmark drivers read and drive, with the same names and shapes since the demo page first had
// them (stats(), characters(), getGait(id), shareUrl(id), throwBox(xyz), setGoal(id|'all',
// {speed, turn}), ...). It only forwards to the page's parts (main.ts hands them over): nothing
// here keeps state of its own.
import type { CreatureFile } from './creature/creature-file';
import { randomDesign, type CreatureDesign } from './creature/design';
import type { CharacterType } from './gait/character';
import type { OptimizeForm } from './optimize/options';
import type { GaitFile, ParamPatch } from './share/gait-file';
import type { CharacterStatus, SceneCommand, SimCommand, TimeScale, Vec3 } from './sim/protocol';
import type { TerrainKind } from './sim/terrain-grid';
import type { CreatureDesigner, DesignPreset } from './ui/creature-designer';
import type { GaitEditors } from './ui/gait-editors';
import type { OptimizePanel, OptimizeStatus } from './ui/optimize-panel';

/** What `window.gaitlab.stats()` returns. */
export interface GaitlabStats {
  characters: number;
  fallen: number;
  /** Simulated seconds of the frame on screen. */
  simTime: number;
  /** Simulated seconds per wall-clock second, smoothed (1 = real time). */
  realtimeFactor: number;
  /** Rendered frames per second, smoothed. */
  fps: number;
  threads: number;
  crossOriginIsolated: boolean;
  /** WebGL draw calls of the last frame (shadow pass included): constant in the crowd's size. */
  drawCalls: number;
  /** How the page got its threads: 'headers', 'service worker' or 'none'. */
  isolation: string;
  /** Bodies in the frame on screen. */
  bodies: number;
  paused: boolean;
  timeScale: TimeScale;
  /** True once a simulated frame has been drawn. */
  ready: boolean;
  /** The problem shown on the page, if any. */
  error: string | null;
  /** Whether this build has the parameter schema (gait editing and sharing). */
  gaits: boolean;
  selected: number | null;
  /** The ground the simulation reports, and the one the page draws (they differ for a moment after a change). */
  terrain: TerrainKind;
  drawnTerrain: TerrainKind | null;
  /** Arena wandering as the worker reports it: on or off, and the arena's radius (m, about the origin). */
  wander: { on: boolean; arenaRadius: number };
}

export interface GaitlabHook {
  stats(): GaitlabStats;
  characters(): CharacterStatus[];
  getGait(id: number): Promise<GaitFile>;
  shareUrl(id: number): Promise<string>;
  /** The preset gait of a type, as the module has it. */
  presetGait(type: CharacterType): Promise<GaitFile>;
  /**
   * An edit through the gait editors, as a gesture makes one: `patch` ({parameter: value}) to
   * the edited gait (select a character first, or the editors edit every character of a type).
   * Resolves with null when the simulation accepted it, or with its refusal (the editors then
   * show the gait the simulation has, and the page says why).
   */
  editGait(patch: ParamPatch): Promise<string | null>;
  /** The gait the editors show, or null before they have one. */
  editorGait(): GaitFile | null;
  throwBox(target: Vec3): void;
  /**
   * A character whose body is a creature file's text (public/creatures/*.json) at (x, z), walking
   * at `speed` m/s: the page's `?creature=NAME` does the same with a shipped file. A refused file
   * is shown on the page as every refused command is.
   */
  spawnCreature(json: string, x: number, z: number, speed: number): void;
  setGoal(id: number | 'all', goal: { speed: number; turn: number }): void;
  select(id: number | null): void;
  /** `count` fixed steps while paused. */
  step(count: number): void;
  pause(): void;
  resume(): void;
  /** Screen position (CSS pixels) of character `id`'s root body, for tests that click it. */
  screenPosition(id: number): { x: number; y: number } | null;

  // ---- The optimize panel. These drive the panel itself, as its buttons do. ----

  /**
   * Starts a search as the panel's Start button does, after writing `form` into the panel's
   * fields (as text, as if typed; fields left out keep their values). Field names: character
   * ('biped' | 'quadruped'), method ('greedy' | 'cmaes'), start ('preset' | 'selected'),
   * generations, candidates, seed, threads, speeds ("0.5, 1"), and every objective setting by
   * its gl_opt_settings_json name (seconds, warmup, starts, turnRate, wd, …). Resolves with
   * optimizeStatus() when the search ends (state 'done', or 'stopped' after stopOptimize());
   * rejects with the panel's message if the form is refused (every problem, each naming its
   * field) or the search fails.
   */
  optimize(form?: OptimizeForm): Promise<OptimizeStatus>;
  /** The panel's state: progress, history of the best objective, the chart's point count, the result. */
  optimizeStatus(): OptimizeStatus;
  /** The panel's Stop: ends the search at once, keeping the best of the finished generations. */
  stopOptimize(): void;
  /** The panel's Apply: the result to the selected character or to every character of its type. */
  applyOptimizeResult(target: 'selected' | 'all'): Promise<void>;
  /** The panel's Share: a link to this page carrying the result. */
  optimizeShareUrl(): Promise<string>;
  /** The learner's id (the character walking the best so far), or null. */
  learner(): number | null;
  /** Changes the ground (as the control panel does): flat, slope or bumps. */
  setTerrain(kind: TerrainKind): void;
  /** Height of the drawn ground at (x, z): from the samples the page drew, the physics' own. */
  groundHeight(x: number, z: number): number | null;
  /**
   * Puts the camera at `from` looking at `to` (screenshots and tests; orbiting continues from
   * there), and keeps that distance as a user's zoom is kept, until "frame the crowd".
   */
  view(from: Vec3, to: Vec3): void;
  /**
   * Every body of the newest simulation frame (read from the shared render buffer now, and then
   * drawn: stats() reports that frame from then on): its owner (character id, −1 for props),
   * centre (m) and instance matrix (column-major, its box's size baked in: the unit box's axes
   * scaled).
   */
  bodies(): { owner: number; position: Vec3; matrix: number[] }[];
  /** The camera: its distance to the point it looks at (m) and its azimuth about +y (rad). */
  camera(): { distance: number; azimuth: number };
  /** The owner of the body a click at (x, y) would pick (character id, −1 a prop), or null. */
  ownerAt(x: number, y: number): number | null;
  /** The creature designer (control panel, "Design a creature"), driven as its controls drive it. */
  designer: DesignerHook;
}

/** `window.gaitlab.designer`. */
export interface DesignerHook {
  /**
   * Changes settings as the controls do ({pairs: 3, upperLength: 0.2}; creature/design.ts names
   * them) and shows the preview: the body is sent after the controls' pause, if it passes the
   * checks. An unknown setting throws.
   */
  set(changes: Partial<CreatureDesign>): void;
  /** The settings now. */
  values(): CreatureDesign;
  /** The designed creature file, or null while the design is refused. */
  json(): CreatureFile | null;
  /** Why the design is refused (the checks' reasons, or the module's refusal of the body sent), or null. */
  error(): string | null;
  /** The preview character's id, or null before the worker has reported it. */
  preview(): number | null;
  /** Loads a shipped creature's settings as the "start from" list does. */
  preset(name: DesignPreset): Promise<void>;
  /** A random body within the designer's limits (creature/design.ts, randomDesign; the same seed, the same body). */
  randomize(seed: number): void;
  /**
   * Where a handle of the designer's drawing is in the page (CSS px), to drag with the mouse:
   * knee, hock, ankle, frame, top, hip or side (creature/blueprint.ts); null when the design has
   * none such or the folder is closed.
   */
  handle(name: string): { x: number; y: number } | null;
  /**
   * "Teach it to walk": the optimize panel searches a gait for the designed body with its
   * teaching settings and `form` written over them into its fields, as optimize() does; resolves
   * with optimizeStatus() when it ends.
   */
  teach(form?: OptimizeForm): Promise<OptimizeStatus>;
}

declare global {
  interface Window {
    gaitlab: GaitlabHook;
  }
}

/** The page's parts the hook forwards to (main.ts). */
export interface TestHookHost {
  stats(): GaitlabStats;
  characters(): CharacterStatus[];
  editors(): GaitEditors | null;
  optimizer(): OptimizePanel | null;
  /** Why the optimize panel is missing, when it is. */
  optimizerMissing(): string;
  send(command: SceneCommand): void;
  control(command: SimCommand): void;
  select(id: number | null): void;
  throwBox(target: Vec3): void;
  learner(): number | null;
  setTerrain(kind: TerrainKind): void;
  screenPosition(id: number): { x: number; y: number } | null;
  groundHeight(x: number, z: number): number | null;
  view(from: Vec3, to: Vec3): void;
  bodies(): { owner: number; position: Vec3; matrix: number[] }[];
  camera(): { distance: number; azimuth: number };
  ownerAt(x: number, y: number): number | null;
  designer(): CreatureDesigner;
}

/** Installs `window.gaitlab`, frozen. */
export function installTestHook(host: TestHookHost): GaitlabHook {
  const editors = (): GaitEditors => {
    const e = host.editors();
    if (!e) throw new Error('this build has no parameter schema');
    return e;
  };
  const optimizer = (): OptimizePanel => {
    const o = host.optimizer();
    if (!o) throw new Error(host.optimizerMissing());
    return o;
  };
  const hook: GaitlabHook = {
    stats: () => host.stats(),
    characters: () => host.characters().map((c) => ({ ...c, position: [...c.position] as Vec3, goal: { ...c.goal } })),
    getGait: async (id) => editors().gaitOf(id),
    shareUrl: async (id) => editors().shareUrl(id),
    presetGait: async (type) => editors().presetOf(type),
    editGait: async (patch) => editors().editAsGesture(patch),
    editorGait: () => host.editors()?.editorGait ?? null,
    throwBox: (target) => host.throwBox(target),
    spawnCreature: (json, x, z, speed) => host.send({ type: 'spawnCreature', json, x, z, heading: 0, speed }),
    setGoal: (id, goal) => host.send({ type: 'setGoal', id, speed: goal.speed, turn: goal.turn }),
    select: (id) => host.select(id),
    step: (count) => host.control({ type: 'step', count }),
    pause: () => host.control({ type: 'pause' }),
    resume: () => host.control({ type: 'resume' }),
    optimize: (form) => {
      const o = host.optimizer();
      if (!o) return Promise.reject(new Error(host.optimizerMissing()));
      return o.start(form);
    },
    optimizeStatus: () => optimizer().status(),
    stopOptimize: () => host.optimizer()?.stop(),
    applyOptimizeResult: async (target) => optimizer().applyResult(target),
    optimizeShareUrl: async () => optimizer().shareUrl(),
    learner: () => host.learner(),
    screenPosition: (id) => host.screenPosition(id),
    setTerrain: (kind) => host.setTerrain(kind),
    groundHeight: (x, z) => host.groundHeight(x, z),
    view: (from, to) => host.view(from, to),
    bodies: () => host.bodies(),
    camera: () => host.camera(),
    ownerAt: (x, y) => host.ownerAt(x, y),
    designer: Object.freeze({
      set: (changes: Partial<CreatureDesign>) => host.designer().set(changes),
      values: () => host.designer().design(),
      json: () => host.designer().creatureJson(),
      error: () => host.designer().error(),
      preview: () => host.designer().preview(),
      preset: (name: DesignPreset) => host.designer().loadPreset(name),
      randomize: (seed: number) => host.designer().set(randomDesign(seed)),
      handle: (name: string) => host.designer().blueprint.handlePosition(name),
      teach: async (form?: OptimizeForm) => (await host.designer().teach(form)) as OptimizeStatus,
    }),
  };
  window.gaitlab = Object.freeze(hook);
  return hook;
}
