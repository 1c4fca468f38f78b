// The creature designer's model (web/src/creature/design.ts): settings to creature files, the
// shipped creatures to settings, and the checks that refuse a body before it is sent.
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { totalMass, type CreatureFile } from '../../../web/src/creature/creature-file';
import {
  buildFile,
  checkDesign,
  DEFAULT_DESIGN,
  designCreature,
  designFromFile,
  HIP_SWING_MIN,
  KNEE_FLEXION_MIN,
  LEG_SHARE_RANGE,
  MASS_PER_LEG,
  randomDesign,
  SETTING_RANGES,
  SINGLE_FRAME_INERTIA_MIN,
  stanceSweep,
  type CreatureDesign,
} from '../../../web/src/creature/design';

const shipped = (name: string): CreatureFile =>
  JSON.parse(fs.readFileSync(path.join(__dirname, '../../../public/creatures', `${name}.json`), 'utf8')) as CreatureFile;
const SHIPPED = ['insect', 'spider', 'dragon', 'bird', 'quadruped', 'biped'];

const settingsOf = (problems: { setting: string }[]) => problems.map((p) => p.setting);

/** Every number of a file within what the module's reader allows (native/src/body/creature.cpp). */
function expectReadable(file: CreatureFile): void {
  for (const f of file.legFrames) {
    for (const h of f.halfExtents) expect(h).toBeGreaterThanOrEqual(0.002);
    expect(f.mass).toBeGreaterThanOrEqual(0.01);
    for (const limb of [f.legs.upper, f.legs.lower, ...(f.legs.tarsus ? [f.legs.tarsus] : [])]) {
      expect(limb.length).toBeGreaterThanOrEqual(0.01);
      expect(limb.length).toBeLessThanOrEqual(2);
      expect(limb.halfThickness).toBeGreaterThanOrEqual(0.002);
      expect(limb.mass).toBeGreaterThanOrEqual(0.01);
    }
    for (const h of f.legs.foot.halfExtents) expect(h).toBeGreaterThanOrEqual(0.002);
    expect(f.legs.foot.mass).toBeGreaterThanOrEqual(0.01);
    expect(f.legs.hipSpacing).toBeLessThanOrEqual(1);
  }
  file.legFrames.forEach((f, k) => k > 0 && expect(f.z).toBeLessThan(file.legFrames[k - 1].z));
  expect(file.spine).toHaveLength(file.legFrames.length - 1);
  file.spine.forEach((s, k) => {
    expect(s.from).toBeLessThanOrEqual(file.legFrames[k].z);
    expect(s.to).toBeGreaterThanOrEqual(file.legFrames[k + 1].z);
    expect(s.to).toBeLessThan(s.from);
    expect(Number.isInteger(s.links) && s.links >= 1 && s.links <= 8).toBe(true);
    expect((s.from - s.to) / s.links / 2).toBeGreaterThanOrEqual(0.002);
  });
}

