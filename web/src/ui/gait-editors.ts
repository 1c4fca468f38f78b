// The gait editors: curve editors for the motion graphs, the gait diagram (thesis Figure 2.1), a
// grouped panel of scalars and gains, and the Gait folder's buttons (undo, redo, reset to preset,
// the quadruped's gaits, share, export, import), all showing and editing one GaitModel
// (web/src/gait/gait-model.ts): the selected character's gait, or that of every character of a
// type. Gestures become patches; what the simulation refuses is taken back in the editors.
//
// Everything is driven by the parameter schema the module reports (gl_schema_json): names,
// groups, bounds, units, descriptions, and which leg or leg frame a parameter belongs to are
// never written out here. Gaits from outside go through GaitTransfer (gait-transfer.ts).
import { guardNumberController } from './field-check';
import type GUI from 'lil-gui';
import { CurveEditor } from './curve-editor';
import { GaitDiagram, type LegTiming } from './gait-diagram';
import type { GaitTransfer } from './gait-transfer';
import type { Overlay } from './overlay';
import { CHARACTER_TYPES, type CharacterType } from '../gait/character';
import { GaitModel, type GaitTarget } from '../gait/gait-model';
import { GaitError, speedKeysOf, type GaitFile, type ParamPatch, type ParamSchema, type ParamValue, type SchemaEntry, type SchemaLeg } from '../share/gait-file';
import type { CharacterStatus } from '../sim/protocol';
import type { SimClient } from '../sim/sim-client';

/**
 * The quadruped's gaits. The preset (public/presets/quadruped.json) chooses by speed: the walk
 * below 0.3 m/s, the trot above, changing in mid-stride (native/src/gait/gait_transition.h).
 * Walk, trot and pace pin one gait, each tuned by the optimiser for its own footfall pattern
 * (quadruped-walk.json, quadruped-trot.json, quadruped-pace.json); choosing one switches the
 * running characters to it in mid-stride. Bound is only a footfall pattern (Hildebrand's gait
 * diagrams, as in the thesis's Figure 2.1: per leg the step trigger, the phase of lift-off, and
 * the duty factor) laid over the gait being edited; no gait has been tuned for it, and it falls.
 * A pattern says per leg, from the schema's morphology (its leg frame and side), [step trigger,
 * duty factor].
 */
const QUADRUPED_BY_SPEED = 'by speed: walk, trot';
const QUADRUPED_GAIT_FILES: Record<string, string> = {
  [QUADRUPED_BY_SPEED]: 'presets/quadruped.json',
  walk: 'presets/quadruped-walk.json',
  trot: 'presets/quadruped-trot.json',
  pace: 'presets/quadruped-pace.json',
};
const QUADRUPED_PATTERNS: Record<string, (leg: SchemaLeg) => [number, number]> = {
  // Fore pair (the first leg frame's legs), then hind pair.
  bound: (leg) => [leg.legFrame === 0 ? 0 : 0.5, 0.5],
};
/** The choices as offered: the pattern no gait is tuned for is marked experimental (it falls). */
const QUADRUPED_GAITS: Record<string, string> = Object.fromEntries([
  ...Object.keys(QUADRUPED_GAIT_FILES).map((name) => [name, name]),
  ...Object.keys(QUADRUPED_PATTERNS).map((name) => [`${name} (experimental: falls)`, name]),
]);

/** A field for numbers: the knots' (type number) and lil-gui's number controllers' (text). */
function isNumberField(input: HTMLInputElement): boolean {
  return input.type === 'number' || input.closest('.lil-number') !== null;
}

/** A leg's gait-diagram parameters: its duty factor and step trigger entries (§3.1.1). */
interface DiagramLeg {
  leg: SchemaLeg;
  duty: SchemaEntry;
  trigger: SchemaEntry;
}

