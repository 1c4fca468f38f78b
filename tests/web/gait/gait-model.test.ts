// The gait model (web/src/gait/gait-model.ts): edits are patches, shown at once and kept in step
// with what the simulation accepted; a refused edit is taken back (and the edits after it kept);
// undo and redo are patches too and restore exactly the remembered gait.
import { describe, expect, it } from 'vitest';
import { CHARACTER_TYPES, isCharacterType, kindOf, typeOfKind } from '../../../web/src/gait/character';
import { GaitModel, UNDO_LIMIT, type GaitTarget } from '../../../web/src/gait/gait-model';
import { patched, presetGait, sameParams, type GaitFile, type ParamPatch, type SpeedKeys } from '../../../web/src/share/gait-file';
import { schema } from '../fixtures/schema';

/**
 * A stand-in simulation: keeps a gait, applies patches in order as the worker does (checking each
 * value against the fixture schema's bounds, all or nothing) and answers when told to.
 */
class FakeSimulation {
  gait: GaitFile;
  readonly sent: { target: GaitTarget; patch: ParamPatch; speedKeys?: SpeedKeys }[] = [];
  private queue: { patch: ParamPatch; speedKeys?: SpeedKeys; resolve: () => void; reject: (e: Error) => void }[] = [];

  constructor(gait: GaitFile) {
    this.gait = structuredClone(gait);
  }

  send = (target: GaitTarget, patch: ParamPatch, speedKeys?: SpeedKeys): Promise<void> => {
    this.sent.push({ target, patch: structuredClone(patch), ...(speedKeys ? { speedKeys: structuredClone(speedKeys) } : {}) });
    return new Promise((resolve, reject) => this.queue.push({ patch: structuredClone(patch), speedKeys, resolve, reject }));
  };

  /** Applies every queued patch in order, answering each. */
  async answer(): Promise<void> {
    const queue = this.queue;
    this.queue = [];
    for (const { patch, speedKeys, resolve, reject } of queue) {
      const entries = new Map(schema.characters[this.gait.character].map((e) => [e.name, e]));
      const bad = Object.entries(patch).find(([name, v]) => {
        const e = entries.get(name);
        return !e || (Array.isArray(v) ? v : [v]).some((x) => x < e.min || x > e.max);
      });
      if (bad) reject(new Error(`the edit (patchParams) was refused: ${bad[0]}: ${String(bad[1])} is outside`));
      else {
        this.gait = patched(this.gait, patch, speedKeys);
        resolve();
      }
    }
    await new Promise((r) => setTimeout(r, 0));
  }
}

function setUp() {
  const preset = presetGait(schema, 'biped');
  const sim = new FakeSimulation(preset);
  const changes: GaitFile[] = [];
  const refusals: string[] = [];
  const model = new GaitModel(sim.send, { changed: (g) => changes.push(structuredClone(g)), refused: (m) => refusals.push(m) });
  model.load({ id: 3, character: 'biped' }, preset);
  return { preset, sim, model, changes, refusals };
}