describe('creature designs', () => {
  it('start from the insect', () => {
    const insect = designFromFile(shipped('insect'));
    for (const [key, value] of Object.entries(DEFAULT_DESIGN)) {
      const read = insect[key as keyof CreatureDesign];
      if (typeof value === 'number') expect(read as number, key).toBeCloseTo(value, 9);
      else expect(read, key).toBe(value);
    }
  });

  it('read every shipped creature as settings that pass the checks', () => {
    for (const name of SHIPPED) {
      const design = designFromFile(shipped(name));
      expect(checkDesign(design), name).toEqual([]);
      expect(design.pairs, name).toBe(shipped(name).legFrames.length);
    }
  });

  it('give back the insect and the spider as shipped, but for their frames\' mean mass and the spine links\' mass', () => {
    for (const name of ['insect', 'spider']) {
      const file = shipped(name);
      const built = buildFile(designFromFile(file), name);
      expectReadable(built);
      const mean = file.legFrames.reduce((s, f) => s + f.mass, 0) / file.legFrames.length;
      built.legFrames.forEach((f, k) => {
        const original = file.legFrames[k];
        expect(f.mass).toBeCloseTo(mean, 5);
        expect({ ...f, mass: 0, legs: { ...f.legs, upper: { ...f.legs.upper, mass: 0 }, lower: { ...f.legs.lower, mass: 0 }, foot: { ...f.legs.foot, mass: 0 } } })
          .toEqual({ ...original, mass: 0, legs: { ...original.legs, upper: { ...original.legs.upper, mass: 0 }, lower: { ...original.legs.lower, mass: 0 }, foot: { ...original.legs.foot, mass: 0 } } });
        // The legs weigh what the shipped legs weigh (1.2, 0.6, 0.2 kg).
        expect(f.legs.upper.mass).toBeCloseTo(original.legs.upper.mass, 5);
        expect(f.legs.lower.mass).toBeCloseTo(original.legs.lower.mass, 5);
        expect(f.legs.foot.mass).toBeCloseTo(original.legs.foot.mass, 5);
      });
      built.spine.forEach((s, k) => expect({ ...s, mass: 0 }).toEqual({ ...file.spine[k], mass: 0 }));
      expect(totalMass(built)).toBeCloseTo(totalMass(file), -1);
    }
  });

  it('make readable files of 1 to 4 leg pairs, front to back, with a spine between each two', () => {
    for (let pairs = 1; pairs <= 4; pairs++) {
      const { file, problems } = designCreature({ ...DEFAULT_DESIGN, pairs, ...(pairs === 1 ? { upperLength: 0.42, lowerLength: 0.42, frameMass: 36, bodyWidth: 0.34, bodyHeight: 0.56 } : {}) });
      expect(problems, `${pairs} pairs`).toEqual([]);
      expect(file.format).toBe('gaitlab-creature');
      expect(file.version).toBe(3);
      expect(file.legFrames).toHaveLength(pairs);
      expectReadable(file);
      // Centred on the body's middle.
      expect(file.legFrames[0].z + file.legFrames[pairs - 1].z).toBeCloseTo(0, 9);
    }
  });

  it('bend the front half\'s knees backward when mixed, as the shipped bodies do', () => {
    const points = (pairs: number, knees: CreatureDesign['knees'] = 'mixed') =>
      buildFile({ ...DEFAULT_DESIGN, pairs, knees }).legFrames.map((f) => f.legs.knee.points);
    expect(points(2)).toEqual(['backward', 'forward']);
    expect(points(3)).toEqual(['backward', 'forward', 'forward']);
    expect(points(4)).toEqual(['backward', 'backward', 'forward', 'forward']);
    expect(points(4, 'backward')).toEqual(['backward', 'backward', 'backward', 'backward']);
    expect(points(3, 'forward')).toEqual(['forward', 'forward', 'forward']);
  });

  it('share the mass between a leg frame and its legs as the leg mass share says', () => {
    const file = buildFile({ ...DEFAULT_DESIGN, frameMass: 10, legShare: 0.25 });
    const f = file.legFrames[0];
    const pair = 2 * (f.legs.upper.mass + f.legs.lower.mass + f.legs.foot.mass);
    expect(pair / (pair + f.mass)).toBeCloseTo(0.25, 5);
    // Upper, lower and foot 0.6, 0.3, 0.1 of a leg.
    expect(f.legs.upper.mass / f.legs.lower.mass).toBeCloseTo(2, 5);
    expect(f.legs.lower.mass / f.legs.foot.mass).toBeCloseTo(3, 4);
  });
});

