// Gait editing and sharing: which gait is being edited (the selected character's, or that of
// every character of a type), the editors for it (curve editors for the motion graphs, the gait
// diagram, a grouped panel for scalars and gains), undo/redo, reset to preset, and the ways a
// gait leaves and enters the page (share link, JSON file export and import).
//
// Everything is driven by the parameter schema the WASM module reports (gl_schema_json): names,
// groups, bounds, units and descriptions are never written out here.
import type GUI from 'lil-gui';
import { CurveEditor } from './curve-editor';
import { GaitDiagram, type LegTiming } from './gait-diagram';
import type { Overlay } from './overlay';
import {
  CHARACTER_TYPES,
  GaitError,
  parseGait,
  sameParams,
  type CharacterType,
  type GaitFile,
  type ParamSchema,
  type ParamValue,
  type SchemaEntry,
} from '../share/gait-file';
import { decodeGaitHash, encodeGaitHash, hasGait } from '../share/link';
import type { CharacterStatus } from '../sim/protocol';
import type { SimClient } from '../sim/sim-client';

/**
 * The quadruped's gaits. Walk and trot are whole gaits, each tuned by the optimiser for its own
 * footfall pattern (public/presets/quadruped.json is the trot, quadruped-walk.json the walk);
 * choosing one switches the running characters to it in mid-stride. Pace and bound are only
 * footfall patterns (Hildebrand's gait diagrams, as in the thesis's Figure 2.1: per leg the step
 * trigger, the phase of lift-off, and the duty factor) laid over the gait being edited; no gait
 * has been tuned for them, and they fall.
 */
const QUADRUPED_GAIT_FILES: Record<string, string> = { walk: 'presets/quadruped-walk.json', trot: 'presets/quadruped.json' };
const QUADRUPED_PATTERNS: Record<string, Record<string, [number, number]>> = {
  // Lateral pairs together.
  pace: { frontLeft: [0, 0.6], backLeft: [0, 0.6], frontRight: [0.5, 0.6], backRight: [0.5, 0.6] },
  // Fore pair, then hind pair.
  bound: { frontLeft: [0, 0.5], frontRight: [0, 0.5], backLeft: [0.5, 0.5], backRight: [0.5, 0.5] },
};
const QUADRUPED_GAITS = [...Object.keys(QUADRUPED_GAIT_FILES), ...Object.keys(QUADRUPED_PATTERNS)];

/** Undo steps kept per session. */
const UNDO_LIMIT = 100;

/**
 * The duty factor / step trigger pairs of the schema, one per leg: "<leg>.dutyFactor" and
 * "<leg>.stepTrigger" (the leg's name is the last part before them).
 */
function legTimings(entries: SchemaEntry[]): { leg: string; duty: SchemaEntry; trigger: SchemaEntry }[] {
  const out: { leg: string; duty: SchemaEntry; trigger: SchemaEntry }[] = [];
  for (const duty of entries) {
    if (!duty.name.endsWith('dutyFactor') || duty.knots !== 1) continue;
    const prefix = duty.name.slice(0, duty.name.length - 'dutyFactor'.length);
    const trigger = entries.find((e) => e.name === `${prefix}stepTrigger`);
    if (trigger) out.push({ leg: prefix.replace(/\.$/, '').split('.').pop() || prefix, duty, trigger });
  }
  return out;
}

export class GaitSession {
  /** The editors, folded into their heading unless a character is selected (or the user opens them). */
  private readonly editorsPanel: HTMLDetailsElement;
  private readonly heading: HTMLElement;
  private readonly content: HTMLElement;
  /** What is edited: one character, or every character of a type. */
  private target: { id: number | 'all'; character: CharacterType } = { id: 'all', character: 'biped' };
  private gait: GaitFile | null = null;
  private undoStack: GaitFile[] = [];
  private redoStack: GaitFile[] = [];
  private curves = new Map<string, CurveEditor>();
  private diagram: GaitDiagram | null = null;
  private diagramLegs: ReturnType<typeof legTimings> = [];
  private scalarFolder: GUI | null = null;
  private readonly scalarValues: Record<string, number> = {};
  /** The character whose phase the markers show, and when its phase was reported. */
  private phaseSource: { phase: number; at: number; period: number } | null = null;
  /** Loads are asynchronous: only the newest may land. */
  private loadToken = 0;
  private readonly controls: { editType: CharacterType };
  private readonly shareInfo = { link: '' };

