// The gait being edited: one character's gait (or that of every character of a type), its edits
// and their undo history, kept in step with what the simulation accepted. No DOM: the editors
// (web/src/ui/gait-editors.ts) show it and turn gestures into edits.
//
// An edit is a patch ({parameter: value}), not a new gait: a dragged knot sends that one
// parameter to the simulation, which validates it against the schema (gl_sim_patch_params) and
// answers with acceptance or a refusal naming the parameter. The model shows its edits at once
// (the editor must follow the pointer) and keeps two gaits: `confirmed`, what the simulation has
// accepted, and the edits still on their way. A refused edit is dropped and the shown gait is
// recomputed from the confirmed one and the edits after it, so the editor never drifts from the
// simulation. Undo, redo and replacing the whole gait (a preset, an import) are patches too, of
// every parameter: they restore exactly the remembered gait whatever happened in between.
import type { CharacterType } from './character';
import { patched, sameParams, speedKeysOf, type GaitFile, type ParamPatch, type SpeedKeys } from '../share/gait-file';

/** What is edited: one character, or every character of a type. */
export interface GaitTarget {
  id: number | 'all';
  character: CharacterType;
}

/**
 * Sends a patch to the simulation, with the gait's speed keys when they are to be set too (a whole
 * gait); resolves with what it accepted, rejects with the refusal.
 */
export type PatchSender = (target: GaitTarget, patch: ParamPatch, speedKeys?: SpeedKeys) => Promise<ParamPatch | void>;

export interface GaitModelEvents {
  /** The shown gait changed for another reason than an edit the editors made themselves (undo, a refusal, a load). */
  changed(gait: GaitFile): void;
  /** The simulation refused an edit; the edit has been taken back. */
  refused(message: string): void;
}

/** Undo steps kept. */
export const UNDO_LIMIT = 100;

export class GaitModel {
  private targetNow: GaitTarget = { id: 'all', character: 'biped' };
  private confirmed: GaitFile | null = null;
  private pending: { seq: number; patch: ParamPatch; speedKeys?: SpeedKeys }[] = [];
  private shown: GaitFile | null = null;
  private undoStack: GaitFile[] = [];
  private redoStack: GaitFile[] = [];
  private seq = 0;
  /** Counts loads: answers to edits of an earlier target are not this target's. */
  private epoch = 0;

  constructor(
    private readonly send: PatchSender,
    private readonly events: GaitModelEvents,
  ) {}

  get target(): GaitTarget {
    return this.targetNow;
  }

  /** The gait as the editors show it: the accepted one with the edits still on their way. */
  get gait(): GaitFile | null {
    return this.shown;
  }

  /** The gait the simulation has accepted. */
  get accepted(): GaitFile | null {
    return this.confirmed;
  }

  get canUndo(): boolean {
    return this.undoStack.length > 0;
  }

  get canRedo(): boolean {
    return this.redoStack.length > 0;
  }

  /** Starts editing `target`, whose gait in the simulation is `gait`; the history starts over. */
  load(target: GaitTarget, gait: GaitFile): void {
    this.epoch++;
    this.targetNow = { ...target };
    this.confirmed = structuredClone(gait);
    this.shown = structuredClone(gait);
    this.pending = [];
    this.undoStack = [];
    this.redoStack = [];
  }

  /** Remembers the gait before a gesture for undo (once per gesture: a second call without a change keeps one step). */
  remember(): void {
    if (!this.shown) return;
    const top = this.undoStack[this.undoStack.length - 1];
    if (top && sameParams(top, this.shown)) return;
    this.undoStack.push(structuredClone(this.shown));
    if (this.undoStack.length > UNDO_LIMIT) this.undoStack.shift();
    this.redoStack = [];
  }

  /**
   * Changes some parameters: shown at once, sent to the simulation. Resolves with null when the
   * simulation accepted it, or with its refusal (reported through events.refused, and undone).
   */
  edit(patch: ParamPatch): Promise<string | null> {
    return this.submit(patch, () => {});
  }

  /** Replaces the whole gait by `gait` (a preset, an import, an optimiser's result) as one undoable edit. */
  replace(gait: GaitFile): Promise<string | null> {
    if (!this.shown) return Promise.resolve('there is no gait to replace yet');
    if (gait.character !== this.targetNow.character) {
      return Promise.resolve(`a ${gait.character}'s gait cannot drive a ${this.targetNow.character}`);
    }
    this.remember();
    return this.submit(gait.params, () => {}, true, speedKeysOf(gait));
  }

  /** Brings back the gait before the last gesture; resolves as edit() does (null when there was nothing to undo). */
  undo(): Promise<string | null> {
    const previous = this.undoStack.pop();
    if (!previous || !this.shown) return Promise.resolve(null);
    const current = this.shown;
    this.redoStack.push(current);
    return this.submit(previous.params, () => {
      // Refused: the history is as it was before the undo.
      this.redoStack.pop();
      this.undoStack.push(previous);
    }, true, speedKeysOf(previous));
  }

  redo(): Promise<string | null> {
    const next = this.redoStack.pop();
    if (!next || !this.shown) return Promise.resolve(null);
    const current = this.shown;
    this.undoStack.push(current);
    return this.submit(next.params, () => {
      this.undoStack.pop();
      this.redoStack.push(next);
    }, true, speedKeysOf(next));
  }

  private async submit(patch: ParamPatch, onRefused: () => void, notify = false, speedKeys?: SpeedKeys): Promise<string | null> {
    if (!this.shown || !this.confirmed) return 'there is no gait to edit yet';
    if (Object.keys(patch).length === 0) return null;
    const seq = ++this.seq;
    const epoch = this.epoch;
    this.pending.push({ seq, patch, speedKeys });
    this.shown = patched(this.shown, patch, speedKeys);
    if (notify) this.events.changed(this.shown);
    let accepted: ParamPatch | void;
    try {
      accepted = speedKeys ? await this.send(this.targetNow, patch, speedKeys) : await this.send(this.targetNow, patch);
    } catch (error) {
      const message = error instanceof Error ? error.message : String(error);
      if (epoch === this.epoch) {
        this.pending = this.pending.filter((p) => p.seq !== seq);
        this.recompute();
        onRefused();
        // A gesture whose only edit was refused leaves no undo step.
        const top = this.undoStack[this.undoStack.length - 1];
        if (top && this.shown && sameParams(top, this.shown)) this.undoStack.pop();
        this.events.changed(this.shown!);
      }
      this.events.refused(message);
      return message;
    }
    if (epoch === this.epoch) {
      // What the simulation says it took (the same values, as the worker answers).
      this.confirmed = patched(this.confirmed!, accepted ?? patch, speedKeys);
      this.pending = this.pending.filter((p) => p.seq !== seq);
    }
    return null;
  }

  private recompute(): void {
    if (!this.confirmed) return;
    this.shown = this.pending.reduce((g, p) => patched(g, p.patch, p.speedKeys), this.confirmed);
  }
}