/** The duty factor and step trigger of each leg, found by the leg the schema gives them. */
function diagramLegs(schema: ParamSchema, character: CharacterType): DiagramLeg[] {
  const entries = schema.characters[character];
  const out: DiagramLeg[] = [];
  for (const leg of schema.morphologies[character].legs) {
    const duty = entries.find((e) => e.leg?.index === leg.index && e.field === 'dutyFactor');
    const trigger = entries.find((e) => e.leg?.index === leg.index && e.field === 'stepTrigger');
    if (duty && trigger) out.push({ leg, duty, trigger });
  }
  return out;
}

export class GaitEditors {
  /** The editors, folded into their heading unless a character is selected (or the user opens them). */
  private readonly editorsPanel: HTMLDetailsElement;
  private readonly heading: HTMLElement;
  private readonly content: HTMLElement;
  private readonly model: GaitModel;
  private curves = new Map<string, CurveEditor>();
  private diagram: GaitDiagram | null = null;
  private diagramLegs: DiagramLeg[] = [];
  private scalarFolder: GUI | null = null;
  private readonly scalarValues: Record<string, number> = {};
  /** The character whose phase the markers show, and when its phase was reported. */
  private phaseSource: { phase: number; at: number; period: number } | null = null;
  /** Loads are asynchronous: only the newest may land. */
  private loadToken = 0;
  private readonly controls: { editType: CharacterType };
  private readonly shareInfo = { link: '' };

  /** Editors for this build's schema, or null (with a note in the panel) if it has none. */
  static create(schemaJson: string | null, client: SimClient, transfer: GaitTransfer, folder: GUI, overlay: Overlay): GaitEditors | null {
    let schema: ParamSchema | null = null;
    try {
      schema = schemaJson ? (JSON.parse(schemaJson) as ParamSchema) : null;
    } catch (error) {
      overlay.message(`The module's parameter schema could not be read (${String(error)}); gait editing is off.`, 'problem');
    }
    if (!schema || !schema.characters || !schema.morphologies || !CHARACTER_TYPES.every((t) => Array.isArray(schema!.characters[t]))) {
      folder.$children.append(
        Object.assign(document.createElement('div'), {
          className: 'panel-note',
          textContent: 'Gait editing and sharing need the parameter schema (gl_schema_json), which this build of the module does not have yet.',
        }),
      );
      if (transfer.linkInPage()) overlay.message('This link carries a gait, but this build cannot read gaits yet; running with the presets.', 'problem');
      return null;
    }
    return new GaitEditors(schema, client, transfer, folder, overlay);
  }