  /** A session for this build's schema, or null (with a note in the panel) if it has none. */
  static create(schemaJson: string | null, client: SimClient, folder: GUI, overlay: Overlay): GaitSession | null {
    let schema: ParamSchema | null = null;
    try {
      schema = schemaJson ? (JSON.parse(schemaJson) as ParamSchema) : null;
    } catch (error) {
      overlay.message(`The module's parameter schema could not be read (${String(error)}); gait editing is off.`, 'problem');
    }
    if (!schema || !schema.characters || !CHARACTER_TYPES.every((t) => Array.isArray(schema!.characters[t]))) {
      folder.$children.append(
        Object.assign(document.createElement('div'), {
          className: 'panel-note',
          textContent: 'Gait editing and sharing need the parameter schema (gl_schema_json), which this build of the module does not have yet.',
        }),
      );
      if (hasGait(location.hash)) overlay.message('This link carries a gait, but this build cannot read gaits yet; running with the presets.', 'problem');
      return null;
    }
    return new GaitSession(schema, client, folder, overlay);
  }

  private constructor(
    private readonly schema: ParamSchema,
    private readonly client: SimClient,
    private readonly folder: GUI,
    private readonly overlay: Overlay,
  ) {
    this.controls = { editType: 'biped' };
    folder
      .add(this.controls, 'editType', CHARACTER_TYPES as CharacterType[])
      .name('edit all of type')
      .onChange((t: CharacterType) => {
        if (this.target.id === 'all') void this.load({ id: 'all', character: t });
      });
    const pattern = { quadrupedGait: 'trot' };
    folder
      .add(pattern, 'quadrupedGait', QUADRUPED_GAITS)
      .name('quadruped gait')
      .onChange((name: string) => void this.setQuadrupedGait(name));
    folder.add({ undo: () => this.undo() }, 'undo').name('Undo');
    folder.add({ redo: () => this.redo() }, 'redo').name('Redo');
    folder.add({ reset: () => void this.resetToPreset() }, 'reset').name('Reset to preset');
    folder.add({ share: () => void this.share() }, 'share').name('Share');
    folder.add(this.shareInfo, 'link').name('link').disable();
    folder.add({ exportGait: () => this.exportFile() }, 'exportGait').name('Export JSON');
    folder.add({ importGait: () => this.importFile() }, 'importGait').name('Import JSON');

    this.editorsPanel = document.createElement('details');
    this.editorsPanel.className = 'editors';
    this.editorsPanel.setAttribute('aria-label', 'gait editors');
    this.heading = document.createElement('summary');
    this.heading.className = 'editors-heading';
    this.content = document.createElement('div');
    this.editorsPanel.append(this.heading, this.content);
    document.body.append(this.editorsPanel);

    window.addEventListener('keydown', (e) => {
      if (!(e.ctrlKey || e.metaKey) || e.target instanceof HTMLInputElement) return;
      if (e.key === 'z' && !e.shiftKey) this.undo();
      else if (e.key === 'y' || (e.key === 'z' && e.shiftKey) || e.key === 'Z') this.redo();
      else return;
      e.preventDefault();
    });

    void this.openLink().then(() => this.load(this.target));
    // A link pasted into the address bar of the open page changes only the hash: read it too.
    window.addEventListener('hashchange', () => {
      if (hasGait(location.hash)) void this.openLink().then(() => this.load(this.target));
    });
  }

  // ---- what is edited ----

