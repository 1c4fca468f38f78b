// The gait link codec (web/src/share): round trips, and every kind of bad link refused with the
// problem named — never a crash and never a silently different gait.
import { describe, expect, it } from 'vitest';
import {
  GaitError,
  MIGRATIONS,
  parseGait,
  presetGait,
  sameParams,
  type GaitFile,
  type GaitProblem,
} from '../../../web/src/share/gait-file';
import { crc32, decodeGaitHash, encodeGaitHash, fromBase64Url, hasGait, MAX_LINK_CHARS, toBase64Url } from '../../../web/src/share/link';
import { schema } from '../fixtures/schema';

/** The problem decoding `hash` reports (fails the test if it decodes). */
async function problemOf(hash: string, migrations = {}): Promise<{ problem: GaitProblem; message: string }> {
  try {
    await decodeGaitHash(hash, schema, migrations);
  } catch (error) {
    expect(error).toBeInstanceOf(GaitError);
    return { problem: (error as GaitError).problem, message: (error as GaitError).message };
  }
  throw new Error(`${hash.slice(0, 60)}… decoded without complaint`);
}

/** A seeded generator (mulberry32), so a failing random case can be reproduced. */
function random(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** A random valid gait: every parameter anywhere in its bounds, including exactly on them. */
function randomGait(next: () => number): GaitFile {
  const character = next() < 0.5 ? 'biped' : 'quadruped';
  const gait = presetGait(schema, character);
  for (const e of schema.characters[character]) {
    const value = () => {
      const r = next();
      return r < 0.05 ? e.min : r > 0.95 ? e.max : e.min + (e.max - e.min) * next();
    };
    gait.params[e.name] = e.knots === 1 ? value() : Array.from({ length: e.knots }, value);
  }
  return gait;
}

/** Rewrites a link's data: decode, change the JSON, re-encode with a correct checksum. */
async function relink(edit: (gait: Record<string, unknown>) => void): Promise<string> {
  const gait = presetGait(schema, 'biped') as unknown as Record<string, unknown>;
  edit(gait);
  // encodeGaitHash only serialises; it does not validate, which is what these tests need.
  return encodeGaitHash(gait as unknown as GaitFile);
}

describe('gait links', () => {
  it('round-trip the presets exactly', async () => {
    for (const character of ['biped', 'quadruped'] as const) {
      const gait = presetGait(schema, character);
      const hash = await encodeGaitHash(gait);
      expect(hash).toMatch(/^#gait=1\.\d+\.[A-Za-z0-9_-]+$/);
      expect(hasGait(hash)).toBe(true);
      const back = await decodeGaitHash(hash, schema);
      expect(sameParams(back, gait)).toBe(true);
      expect(back.character).toBe(character);
    }
  });

  it('round-trip random gaits bit for bit', async () => {
    const next = random(12345);
    for (let i = 0; i < 200; i++) {
      const gait = randomGait(next);
      const back = await decodeGaitHash(await encodeGaitHash(gait), schema);
      expect(sameParams(back, gait), `case ${i}`).toBe(true);
    }
  });

  it('keep links short', async () => {
    const hash = await encodeGaitHash(randomGait(random(7)));
    expect(hash.length).toBeLessThan(600);
  });

  it('are not confused by other keys in the hash', async () => {
    const hash = await encodeGaitHash(presetGait(schema, 'biped'));
    const back = await decodeGaitHash(`#view=top&${hash.slice(1)}&x=1`, schema);
    expect(back.character).toBe('biped');
    expect(hasGait('#view=top')).toBe(false);
    expect(hasGait('')).toBe(false);
  });

  it('refuse a truncated link wherever it was cut', async () => {
    const hash = await encodeGaitHash(presetGait(schema, 'quadruped'));
    const dataStart = hash.lastIndexOf('.') + 1;
    // Cut inside the data, right after the version, inside the length, and the empty value.
    for (const cut of [hash.length - 1, dataStart + 3, dataStart, dataStart - 1, '#gait=1.'.length, '#gait=1'.length, '#gait='.length]) {
      const { problem, message } = await problemOf(hash.slice(0, cut));
      expect(problem, `cut at ${cut}`).toBe('truncated');
      expect(message).toMatch(/truncated/);
    }
  });

  it('refuse corrupt data', async () => {
    const hash = await encodeGaitHash(presetGait(schema, 'biped'));
    const dataStart = hash.lastIndexOf('.') + 1;
    // Flip one character of the data at many positions: the checksum or inflate must notice.
    for (let i = dataStart; i < hash.length; i += 3) {
      const c = hash[i] === 'A' ? 'B' : 'A';
      const { problem } = await problemOf(hash.slice(0, i) + c + hash.slice(i + 1));
      expect(problem, `flip at ${i}`).toBe('corrupt');
    }
    expect((await problemOf(hash.slice(0, dataStart) + '!' + hash.slice(dataStart + 1))).message).toMatch(/base64url/);
    expect((await problemOf(`${hash}AB`)).problem).toBe('corrupt'); // longer than declared
    expect((await problemOf('#gait=hello')).problem).toBe('corrupt');
    // Valid base64url and checksum over bytes that are not deflate data at all.
    const junk = new Uint8Array([0, 0, 0, 0, 0xff, 0xff, 0xff, 0xff]);
    const data = toBase64Url(junk);
    expect((await problemOf(`#gait=1.${data.length}.${data}`)).problem).toBe('corrupt');
  });

  it('refuse JSON that is not a gait, with the reason', async () => {
    const cases: [(g: Record<string, unknown>) => void, RegExp][] = [
      [(g) => (g.format = 'something-else'), /not a gait file/],
      [(g) => (g.character = 'octopus'), /"character"/],
      [(g) => (g.params = [1, 2]), /"params"/],
      [(g) => ((g.params as Record<string, unknown>)['no.such.param'] = 1), /unknown parameter "no\.such\.param"/],
      [(g) => ((g.params as Record<string, unknown>).period = '0.8'), /period must be a number/],
      [(g) => ((g.params as Record<string, unknown>)['legFrame.pitch'] = [0, 0, 0]), /legFrame\.pitch must be a list of 4/],
      [(g) => ((g.params as Record<string, unknown>)['legFrame.pitch'] = 0.1), /legFrame\.pitch must be a list of 4/],
    ];
    for (const [edit, message] of cases) {
      const { problem, message: text } = await problemOf(await relink(edit));
      expect(problem).toBe('invalid');
      expect(text).toMatch(message);
    }
  });

  it('refuse values out of bounds, naming the parameter and its bounds', async () => {
    const { problem, message } = await problemOf(await relink((g) => ((g.params as Record<string, number>).period = 7.5)));
    expect(problem).toBe('out-of-bounds');
    expect(message).toBe('period = 7.5 is out of bounds (0.2 to 3 s)');
    const knot = await problemOf(await relink((g) => ((g.params as Record<string, number[]>)['legFrame.stepHeight'] = [0, 0.1, -0.01, 0])));
    expect(knot.problem).toBe('out-of-bounds');
    expect(knot.message).toMatch(/legFrame\.stepHeight = -0\.01/);
  });

  it('refuse values that are not finite', async () => {
    // JSON.stringify writes Infinity as null, so the link is made by hand: 1e999 parses to Infinity.
    const json = JSON.stringify(presetGait(schema, 'biped')).replace('"period":0.8', '"period":1e999');
    const text = new TextEncoder().encode(json);
    const packed = new Uint8Array(await new Response(new Blob([text]).stream().pipeThrough(new CompressionStream('deflate-raw'))).arrayBuffer());
    const bytes = new Uint8Array(4 + packed.length);
    new DataView(bytes.buffer).setUint32(0, crc32(text));
    bytes.set(packed, 4);
    const data = toBase64Url(bytes);
    const { problem, message } = await problemOf(`#gait=1.${data.length}.${data}`);
    expect(problem).toBe('not-finite');
    expect(message).toMatch(/period is not a finite number/);
  });

  it('refuse links that are too long, before decompressing them', async () => {
    const data = 'A'.repeat(MAX_LINK_CHARS + 100);
    expect((await problemOf(`#gait=1.${data.length}.${data}`)).problem).toBe('too-long');
    // A short link that would inflate to a huge JSON.
    const huge = new TextEncoder().encode(' '.repeat(4 << 20));
    const packed = new Uint8Array(await new Response(new Blob([huge]).stream().pipeThrough(new CompressionStream('deflate-raw'))).arrayBuffer());
    const bytes = new Uint8Array(4 + packed.length);
    bytes.set(packed, 4);
    const bomb = toBase64Url(bytes);
    expect(bomb.length).toBeLessThan(MAX_LINK_CHARS);
    expect((await problemOf(`#gait=1.${bomb.length}.${bomb}`)).problem).toBe('too-long');
  });

  it('refuse unknown versions of the link and of the schema', async () => {
    const hash = await encodeGaitHash(presetGait(schema, 'biped'));
    const v9 = await problemOf(hash.replace('#gait=1.', '#gait=9.'));
    expect(v9.problem).toBe('unknown-version');
    expect(v9.message).toMatch(/format version 9/);
    const newer = await problemOf(await relink((g) => (g.version = 2)));
    expect(newer.problem).toBe('unknown-version');
    expect(newer.message).toMatch(/newer/);
  });

  it('migrate a gait from an older schema version', async () => {
    // As if schema version 2 had renamed "gains.hipStiffness" to "gains.hipKp".
    const newSchema = { ...schema, version: 2 };
    const migrations = {
      1: (g: GaitFile): GaitFile => {
        const { 'gains.hipStiffness': hip, ...rest } = g.params;
        return { ...g, params: hip === undefined ? rest : { ...rest, 'gains.hipKp': hip } };
      },
    };
    const { 'gains.hipKp': _, ...others } = presetGait(schema, 'biped').params;
    const old = { format: 'gaitlab-gait', version: 1, character: 'biped', params: { ...others, 'gains.hipStiffness': 450 } };
    const hash = await encodeGaitHash(old as unknown as GaitFile);
    const migrated = await decodeGaitHash(hash, newSchema, migrations);
    expect(migrated.version).toBe(2);
    expect(migrated.params).toEqual({ ...others, 'gains.hipKp': 450 });
    // Without a migration for that version, the link is refused rather than misread.
    expect((await decodeGaitHash(hash, newSchema, {}).catch((e: GaitError) => e.problem))).toBe('unknown-version');
  });

  it('migrate a schema-1 gait to schema 2: the support gain goes, the swing target rate is 0', () => {
    const schema2 = { ...schema, version: 2 };
    schema2.characters = {
      ...schema.characters,
      biped: [...schema.characters.biped, { name: 'gains.swingTargetRate', group: 'Joint gains', min: 0, max: 1, default: 0, unit: '1', description: '', knots: 1 }],
    };
    const { params } = presetGait(schema, 'biped');
    const old = { format: 'gaitlab-gait', version: 1, character: 'biped', params: { ...params, 'legFrame.supportGain': 800 } };
    const migrated = parseGait(old, schema2, MIGRATIONS);
    expect(migrated.version).toBe(2);
    expect(migrated.params).toEqual({ ...params, 'gains.swingTargetRate': 0 });
  });

  it('survive random garbage without throwing anything but GaitError', async () => {
    const next = random(99);
    const alphabet = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_.=#&%!';
    for (let i = 0; i < 300; i++) {
      const length = Math.floor(next() * 200);
      let text = '#gait=';
      if (next() < 0.5) text += `1.${length}.`;
      for (let k = 0; k < length; k++) text += alphabet[Math.floor(next() * alphabet.length)];
      await problemOf(text);
    }
  });
});

describe('base64url and CRC-32', () => {
  it('match their standards', () => {
    expect(crc32(new TextEncoder().encode('123456789'))).toBe(0xcbf43926);
    const bytes = new Uint8Array([251, 255, 0, 1, 2]);
    expect(toBase64Url(bytes)).toBe('-_8AAQI');
    expect(Array.from(fromBase64Url('-_8AAQI'))).toEqual(Array.from(bytes));
  });
});

describe('gait files', () => {
  it('keep meta, and refuse gaits with a parameter missing', () => {
    const full = presetGait(schema, 'biped');
    expect(parseGait({ ...full, meta: { author: 'x' } }, schema).meta).toEqual({ author: 'x' });
    const { period: _, ...partial } = full.params;
    expect(() => parseGait({ ...full, params: partial }, schema)).toThrow('parameter "period" is missing');
  });

  it('refuse what is not an object', () => {
    for (const bad of [null, 3, 'gait', [1]]) expect(() => parseGait(bad, schema)).toThrow(GaitError);
  });
});
