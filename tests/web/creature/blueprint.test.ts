import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { blueprint, dragTo, HANDLES, onSlider, type HandleName, type Point } from '../../../web/src/creature/blueprint';
import { buildFile, DEFAULT_DESIGN, designFromFile, SETTING_RANGES, type CreatureDesign } from '../../../web/src/creature/design';
import type { CreatureFile } from '../../../web/src/creature/creature-file';

const shipped = (name: string) => designFromFile(JSON.parse(readFileSync(`public/creatures/${name}.json`, 'utf8')) as CreatureFile);
const handle = (design: CreatureDesign, name: HandleName) => {
  const b = blueprint(design);
  const h = [...b.side.handles, ...b.top.handles].find((x) => x.name === name);
  if (!h) throw new Error(`no ${name} handle`);
  return h;
};
const near = (a: Point, b: Point) => {
  expect(a.x).toBeCloseTo(b.x, 6);
  expect(a.y).toBeCloseTo(b.y, 6);
};

describe('the blueprint', () => {
  it('draws every leg frame, its legs down to the ground, and a handle for each setting it stands for', () => {
    for (const name of ['insect', 'spider', 'dragon', 'quadruped', 'bird', 'biped']) {
      const design = shipped(name);
      const file = buildFile(design);
      const b = blueprint(design);
      expect(b.side.legs).toHaveLength(design.pairs);
      expect(b.top.legs).toHaveLength(2 * design.pairs);
      // A frame box for each leg frame and one for each spine section, in both views.
      expect(b.side.boxes).toHaveLength(design.pairs + file.spine.length);
      expect(b.top.boxes).toHaveLength(design.pairs + file.spine.length);
      for (const leg of b.side.legs) {
        // Hip, knee, (hock,) ankle; the ankle straight below the hip; the sole on the ground.
        expect(leg.joints).toHaveLength(design.tarsusLength > 0 ? 4 : 3);
        expect(leg.joints[leg.joints.length - 1].x).toBeCloseTo(leg.joints[0].x, 9);
        expect(leg.foot.centre.y - leg.foot.half.y).toBeCloseTo(b.side.ground!, 9);
        // Each segment as long as the file says.
        const lengths = [file.legFrames[0].legs.upper.length, file.legFrames[0].legs.lower.length, file.legFrames[0].legs.tarsus?.length];
        for (let k = 1; k < leg.joints.length; k++) {
          expect(Math.hypot(leg.joints[k].x - leg.joints[k - 1].x, leg.joints[k].y - leg.joints[k - 1].y)).toBeCloseTo(lengths[k - 1]!, 9);
        }
      }
      const names = [...b.side.handles, ...b.top.handles].map((h) => h.name);
      expect(names).toContain('knee');
      expect(names).toContain('ankle');
      expect(names.includes('hock')).toBe(design.tarsusLength > 0);
      expect(names.includes('frame')).toBe(design.pairs > 1);
      for (const h of [...b.side.handles, ...b.top.handles]) expect(HANDLES).toContain(h.name);
    }
  });

  it('bends each knee the way it points', () => {
    const forward = blueprint({ ...DEFAULT_DESIGN, knees: 'forward' }).side.legs;
    const backward = blueprint({ ...DEFAULT_DESIGN, knees: 'backward' }).side.legs;
    for (const leg of forward) expect(leg.joints[1].x).toBeGreaterThan(leg.joints[0].x);
    for (const leg of backward) expect(leg.joints[1].x).toBeLessThan(leg.joints[0].x);
  });
});

describe('dragging a handle', () => {
  it('puts it where it is dropped, for every handle of every shipped design', () => {
    for (const name of ['insect', 'spider', 'dragon', 'bird']) {
      const design = shipped(name);
      for (const h of [...blueprint(design).side.handles, ...blueprint(design).top.handles]) {
        // Dropped where it is, it changes nothing (but for the slider's step).
        const change = dragTo(design, h.name, h.at);
        expect(change[h.setting]).toBeCloseTo(onSlider(h.setting, design[h.setting]), 6);
      }
    }
  });

  it('sets the setting it stands for from where it is dropped', () => {
    const d = { ...DEFAULT_DESIGN };
    // The knee 0.3 m from the hip: the upper leg is 0.3 m.
    const hip = blueprint(d).side.legs[0].joints[0];
    expect(dragTo(d, 'knee', { x: hip.x, y: hip.y - 0.3 })).toEqual({ upperLength: 0.3 });
    // The ankle 0.25 m from the knee: the lower leg.
    const knee = handle(d, 'knee').at;
    expect(dragTo(d, 'ankle', { x: knee.x + 0.15, y: knee.y - 0.2 })).toEqual({ lowerLength: 0.25 });
    // The last frame 0.8 m behind the first, two spacings: 0.4 m apart.
    expect(dragTo(d, 'frame', { x: -0.8, y: 0 })).toEqual({ frameSpacing: 0.4 });
    // The top 0.27 m above the hips: hips are 3 cm above the underside, so 0.3 m tall.
    expect(dragTo(d, 'top', { x: 0, y: 0.27 })).toEqual({ bodyHeight: 0.3 });
    expect(dragTo(d, 'hip', { x: 0.15, y: 0 })).toEqual({ hipSpacing: 0.15 });
    expect(dragTo(d, 'side', { x: 0.2, y: 0 })).toEqual({ bodyWidth: 0.4 });
    // With a third segment, the hock sets the lower leg and the ankle the third segment.
    const bird = { ...d, tarsusLength: 0.1 };
    const hock = handle(bird, 'hock').at;
    expect(dragTo(bird, 'ankle', { x: hock.x, y: hock.y - 0.12 })).toEqual({ tarsusLength: 0.12 });
    expect(dragTo(bird, 'hock', { x: knee.x, y: knee.y - 0.3 })).toEqual({ lowerLength: 0.3 });
  });

  it('keeps to the slider: its steps and its range', () => {
    const d = { ...DEFAULT_DESIGN };
    const hip = blueprint(d).side.legs[0].joints[0];
    expect(dragTo(d, 'knee', { x: hip.x, y: hip.y - 0.2345 })).toEqual({ upperLength: 0.23 });
    expect(dragTo(d, 'knee', { x: hip.x, y: hip.y - 5 })).toEqual({ upperLength: SETTING_RANGES.upperLength.max });
    expect(dragTo(d, 'knee', hip)).toEqual({ upperLength: SETTING_RANGES.upperLength.min });
    expect(dragTo(d, 'frame', { x: 3, y: 0 })).toEqual({ frameSpacing: SETTING_RANGES.frameSpacing.min });
    // A handle the design does not have changes nothing.
    expect(dragTo({ ...d, pairs: 1 }, 'frame', { x: -1, y: 0 })).toEqual({});
    expect(dragTo(d, 'hock', { x: 0, y: -1 })).toEqual({});
  });

  it('moves the handle to where the setting puts it', () => {
    const d = { ...DEFAULT_DESIGN };
    const hip = blueprint(d).side.legs[0].joints[0];
    const changed = { ...d, ...dragTo(d, 'knee', { x: hip.x, y: hip.y - 0.3 }) };
    expect(Math.hypot(handle(changed, 'knee').at.x - hip.x, handle(changed, 'knee').at.y - hip.y)).toBeCloseTo(0.3, 9);
    const wider = { ...d, ...dragTo(d, 'hip', { x: 0.15, y: 0 }) };
    near(handle(wider, 'hip').at, { x: 0.15, y: 0 });
  });
});