  /** The selected character (or none: every character of the chosen type). */
  select(status: CharacterStatus | null): void {
    const target = status ? { id: status.id, character: status.type } : { id: 'all' as const, character: this.controls.editType };
    // Open while a character is selected: selecting one is how people ask to edit it.
    this.editorsPanel.open = status !== null;
    if (target.id === this.target.id && target.character === this.target.character) return;
    void this.load(target);
  }

  /** The statistics report: the phase marker follows the selected character (or the first of the type). */
  tick(selected: CharacterStatus | null, all: CharacterStatus[] = []): void {
    this.characters = all;
    const source = selected ?? all.find((c) => c.type === this.target.character) ?? null;
    const period = typeof this.gait?.params.period === 'number' ? (this.gait.params.period as number) : 1;
    this.phaseSource = source ? { phase: source.phase, at: performance.now(), period } : null;
  }

  /**
   * Called every animation frame: the phase marker moves smoothly between the worker's reports.
   * Redrawn at most 20 times a second, and only in editors on screen (a folded group's are not):
   * a 2D canvas redraw is cheap, twenty of them every frame are not.
   */
  animate(running: boolean): void {
    const now = performance.now();
    if (now - this.lastMarker < 50) return;
    this.lastMarker = now;
    const s = this.phaseSource;
    const phase = s ? (s.phase + (running ? (now - s.at) / 1000 / s.period : 0)) % 1 : null;
    for (const c of this.curves.values()) if (c.element.offsetParent !== null) c.setPhase(phase);
    this.diagram?.setPhase(phase);
  }

  private lastMarker = 0;
  /** The crowd as last reported. */
  private characters: CharacterStatus[] = [];

  /** The newest load, for those that must wait until the editors show their target. */
  private loading: Promise<void> = Promise.resolve();

  private load(target: { id: number | 'all'; character: CharacterType }): Promise<void> {
    this.loading = this.loadNow(target);
    return this.loading;
  }

  private async loadNow(target: { id: number | 'all'; character: CharacterType }): Promise<void> {
    const token = ++this.loadToken;
    this.target = target;
    try {
      // Every character of a type walks with the same gait unless one was edited alone: start
      // from the first one's (the preset only when there is none of that type).
      const first = this.characters.find((c) => c.type === target.character);
      const id = target.id === 'all' ? first?.id : target.id;
      const gait = id === undefined ? await this.preset(target.character) : await this.gaitOf(id);
      if (token !== this.loadToken) return;
      this.gait = gait;
      this.undoStack = [];
      this.redoStack = [];
      this.build();
    } catch (error) {
      if (token === this.loadToken) this.overlay.message(`Could not read the gait: ${error instanceof Error ? error.message : String(error)}`, 'problem');
    }
  }

  /** Character `id`'s gait as the simulation has it now. */
  async gaitOf(id: number): Promise<GaitFile> {
    return this.normalise(await this.client.getParams(id));
  }

  /** A type's preset gait, as the module has it. */
  presetOf(character: CharacterType): Promise<GaitFile> {
    return this.preset(character);
  }

  private async preset(character: CharacterType): Promise<GaitFile> {
    return this.normalise(await this.client.getPreset(character));
  }

  /** The module's JSON as a checked GaitFile (a bare params object is accepted too). */
  private normalise(json: string): GaitFile {
    const data = JSON.parse(json) as Record<string, unknown>;
    return parseGait(data, this.schema);
  }

  // ---- editing ----

  private entries(): SchemaEntry[] {
    return this.schema.characters[this.target.character];
  }

  private value(entry: SchemaEntry): ParamValue {
    return this.gait?.params[entry.name] ?? entry.default;
  }