describe('legs of three segments', () => {
  it('get a tarsus with its hock, sharing the lower leg\'s mass by length; without one, none', () => {
    const file = buildFile({ ...DEFAULT_DESIGN, upperLength: 0.2, lowerLength: 0.15, tarsusLength: 0.1 });
    const legs = file.legFrames[1].legs;
    expect(file.version).toBe(3);
    expect(legs.tarsus).toBeDefined();
    expect(legs.tarsus!.length).toBe(0.1);
    expect(legs.tarsus!.hock).toEqual({ flexion: 2.4, hyperextension: 0.05 });
    expect(legs.lower.mass / legs.tarsus!.mass).toBeCloseTo(0.15 / 0.1, 4);
    // Upper 0.6, lower and tarsus together 0.3, foot 0.1 of a leg, as with two segments.
    expect(legs.upper.mass / (legs.lower.mass + legs.tarsus!.mass)).toBeCloseTo(2, 4);
    expect(legs.tarsus!.halfThickness).toBeLessThan(legs.lower.halfThickness);
    expect(buildFile(DEFAULT_DESIGN).legFrames[0].legs.tarsus).toBeUndefined();
  });

  it('read back from the bird, and count in the leg\'s length', () => {
    const bird = designFromFile(shipped('bird'));
    expect(bird.tarsusLength).toBe(0.18);
    expect(bird.pairs).toBe(1);
    expect(checkDesign(bird)).toEqual([]);
    // Without its tarsus the bird's legs (0.66 m) are too short for the biped's gait.
    expect(settingsOf(checkDesign({ ...bird, tarsusLength: 0 }))).toEqual(['lowerLength']);
  });

  it('refuse a third segment longer than the measured share of the leg', () => {
    const problems = checkDesign({ ...DEFAULT_DESIGN, upperLength: 0.2, lowerLength: 0.2, tarsusLength: 0.2 });
    expect(settingsOf(problems)).toEqual(['tarsusLength']);
    expect(problems[0].message).toMatch(/more than 0.3 of the leg/);
  });
});

describe('joint ranges', () => {
  it('read back from every shipped creature as the ranges they have', () => {
    for (const name of SHIPPED) {
      const design = designFromFile(shipped(name));
      expect(design.kneeFlexion, name).toBe(2.4);
      expect(design.hipSwing, name).toBeCloseTo(1.2, 6);
      // Built again, the hips and knees are the file's.
      const legs = buildFile(design).legFrames[0].legs;
      expect(legs.hip, name).toEqual(shipped(name).legFrames[0].legs.hip);
      expect(legs.knee.flexion, name).toBe(shipped(name).legFrames[0].legs.knee.flexion);
    }
  });

  it('set the knees\' and hocks\' flexion, and scale the hips\' swing (a single pair keeps the biped\'s shape of range)', () => {
    const insect = buildFile({ ...DEFAULT_DESIGN, kneeFlexion: 1.8, hipSwing: 0.9, tarsusLength: 0.05 });
    for (const f of insect.legFrames) {
      expect(f.legs.knee.flexion).toBe(1.8);
      expect(f.legs.tarsus?.hock.flexion).toBe(1.8);
      expect(f.legs.hip.lower).toEqual([-0.9, -0.3, -0.35]);
      expect(f.legs.hip.upper).toEqual([0.9, 0.3, 0.35]);
    }
    const biped = designFromFile(shipped('biped'));
    const hips = buildFile({ ...biped, hipSwing: 1.5 }).legFrames[0].legs.hip;
    expect(hips.lower[0]).toBeCloseTo(-2.5, 6);
    expect(hips.upper[0]).toBeCloseTo(0.875, 6);
    expect(designFromFile(buildFile({ ...biped, hipSwing: 1.5 })).hipSwing).toBeCloseTo(1.5, 6);
  });

  it('refuse knees that cannot fold and hips that cannot swing as far as the gait needs, by leg count', () => {
    const insect = DEFAULT_DESIGN;
    const biped = designFromFile(shipped('biped'));
    expect(settingsOf(checkDesign({ ...insect, kneeFlexion: KNEE_FLEXION_MIN.frames }))).toEqual([]);
    expect(settingsOf(checkDesign({ ...insect, kneeFlexion: KNEE_FLEXION_MIN.frames - 0.05 }))).toEqual(['kneeFlexion']);
    expect(settingsOf(checkDesign({ ...biped, kneeFlexion: KNEE_FLEXION_MIN.frames }))).toEqual(['kneeFlexion']);
    expect(settingsOf(checkDesign({ ...biped, kneeFlexion: KNEE_FLEXION_MIN.single }))).toEqual([]);
    expect(settingsOf(checkDesign({ ...insect, hipSwing: HIP_SWING_MIN.frames }))).toEqual([]);
    const problems = checkDesign({ ...insect, hipSwing: HIP_SWING_MIN.frames - 0.05 });
    expect(settingsOf(problems)).toEqual(['hipSwing']);
    expect(problems[0].message).toMatch(/cannot take the gait's steps/);
    expect(settingsOf(checkDesign({ ...biped, hipSwing: HIP_SWING_MIN.frames }))).toEqual(['hipSwing']);
    expect(settingsOf(checkDesign({ ...biped, hipSwing: HIP_SWING_MIN.single }))).toEqual([]);
  });
});

describe('a single pair', () => {
  it('stands on the biped\'s foot, scaled by its leg length', () => {
    const biped = designFromFile(shipped('biped'));
    expect(buildFile(biped).legFrames[0].legs.foot).toEqual({ ...shipped('biped').legFrames[0].legs.foot, mass: expect.any(Number) });
    const longer = buildFile({ ...biped, upperLength: 0.5, lowerLength: 0.5 }).legFrames[0].legs.foot;
    expect(longer.halfExtents[2]).toBeCloseTo(0.12 * (1.0 / 0.84), 6);
  });

  it('refuses a leg frame its legs would tip over: too flat, too short or too light', () => {
    const biped = designFromFile(shipped('biped'));
    expect(checkDesign(biped)).toEqual([]);
    const flat = checkDesign({ ...biped, bodyHeight: 0.15 });
    expect(settingsOf(flat)).toEqual(['bodyHeight']);
    expect(flat[0].message).toMatch(new RegExp(`at least ${SINGLE_FRAME_INERTIA_MIN} needed`));
    // Taller passes; the same frame for two pairs or more is not judged so (its spine and the other frames share the load).
    expect(checkDesign({ ...biped, bodyHeight: 0.3 })).toEqual([]);
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, bodyHeight: 0.08 }))).not.toContain('bodyHeight');
  });
});