describe('the gait model', () => {
  it('sends an edit as a patch of what changed, and shows it before the answer', async () => {
    const { sim, model } = setUp();
    model.remember();
    const done = model.edit({ 'legFrame.pitch': [0, 0.2, 0, -0.05] });
    expect(model.gait!.params['legFrame.pitch']).toEqual([0, 0.2, 0, -0.05]);
    expect(model.accepted!.params['legFrame.pitch']).toEqual([0, 0.05, 0, -0.05]);
    expect(sim.sent).toEqual([{ target: { id: 3, character: 'biped' }, patch: { 'legFrame.pitch': [0, 0.2, 0, -0.05] } }]);
    await sim.answer();
    expect(await done).toBeNull();
    expect(sameParams(model.accepted!, sim.gait)).toBe(true);
    expect(sameParams(model.gait!, sim.gait)).toBe(true);
  });

  it('takes a refused edit back, keeps the edits after it, and says why', async () => {
    const { preset, sim, model, changes, refusals } = setUp();
    model.remember();
    const bad = model.edit({ period: 9 });
    const good = model.edit({ 'gains.hipKp': 500 });
    expect(model.gait!.params.period).toBe(9);
    await sim.answer();
    expect(await bad).toMatch(/patchParams.*period/);
    expect(await good).toBeNull();
    expect(refusals).toHaveLength(1);
    expect(refusals[0]).toMatch(/period/);
    // The editor shows what the simulation has: the refused value gone, the accepted one kept.
    expect(model.gait!.params.period).toBe(preset.params.period);
    expect(model.gait!.params['gains.hipKp']).toBe(500);
    expect(sameParams(model.gait!, sim.gait)).toBe(true);
    expect(changes.at(-1)!.params.period).toBe(preset.params.period);
  });

  it('leaves no undo step for a gesture whose only edit was refused', async () => {
    const { sim, model } = setUp();
    model.remember();
    void model.edit({ period: 9 });
    await sim.answer();
    expect(model.canUndo).toBe(false);
  });

  it('undoes and redoes through the same patches, restoring the remembered gait exactly', async () => {
    const { preset, sim, model } = setUp();
    model.remember();
    void model.edit({ 'legFrame.pitch': [0, 0.1, 0, 0] });
    void model.edit({ 'legFrame.pitch': [0, 0.3, 0, 0] }); // the same drag: one undo step
    await sim.answer();
    const dragged = structuredClone(sim.gait);
    model.remember();
    void model.edit({ period: 1.5 });
    await sim.answer();
    const undone = model.undo();
    await sim.answer();
    expect(await undone).toBeNull();
    expect(sameParams(sim.gait, dragged)).toBe(true);
    void model.undo();
    await sim.answer();
    expect(sameParams(sim.gait, preset)).toBe(true);
    expect(sameParams(model.gait!, preset)).toBe(true);
    expect(model.canUndo).toBe(false);
    void model.redo();
    await sim.answer();
    expect(sameParams(sim.gait, dragged)).toBe(true);
    void model.redo();
    await sim.answer();
    expect(sim.gait.params.period).toBe(1.5);
    expect(model.canRedo).toBe(false);
    // Every one of them went to the simulation as a patch.
    expect(sim.sent.every((s) => s.target.id === 3)).toBe(true);
  });

  it('replaces the whole gait as one undoable edit, and refuses another type\'s gait', async () => {
    const { preset, sim, model } = setUp();
    const other = patched(preset, { period: 2, 'right.dutyFactor': 0.8 });
    void model.replace(other);
    await sim.answer();
    expect(sameParams(sim.gait, other)).toBe(true);
    void model.undo();
    await sim.answer();
    expect(sameParams(sim.gait, preset)).toBe(true);
    expect(await model.replace(presetGait(schema, 'quadruped'))).toMatch(/quadruped's gait cannot drive a biped/);
  });

  it('carries speed keys when it replaces the whole gait, and undo takes them back', async () => {
    const { preset, sim, model } = setUp();
    const keyed: GaitFile = { ...patched(preset, { period: 0.8 }), speed: 1.4, keys: [{ speed: 1.7, params: { ...preset.params, period: 0.6 } }] };
    void model.replace(keyed);
    await sim.answer();
    expect(sim.sent[0].speedKeys).toEqual({ speed: 1.4, keys: keyed.keys });
    expect(sameParams(sim.gait, keyed)).toBe(true);
    expect(sameParams(model.gait!, keyed)).toBe(true);
    // An edit leaves the keys alone; undo of the replace restores the gait without keys.
    void model.edit({ period: 0.9 });
    await sim.answer();
    expect(sim.sent[1].speedKeys).toBeUndefined();
    expect(sim.gait.keys).toEqual(keyed.keys);
    void model.undo();
    await sim.answer();
    expect(sameParams(sim.gait, preset)).toBe(true);
    expect(sim.gait.keys).toBeUndefined();
    expect(sameParams(sim.gait, keyed)).toBe(false);
  });

  it('ignores answers meant for the gait it edited before a load, and keeps a bounded history', async () => {
    const { preset, sim, model } = setUp();
    void model.edit({ period: 9 });
    model.load({ id: 'all', character: 'biped' }, preset);
    await sim.answer();
    expect(sameParams(model.gait!, preset)).toBe(true);
    for (let i = 0; i < UNDO_LIMIT + 10; i++) {
      model.remember();
      void model.edit({ period: 0.5 + i / 1000 });
    }
    await sim.answer();
    let undos = 0;
    while (model.canUndo) {
      void model.undo();
      undos++;
    }
    expect(undos).toBe(UNDO_LIMIT);
  });
});

describe('character types', () => {
  it('are numbered as the module numbers its kinds', () => {
    for (const t of CHARACTER_TYPES) {
      expect(kindOf(t)).toBe(schema.morphologies[t].kind);
      expect(typeOfKind(kindOf(t))).toBe(t);
    }
    expect(typeOfKind(2)).toBeNull(); // GL_KIND_BOX
    expect(isCharacterType('octopus')).toBe(false);
  });
});