  /** Rebuilds the editors for the current gait. */
  private build(): void {
    const entries = this.entries();
    const who = this.target.id === 'all' ? `every ${this.target.character}` : `${this.target.character} #${this.target.id}`;
    this.heading.textContent = `Gait of ${who}`;
    this.content.replaceChildren();
    this.curves.clear();

    this.diagramLegs = legTimings(entries);
    if (this.diagramLegs.length > 0) {
      const d = this.diagramLegs[0].duty;
      this.diagram = new GaitDiagram({
        legs: this.timings(),
        dutyBounds: [d.min, d.max],
        onEditStart: () => this.remember(),
        onChange: (legs, done) => {
          const params: Record<string, ParamValue> = {};
          legs.forEach((l, i) => {
            params[this.diagramLegs[i].duty.name] = l.dutyFactor;
            params[this.diagramLegs[i].trigger.name] = l.stepTrigger;
          });
          this.edit(params, done);
        },
      });
      this.content.append(this.diagram.element);
    } else {
      this.diagram = null;
    }

    // Motion graphs, grouped as the schema groups them, each group folded.
    const groups = new Map<string, SchemaEntry[]>();
    for (const e of entries) if (e.knots > 1) groups.set(e.group, [...(groups.get(e.group) ?? []), e]);
    let first = true;
    for (const [group, list] of groups) {
      const details = document.createElement('details');
      details.open = first;
      first = false;
      const summary = document.createElement('summary');
      summary.textContent = `${group} (${list.length} graph${list.length === 1 ? '' : 's'})`;
      details.append(summary);
      for (const e of list) {
        const editor = new CurveEditor({
          name: e.name,
          description: e.description,
          unit: e.unit,
          min: e.min,
          max: e.max,
          values: this.value(e) as number[],
          onEditStart: () => this.remember(),
          onChange: (values, done) => this.edit({ [e.name]: values }, done),
        });
        this.curves.set(e.name, editor);
        details.append(editor.element);
      }
      this.content.append(details);
    }

    // Scalars in the lil-gui panel, a sub-folder per group, descriptions as tooltips.
    this.scalarFolder?.destroy();
    this.scalarFolder = this.folder.addFolder('parameters');
    const sub = new Map<string, GUI>();
    const timingNames = new Set(this.diagramLegs.flatMap((l) => [l.duty.name, l.trigger.name]));
    for (const e of entries) {
      if (e.knots !== 1 || timingNames.has(e.name)) continue;
      let f = sub.get(e.group);
      if (!f) {
        f = this.scalarFolder.addFolder(e.group).close();
        sub.set(e.group, f);
      }
      this.scalarValues[e.name] = this.value(e) as number;
      const c = f
        .add(this.scalarValues, e.name, e.min, e.max)
        .name(e.name.split('.').slice(-2).join('.') + (e.unit ? ` (${e.unit})` : ''))
        .onChange((v: number) => this.edit({ [e.name]: v }, false))
        .onFinishChange((v: number) => this.edit({ [e.name]: v }, true));
      c.domElement.title = `${e.name}: ${e.description}`;
      // A drag of a slider is one undo step: remember the state when it starts.
      c.domElement.addEventListener('pointerdown', () => this.remember(), { capture: true });
      c.domElement.addEventListener('focusin', () => this.remember());
    }
    this.scalarFolder.close();
  }

  private timings(): LegTiming[] {
    return this.diagramLegs.map((l) => ({
      leg: l.leg,
      dutyFactor: this.value(l.duty) as number,
      stepTrigger: this.value(l.trigger) as number,
    }));
  }

  /** Shows the current gait in every editor (after undo, redo, a preset, an import). */
  private refresh(): void {
    for (const e of this.entries()) {
      const v = this.value(e);
      if (e.knots > 1) this.curves.get(e.name)?.set(v as number[]);
      else if (e.name in this.scalarValues) this.scalarValues[e.name] = v as number;
    }
    this.scalarFolder?.controllersRecursive().forEach((c) => c.updateDisplay());
    this.diagram?.set(this.timings());
  }