  private constructor(
    private readonly schema: ParamSchema,
    private readonly client: SimClient,
    private readonly transfer: GaitTransfer,
    private readonly folder: GUI,
    private readonly overlay: Overlay,
  ) {
    this.model = new GaitModel((target, patch, speedKeys) => client.patchParams(target.id, target.character, patch, speedKeys), {
      changed: () => this.refresh(),
      refused: (message) => this.overlay.message(`${message}; the editors show the gait the simulation has.`, 'problem'),
    });
    this.controls = { editType: 'biped' };
    folder
      .add(this.controls, 'editType', [...CHARACTER_TYPES])
      .name('edit all of type')
      .onChange((t: CharacterType) => {
        if (this.model.target.id === 'all') void this.load({ id: 'all', character: t });
      });
    const pattern = { quadrupedGait: QUADRUPED_BY_SPEED };
    folder
      .add(pattern, 'quadrupedGait', QUADRUPED_GAITS)
      .name('quadruped gait')
      .onChange((name: string) => void this.setQuadrupedGait(name));
    folder.add({ undo: () => this.undo() }, 'undo').name('Undo');
    folder.add({ redo: () => this.redo() }, 'redo').name('Redo');
    folder.add({ reset: () => void this.resetToPreset() }, 'reset').name('Reset to preset');
    folder.add({ share: () => void this.share() }, 'share').name('Share');
    folder.add(this.shareInfo, 'link').name('link').disable();
    folder.add({ exportGait: () => this.model.gait && this.transfer.exportFile(this.model.gait) }, 'exportGait').name('Export JSON');
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
      // In a number field undo is the gait's too, as outside it (the field then shows the value
      // undone); a text field (the share link) keeps its own.
      if (!(e.ctrlKey || e.metaKey) || (e.target instanceof HTMLInputElement && !isNumberField(e.target))) return;
      if (e.key === 'z' && !e.shiftKey) this.undo();
      else if (e.key === 'y' || (e.key === 'z' && e.shiftKey) || e.key === 'Z') this.redo();
      else return;
      e.preventDefault();
    });

    const start: GaitTarget = { id: 'all', character: 'biped' };
    void this.openLink(start).then(() => this.load(start));
    // A link pasted into the address bar of the open page changes only the hash: read it too.
    window.addEventListener('hashchange', () => {
      if (!this.transfer.linkInPage()) return;
      const target = { ...this.model.target };
      void this.openLink(target).then(() => this.load(target));
    });
  }

  // ---- what is edited ----

  /** The selected character (or none: every character of the chosen type). */
  select(status: CharacterStatus | null): void {
    const target: GaitTarget = status ? { id: status.id, character: status.type } : { id: 'all', character: this.controls.editType };
    // Open while a character is selected: selecting one is how people ask to edit it.
    this.editorsPanel.open = status !== null;
    if (target.id === this.model.target.id && target.character === this.model.target.character && this.model.gait) return;
    void this.load(target);
  }

  /** The statistics report: the phase marker follows the selected character (or the first of the type). */
  tick(selected: CharacterStatus | null, all: CharacterStatus[] = []): void {
    this.characters = all;
    const source = selected ?? all.find((c) => c.type === this.model.target.character) ?? null;
    const period = this.model.gait?.params.period;
    this.phaseSource = source ? { phase: source.phase, at: performance.now(), period: typeof period === 'number' ? period : 1 } : null;
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

  private load(target: GaitTarget): Promise<void> {
    this.loading = this.loadNow(target);
    return this.loading;
  }

  private async loadNow(target: GaitTarget): Promise<void> {
    const token = ++this.loadToken;
    try {
      // Every character of a type walks with the same gait unless one was edited alone: start
      // from the first one's (the preset only when there is none of that type).
      const first = this.characters.find((c) => c.type === target.character);
      const id = target.id === 'all' ? first?.id : target.id;
      const gait = id === undefined ? await this.presetOf(target.character) : await this.gaitOf(id);
      if (token !== this.loadToken) return;
      this.model.load(target, gait);
      this.build();
    } catch (error) {
      if (token === this.loadToken) this.overlay.message(`Could not read the gait: ${error instanceof Error ? error.message : String(error)}`, 'problem');
    }
  }

  /** Character `id`'s gait as the simulation has it now (the module's own file: nothing to check). */
  async gaitOf(id: number): Promise<GaitFile> {
    return JSON.parse(await this.client.getParams(id)) as GaitFile;
  }

  /** A type's preset gait, as the module has it. */
  async presetOf(character: CharacterType): Promise<GaitFile> {
    return JSON.parse(await this.client.getPreset(character)) as GaitFile;
  }

  /** The gait the editors show (with edits still on their way to the simulation). */
  get editorGait(): GaitFile | null {
    return this.model.gait ? structuredClone(this.model.gait) : null;
  }

  // ---- editing ----

  private entries(): SchemaEntry[] {
    return this.schema.characters[this.model.target.character];
  }

  private value(entry: SchemaEntry): ParamValue {
    return this.model.gait?.params[entry.name] ?? entry.default;
  }

  /** Rebuilds the editors for the current gait. */
  private build(): void {
    const entries = this.entries();
    const { id, character } = this.model.target;
    this.heading.textContent = `Gait of ${id === 'all' ? `every ${character}` : `${character} #${id}`}`;
    this.content.replaceChildren();
    this.curves.clear();

    this.diagramLegs = diagramLegs(this.schema, character);
    if (this.diagramLegs.length > 0) {
      const d = this.diagramLegs[0].duty;
      this.diagram = new GaitDiagram({
        legs: this.timings(),
        dutyBounds: [d.min, d.max],
        onEditStart: () => this.model.remember(),
        onChange: (legs) => {
          // Only the legs whose timing moved: a drag changes one leg.
          const patch: ParamPatch = {};
          legs.forEach((l, i) => {
            const { duty, trigger } = this.diagramLegs[i];
            if (l.dutyFactor !== this.value(duty)) patch[duty.name] = l.dutyFactor;
            if (l.stepTrigger !== this.value(trigger)) patch[trigger.name] = l.stepTrigger;
          });
          this.edit(patch);
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
          onEditStart: () => this.model.remember(),
          onChange: (values) => this.edit({ [e.name]: values }),
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
      const owner = e.leg?.name ?? e.legFrame?.name;
      const c = f
        .add(this.scalarValues, e.name, e.min, e.max)
        .name(`${owner ? `${owner}.` : ''}${e.field}${e.unit ? ` (${e.unit})` : ''}`)
        .onChange((v: number) => this.edit({ [e.name]: v }));
      c.domElement.title = `${e.name}: ${e.description}`;
      guardNumberController(c, e.min, e.max, e.name);
      // A drag of a slider is one undo step: remember the state when it starts.
      c.domElement.addEventListener('pointerdown', () => this.model.remember(), { capture: true });
      c.domElement.addEventListener('focusin', () => this.model.remember());
    }
    this.scalarFolder.close();
  }

  private timings(): LegTiming[] {
    return this.diagramLegs.map((l) => ({
      leg: l.leg.name,
      dutyFactor: this.value(l.duty) as number,
      stepTrigger: this.value(l.trigger) as number,
    }));
  }

  /** Shows the model's gait in every editor (after undo, redo, a refused edit, a preset, an import). */
  private refresh(): void {
    for (const e of this.entries()) {
      const v = this.value(e);
      if (e.knots > 1) this.curves.get(e.name)?.set(v as number[], true);
      else if (e.name in this.scalarValues) this.scalarValues[e.name] = v as number;
    }
    this.scalarFolder?.controllersRecursive().forEach((c) => c.updateDisplay());
    this.diagram?.set(this.timings(), true);
  }

  /** An edit from a gesture: the editor already shows it; the model sends it as a patch. */
  edit(patch: ParamPatch): Promise<string | null> {
    if (Object.keys(patch).length === 0) return Promise.resolve(null);
    this.shareInfo.link = '';
    return this.model.edit(patch);
  }

  /**
   * An edit from outside the editors (the test hook): remembered for undo and shown at once in
   * every editor, as a gesture's would be; resolves with null or the simulation's refusal.
   */
  editAsGesture(patch: ParamPatch): Promise<string | null> {
    this.model.remember();
    const result = this.edit(patch);
    this.refresh();
    return result;
  }

  undo(): Promise<string | null> {
    return this.model.undo();
  }

  redo(): Promise<string | null> {
    return this.model.redo();
  }

  private async resetToPreset(): Promise<void> {
    await this.model.replace(await this.presetOf(this.model.target.character));
  }

  /** Shows `target` in the editors (and the type chooser), loading its gait unless it is shown already. */
  private async show(target: GaitTarget): Promise<void> {
    if (target.id === 'all' && this.controls.editType !== target.character) {
      this.controls.editType = target.character;
      this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
    }
    if (this.model.target.id !== target.id || this.model.target.character !== target.character || !this.model.gait) {
      await this.load(target);
    } else {
      // A load of this target may be in flight (a selection just changed): let it land first,
      // or it would overwrite the gait and clear the undo history after this edit.
      await this.loading;
    }
    if (this.model.target.id !== target.id || this.model.target.character !== target.character || !this.model.gait) {
      throw new Error('the selection changed while the gait was being applied');
    }
  }

  /**
   * Gives `gait` to character `id`, or to every character of its type ('all'), as an edit: the
   * editors switch to that target and show it, and undo brings back what it had before. (The
   * optimize panel's Apply; the caller selects the character, or deselects for 'all', first.)
   * Rejects with the simulation's refusal.
   */
  async applyGait(gait: GaitFile, id: number | 'all'): Promise<void> {
    await this.show({ id, character: gait.character });
    this.shareInfo.link = '';
    const refusal = await this.model.replace(gait);
    if (refusal !== null) throw new Error(refusal);
  }

  /**
   * Sets a footfall pattern's step triggers and duty factors: on the selected character if it is
   * a quadruped, otherwise on every quadruped.
   */
  private async setQuadrupedGait(name: string): Promise<void> {
    if (this.model.target.character !== 'quadruped') await this.show({ id: 'all', character: 'quadruped' });
    if (name in QUADRUPED_GAIT_FILES) {
      let gait: GaitFile;
      try {
        gait = await this.transfer.fromServer(QUADRUPED_GAIT_FILES[name]);
      } catch (error) {
        this.overlay.message(`The ${name} gait could not be loaded: ${error instanceof Error ? error.message : String(error)}`, 'problem');
        return;
      }
      await this.model.replace(gait);
      return;
    }
    const pattern = QUADRUPED_PATTERNS[name];
    if (!pattern) return;
    const patch: ParamPatch = {};
    for (const l of this.diagramLegs) {
      const [trigger, duty] = pattern(l.leg);
      patch[l.trigger.name] = trigger;
      patch[l.duty.name] = Math.min(l.duty.max, Math.max(l.duty.min, duty));
    }
    this.model.remember();
    this.shareInfo.link = '';
    await this.model.edit(patch);
    this.refresh();
  }

  // ---- sharing ----

  /** A link to this page that carries character `id`'s gait. */
  async shareUrl(id: number): Promise<string> {
    return this.transfer.shareUrl(await this.gaitOf(id));
  }

  private async share(): Promise<void> {
    if (!this.model.gait) return;
    const { url, message } = await this.transfer.share(this.model.gait);
    this.shareInfo.link = url;
    this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
    // replaceState changes the hash without a hashchange event: the page does not re-read its own link.
    history.replaceState(null, '', url);
    this.overlay.message(message);
  }

  /**
   * A gait in the page's link, applied to every character of its type (and `target` set to edit
   * them); a bad link is refused with the module's message naming the field, and the presets run.
   */
  private async openLink(target: GaitTarget): Promise<void> {
    // A link with a creature's body carries that creature's gait: the page spawns it (main.ts).
    if (!this.transfer.linkInPage() || this.transfer.creatureInPage()) return;
    try {
      const gait = await this.transfer.readLink();
      Object.assign(target, { id: 'all', character: gait.character });
      this.controls.editType = gait.character;
      this.folder.controllersRecursive().forEach((c) => c.updateDisplay());
      // Every parameter, as one patch to every character of the type: the editors load the gait
      // once the simulation has it (the worker answers after applying it).
      await this.client.patchParams('all', gait.character, gait.params, speedKeysOf(gait));
      this.overlay.message(`Shared ${gait.character} gait loaded from the link; every ${gait.character} walks with it.`);
    } catch (error) {
      const text = error instanceof GaitError || error instanceof Error ? error.message : `unexpected problem (${String(error)})`;
      this.overlay.message(`The gait link was refused: ${text}. Running with the presets.`, 'problem');
    }
  }

  private importFile(): void {
    this.transfer.importFile(async (result) => {
      if ('problem' in result) {
        this.overlay.message(`${result.name} was not imported: ${result.problem}.`, 'problem');
        return;
      }
      const { gait, name } = result;
      try {
        // A quadruped's gait cannot drive a biped: edit every character of the gait's type instead.
        if (gait.character !== this.model.target.character) await this.show({ id: 'all', character: gait.character });
        const refusal = await this.model.replace(gait);
        if (refusal === null) this.overlay.message(`Imported ${name}.`);
      } catch (error) {
        this.overlay.message(`${name} was not imported: ${error instanceof Error ? error.message : String(error)}.`, 'problem');
      }
    });
  }
}