describe('the design checks', () => {
  it('refuse leg frames closer than a foot sweeps plus its length (neighbouring legs would collide)', () => {
    const problems = checkDesign({ ...DEFAULT_DESIGN, frameSpacing: 0.12 });
    expect(settingsOf(problems)).toEqual(['frameSpacing']);
    expect(problems[0].message).toMatch(/legs of neighbouring leg frames would collide/);
    expect(problems[0].message).toMatch(/at least 0\.17\d* m apart/);
    // A single pair has no neighbours.
    expect(settingsOf(checkDesign({ ...designFromFile(shipped('biped')), frameSpacing: 0.1 }))).toEqual([]);
  });

  it('take the sweep from the gait: longer legs, a longer period (√L), a longer sweep', () => {
    const short = stanceSweep(DEFAULT_DESIGN);
    const long = stanceSweep({ ...DEFAULT_DESIGN, upperLength: 0.44, lowerLength: 0.44 });
    expect(long / short).toBeCloseTo(Math.SQRT2, 9);
    expect(short).toBeCloseTo(0.4 * 0.35 * 0.55, 9);
  });

  it('refuse hips outside the body, and left and right legs that would overlap', () => {
    const outside = checkDesign({ ...DEFAULT_DESIGN, hipSpacing: 0.2 });
    expect(settingsOf(outside)).toEqual(['hipSpacing']);
    expect(outside[0].message).toMatch(/the hips are outside the body: at most 0\.135 m/);
    const overlap = checkDesign({ ...DEFAULT_DESIGN, hipSpacing: 0.03 });
    expect(settingsOf(overlap)).toEqual(['hipSpacing']);
    expect(overlap[0].message).toMatch(/left and right legs would overlap/);
  });

  it('refuse a leg mass share outside the measured range', () => {
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, legShare: LEG_SHARE_RANGE.min - 0.01 }))).toEqual(['legShare']);
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, legShare: LEG_SHARE_RANGE.max + 0.01 }))).toContain('legShare');
    expect(checkDesign({ ...DEFAULT_DESIGN, legShare: LEG_SHARE_RANGE.min })).toEqual([]);
  });

  it('refuse a body too light or too heavy for its legs, saying its mass', () => {
    const heavy = checkDesign({ ...DEFAULT_DESIGN, frameMass: 40 });
    expect(settingsOf(heavy)).toEqual(['frameMass']);
    expect(heavy[0].message).toMatch(/the body weighs 197\.\d kg, 32\.\d kg a leg: each leg must carry 4\.5–20 kg/);
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, frameMass: 4 }))).toEqual(['frameMass']);
    // Within the range at both ends.
    const perLeg = (d: CreatureDesign) => totalMass(buildFile(d)) / (2 * d.pairs);
    expect(perLeg(DEFAULT_DESIGN)).toBeGreaterThan(MASS_PER_LEG.min);
    expect(perLeg(DEFAULT_DESIGN)).toBeLessThan(MASS_PER_LEG.max);
  });

  it('refuse legs too short or too long for the gait, and very unequal segments', () => {
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, upperLength: 0.14, lowerLength: 0.14 }))).toEqual(['lowerLength']);
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, upperLength: 0.4, lowerLength: 0.4, frameSpacing: 0.5, hipSpacing: 0.12 }))).toEqual(['upperLength']);
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, upperLength: 0.12, lowerLength: 0.3 }))).toEqual(['upperLength']);
  });

  it('refuse what is not a setting\'s value: out of range, not whole, not a colour, not a knee', () => {
    const problems = checkDesign({ ...DEFAULT_DESIGN, pairs: 5, knees: 'sideways' as CreatureDesign['knees'], leftColour: 'blue' });
    expect(settingsOf(problems)).toEqual(['pairs', 'knees', 'leftColour']);
    expect(problems[0].message).toBe(`leg pairs: 5 is outside [1, ${SETTING_RANGES.pairs.max}]`);
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, pairs: 2.5 }))).toEqual(['pairs']);
    expect(settingsOf(checkDesign({ ...DEFAULT_DESIGN, upperLength: Number.NaN }))).toEqual(['upperLength']);
  });

  it('accept every shipped creature, and its body with any leg count from 2 to 4', () => {
    for (const name of ['insect', 'spider', 'dragon', 'quadruped']) {
      for (let pairs = 2; pairs <= 4; pairs++) expect(checkDesign({ ...designFromFile(shipped(name)), pairs }), `${name} × ${pairs}`).toEqual([]);
    }
  });
});

describe('random designs', () => {
  it('are within the designer\'s limits, pass every check, differ, and repeat for a seed', () => {
    const designs = Array.from({ length: 20 }, (_, k) => randomDesign(k + 1));
    for (const d of designs) {
      expect(checkDesign(d)).toEqual([]);
      for (const [key, r] of Object.entries(SETTING_RANGES)) {
        const value = d[key as keyof typeof SETTING_RANGES];
        expect(value).toBeGreaterThanOrEqual(r.min);
        expect(value).toBeLessThanOrEqual(r.max);
      }
    }
    expect(new Set(designs.map((d) => JSON.stringify(d))).size).toBe(20);
    expect(randomDesign(7)).toEqual(designs[6]);
    // Every number of leg pairs turns up among 20.
    expect(new Set(designs.map((d) => d.pairs)).size).toBeGreaterThan(1);
    // Legs of two segments and of three both turn up.
    expect(designs.some((d) => d.tarsusLength === 0)).toBe(true);
    expect(designs.some((d) => d.tarsusLength > 0)).toBe(true);
  });
});