  /** Keeps the state before an edit for undo (once per gesture). */
  private remember(): void {
    if (!this.gait) return;
    // One gesture can announce itself twice (a slider's press and its focus): keep one step.
    const top = this.undoStack[this.undoStack.length - 1];
    if (top && sameParams(top, this.gait)) return;
    this.undoStack.push(structuredClone(this.gait));
    if (this.undoStack.length > UNDO_LIMIT) this.undoStack.shift();
    this.redoStack = [];
  }

  /** Applies changed parameters live; `done` ends a gesture. */
  private edit(params: Record<string, ParamValue>, done: boolean): void {
    if (!this.gait) return;
    this.gait = { ...this.gait, params: { ...this.gait.params, ...params } };
    this.apply(this.gait);
    if (done) this.shareInfo.link = '';
  }

  /** Sends a gait to the simulation: to the target character, or to every character of its type. */
  private apply(gait: GaitFile): void {
    this.client.send({
      type: 'scene',
      command: { type: 'setParams', id: this.target.id, character: gait.character, json: JSON.stringify(gait) },
    });
  }

  undo(): void {
    const previous = this.undoStack.pop();
    if (!previous || !this.gait) return;
    this.redoStack.push(this.gait);
    this.gait = previous;
    this.apply(previous);
    this.refresh();
  }

  redo(): void {
    const next = this.redoStack.pop();
    if (!next || !this.gait) return;
    this.undoStack.push(this.gait);
    this.gait = next;
    this.apply(next);
    this.refresh();
  }

  private async resetToPreset(): Promise<void> {
    const preset = await this.preset(this.target.character);
    this.remember();
    this.gait = preset;
    this.apply(preset);
    this.refresh();
  }

  /** Replaces the edited gait by one from outside (a file; links go to every character of the type). */
  private adopt(gait: GaitFile): void {
    if (gait.character !== this.target.character) {
      // A quadruped's gait cannot drive a biped: edit every character of the gait's type instead.
      this.target = { id: 'all', character: gait.character };
      this.controls.editType = gait.character;
      this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
      this.gait = gait;
      this.build();
    } else {
      this.remember();
      this.gait = gait;
      this.refresh();
    }
    this.apply(this.gait!);
  }

  /**
   * Gives `gait` to character `id`, or to every character of its type ('all'), as an edit: the
   * editors switch to that target and show it, and undo brings back what it had before. (The
   * optimize panel's Apply; the caller selects the character, or deselects for 'all', first.)
   */
  async applyGait(gait: GaitFile, id: number | 'all'): Promise<void> {
    const wanted = { id, character: gait.character };
    if (this.target.id !== wanted.id || this.target.character !== wanted.character) {
      if (id === 'all') {
        this.controls.editType = gait.character;
        this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
      }
      await this.load(wanted);
    } else {
      // A load of this target may be in flight (a selection just changed): let it land first,
      // or it would overwrite the gait and clear the undo history after this edit.
      await this.loading;
    }
    if (this.target.id !== wanted.id || this.target.character !== wanted.character || !this.gait) {
      throw new Error('the selection changed while the gait was being applied');
    }
    this.remember();
    this.gait = structuredClone(gait);
    this.shareInfo.link = '';
    this.refresh();
    this.apply(this.gait);
  }

  /**
   * Sets a footfall pattern's step triggers and duty factors: on the selected character if it is
   * a quadruped, otherwise on every quadruped.
   */
  private async setQuadrupedGait(name: string): Promise<void> {
    if (this.target.character !== 'quadruped') {
      this.controls.editType = 'quadruped';
      this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
      await this.load({ id: 'all', character: 'quadruped' });
    }
    if (name in QUADRUPED_GAIT_FILES) {
      let gait: GaitFile;
      try {
        gait = await this.gaitFromServer(QUADRUPED_GAIT_FILES[name]);
      } catch (error) {
        this.overlay.message(`The ${name} gait could not be loaded: ${error instanceof Error ? error.message : String(error)}`, 'problem');
        return;
      }
      this.remember();
      this.gait = gait;
      this.apply(gait);
      this.refresh();
      return;
    }
    const pattern = QUADRUPED_PATTERNS[name];
    if (!pattern) return;
    const params: Record<string, ParamValue> = {};
    for (const l of this.diagramLegs) {
      const timing = pattern[l.leg];
      if (!timing) continue;
      params[l.trigger.name] = timing[0];
      params[l.duty.name] = Math.min(l.duty.max, Math.max(l.duty.min, timing[1]));
    }
    this.remember();
    this.edit(params, true);
    this.refresh();
  }

  /** A gait file shipped beside the page (public/), checked like any gait from outside. */
  private async gaitFromServer(file: string): Promise<GaitFile> {
    const response = await fetch(new URL(file, document.baseURI));
    if (!response.ok) throw new Error(`${file}: HTTP ${response.status}`);
    return parseGait(await response.json(), this.schema);
  }

  // ---- sharing ----

  /** A link to this page that carries character `id`'s gait. */
  async shareUrl(id: number): Promise<string> {
    const gait = await this.gaitOf(id);
    return `${location.origin}${location.pathname}${location.search}${await encodeGaitHash(gait)}`;
  }

  private async share(): Promise<void> {
    if (!this.gait) return;
    const url = `${location.origin}${location.pathname}${location.search}${await encodeGaitHash(this.gait)}`;
    this.shareInfo.link = url;
    this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
    let copied = false;
    try {
      await navigator.clipboard.writeText(url);
      copied = true;
    } catch {
      // No clipboard permission (an insecure origin, a headless browser): the link is in the panel.
    }
    // replaceState changes the hash without a hashchange event: the page does not re-read its own link.
    history.replaceState(null, '', url);
    this.overlay.message(`${copied ? 'Link copied' : 'Link ready (copy it from the address bar)'}: ${url.length} characters.`);
  }

  /**
   * A gait in the page's link, applied to every character of its type; a bad link is refused with
   * a message saying what was wrong, and the presets run.
   */
  private async openLink(): Promise<void> {
    if (!hasGait(location.hash)) return;
    try {
      const gait = await decodeGaitHash(location.hash, this.schema);
      this.target = { id: 'all', character: gait.character };
      this.controls.editType = gait.character;
      this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
      this.client.send({ type: 'scene', command: { type: 'setParams', id: 'all', character: gait.character, json: JSON.stringify(gait) } });
      this.overlay.message(`Shared ${gait.character} gait loaded from the link; every ${gait.character} walks with it.`);
    } catch (error) {
      const text = error instanceof GaitError ? error.message : `unexpected problem (${String(error)})`;
      this.overlay.message(`The gait link was refused: ${text}. Running with the presets.`, 'problem');
    }
  }

  private exportFile(): void {
    if (!this.gait) return;
    const file: GaitFile = { ...this.gait, meta: { ...(this.gait.meta ?? {}), exportedBy: 'gaitlab demo', exportedAt: new Date().toISOString() } };
    const blob = new Blob([`${JSON.stringify(file, null, 2)}\n`], { type: 'application/json' });
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = `${this.gait.character}-gait.json`;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  private importFile(): void {
    const input = document.createElement('input');
    input.type = 'file';
    input.accept = 'application/json,.json';
    input.addEventListener('change', async () => {
      const file = input.files?.[0];
      if (!file) return;
      try {
        const gait = parseGait(JSON.parse(await file.text()), this.schema);
        this.adopt(gait);
        this.overlay.message(`Imported ${file.name}.`);
      } catch (error) {
        const text = error instanceof GaitError ? error.message : error instanceof SyntaxError ? 'it is not JSON' : String(error);
        this.overlay.message(`${file.name} was not imported: ${text}.`, 'problem');
      }
    });
    // Tests find the input this way (a file chooser needs a user gesture otherwise).
    input.dataset.testid = 'import-gait';
    input.click();
  }
}
