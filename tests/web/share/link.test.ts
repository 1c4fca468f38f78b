// The gait link codec (web/src/share): round trips, and every kind of bad link refused with the
// problem named — never a crash and never a silently different gait. The gait inside a link is
// the module's to judge (gl_gait_normalize): here a stand-in normaliser takes its place, and
// tests/wasm/gait-normalize.test.mjs runs every check of a gait's content against the module.
import { readFileSync } from 'node:fs';

import { describe, expect, it } from 'vitest';
import {
  GaitError,
  patched,
  presetGait,
  sameParams,
  type GaitFile,
  type GaitNormalizer,
  type GaitProblem,
} from '../../../web/src/share/gait-file';
import {
  crc32,
  decodeCreatureHash,
  decodeGaitHash,
  encodeGaitHash,
  fromBase64Url,
  hasCreature,
  hasGait,
  MAX_LINK_CHARS,
  toBase64Url,
} from '../../../web/src/share/link';
import { schema } from '../fixtures/schema';
import { mulberry32 as random } from '../../../web/src/random';

/** The module's part, stood in for: the text as JSON, unchanged. */
const passThrough: GaitNormalizer = async (json) => JSON.parse(json) as GaitFile;

/** The problem decoding `hash` reports (fails the test if it decodes). */
async function problemOf(hash: string, normalize: GaitNormalizer = passThrough): Promise<{ problem: GaitProblem; message: string }> {
  try {
    await decodeGaitHash(hash, normalize);
  } catch (error) {
    expect(error).toBeInstanceOf(GaitError);
    return { problem: (error as GaitError).problem, message: (error as GaitError).message };
  }
  throw new Error(`${hash.slice(0, 60)}… decoded without complaint`);
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

describe('gait links', () => {
  it('round-trip the presets exactly', async () => {
    for (const character of ['biped', 'quadruped'] as const) {
      const gait = presetGait(schema, character);
      const hash = await encodeGaitHash(gait);
      expect(hash).toMatch(/^#gait=1\.\d+\.[A-Za-z0-9_-]+$/);
      expect(hasGait(hash)).toBe(true);
      const back = await decodeGaitHash(hash, passThrough);
      expect(sameParams(back, gait)).toBe(true);
      expect(back.character).toBe(character);
    }
  });

  it('round-trip random gaits bit for bit', async () => {
    const next = random(12345);
    for (let i = 0; i < 200; i++) {
      const gait = randomGait(next);
      const back = await decodeGaitHash(await encodeGaitHash(gait), passThrough);
      expect(sameParams(back, gait), `case ${i}`).toBe(true);
    }
  });

  it('carry speed keys', async () => {
    const preset = presetGait(schema, 'biped');
    const gait: GaitFile = { ...preset, speed: 1.4, keys: [{ speed: 1.7, params: { ...preset.params, period: 0.55 } }] };
    const back = await decodeGaitHash(await encodeGaitHash(gait), passThrough);
    expect(back.speed).toBe(1.4);
    expect(back.keys).toEqual(gait.keys);
    expect(sameParams(back, gait)).toBe(true);
    expect(sameParams(back, preset)).toBe(false);
  });

  it('carry the shipped presets, every speed key, and a gait with the most keys a gait may have', async () => {
    // The shipped files, not the fixture's stand-ins: a quadruped of eight keys once made a link
    // of 12,818 characters that this page then refused as too long.
    for (const character of ['biped', 'quadruped'] as const) {
      const file = JSON.parse(readFileSync(`public/presets/${character}.json`, 'utf8')) as GaitFile;
      const hash = await encodeGaitHash(file);
      const back = await decodeGaitHash(hash, passThrough);
      expect(back.keys, character).toEqual(file.keys);
      expect(back.speed).toBe(file.speed);
      expect(sameParams(back, file)).toBe(true);
    }
    // Twelve keys (native/src/gait/speed_keys.h, kMaxSpeedKeys), every number as an optimiser
    // leaves it (17 significant digits, which compress worst).
    const file = JSON.parse(readFileSync('public/presets/quadruped.json', 'utf8')) as GaitFile;
    const next = random(3);
    const jitter = (v: number | number[]): number | number[] => (Array.isArray(v) ? v.map((x) => x * (1 + 1e-3 * next())) : v * (1 + 1e-3 * next()));
    const keys = Array.from({ length: 11 }, (_, i) => ({
      speed: 0.1 + 0.4 * i,
      params: Object.fromEntries(Object.entries(file.params).map(([k, v]) => [k, jitter(v)])),
    }));
    const most: GaitFile = { ...file, speed: 4.9, keys };
    const hash = await encodeGaitHash(most);
    expect(hash.length).toBeLessThan(MAX_LINK_CHARS);
    const back = await decodeGaitHash(hash, passThrough);
    expect(back.keys).toEqual(keys);
  });

  it('keep links short', async () => {
    const hash = await encodeGaitHash(randomGait(random(7)));
    expect(hash.length).toBeLessThan(600);
  });

  it('are not confused by other keys in the hash', async () => {
    const hash = await encodeGaitHash(presetGait(schema, 'biped'));
    const back = await decodeGaitHash(`#view=top&${hash.slice(1)}&x=1`, passThrough);
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

  it('hand the gait inside to the normaliser, exactly as it was encoded, and pass its refusal on', async () => {
    const gait = presetGait(schema, 'quadruped');
    const seen: string[] = [];
    const back = await decodeGaitHash(await encodeGaitHash({ ...gait, meta: { author: 'x' } }), async (json) => {
      seen.push(json);
      return JSON.parse(json) as GaitFile;
    });
    // "meta" stays out of links.
    expect(seen).toEqual([JSON.stringify({ format: gait.format, version: gait.version, character: gait.character, params: gait.params })]);
    expect(sameParams(back, gait)).toBe(true);
    // The module's refusal, "FIELD: WHAT", is what the page shows.
    const refusal = await problemOf(await encodeGaitHash(gait), async () => {
      throw new Error('period: 7.5 is outside [0.3, 3.0]');
    });
    expect(refusal).toEqual({ problem: 'refused', message: 'period: 7.5 is outside [0.3, 3.0]' });
  });

  it('refuse data that is not JSON before the normaliser sees it', async () => {
    const text = new TextEncoder().encode('{"format": "gaitlab-gait", ');
    const packed = new Uint8Array(await new Response(new Blob([text]).stream().pipeThrough(new CompressionStream('deflate-raw'))).arrayBuffer());
    const bytes = new Uint8Array(4 + packed.length);
    new DataView(bytes.buffer).setUint32(0, crc32(text));
    bytes.set(packed, 4);
    const data = toBase64Url(bytes);
    let called = false;
    const { problem, message } = await problemOf(`#gait=1.${data.length}.${data}`, async (json) => {
      called = true;
      return JSON.parse(json) as GaitFile;
    });
    expect(problem).toBe('corrupt');
    expect(message).toMatch(/not a JSON gait/);
    expect(called).toBe(false);
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

  it('refuse a short link whose gait is nested thousands deep, before anything parses it', async () => {
    // About 1.5 kB of link: deflate packs 100,000 brackets into almost nothing.
    for (const field of ['format', 'version', 'character', 'params', 'meta']) {
      const json = `{"format":"gaitlab-gait","version":2,"character":"biped","params":{},"${field}":${'['.repeat(100000)}${']'.repeat(100000)}}`
        .replace(`"${field}":"gaitlab-gait"`, '').replace(`"${field}":2,`, '').replace(`"${field}":{},`, '');
      const text = new TextEncoder().encode(json);
      const packed = new Uint8Array(await new Response(new Blob([text]).stream().pipeThrough(new CompressionStream('deflate-raw'))).arrayBuffer());
      const bytes = new Uint8Array(4 + packed.length);
      new DataView(bytes.buffer).setUint32(0, crc32(text));
      bytes.set(packed, 4);
      const data = toBase64Url(bytes);
      expect(data.length).toBeLessThan(MAX_LINK_CHARS);
      let called = false;
      const { problem, message } = await problemOf(`#gait=1.${data.length}.${data}`, async (j) => {
        called = true;
        return JSON.parse(j) as GaitFile;
      });
      expect(problem).toBe('corrupt');
      expect(message).toMatch(/nested deeper than 16 levels/);
      expect(called).toBe(false);
    }
  });

  it('refuse unknown versions of the link', async () => {
    const hash = await encodeGaitHash(presetGait(schema, 'biped'));
    const v9 = await problemOf(hash.replace('#gait=1.', '#gait=9.'));
    expect(v9.problem).toBe('unknown-version');
    expect(v9.message).toMatch(/format version 9/);
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

describe('creature links', () => {
  const insect = readFileSync(new URL('../../../public/creatures/insect.json', import.meta.url), 'utf8');
  const gait = presetGait(schema, 'hexapod');

  it('carry a creature file beside its gait, each read back as it was', async () => {
    const hash = await encodeGaitHash(gait, insect);
    expect(hash).toMatch(/^#creature=1\.\d+\.[A-Za-z0-9_-]+&gait=1\.\d+\.[A-Za-z0-9_-]+$/);
    expect(hasCreature(hash)).toBe(true);
    expect(hasGait(hash)).toBe(true);
    expect(JSON.parse(await decodeCreatureHash(hash))).toEqual(JSON.parse(insect));
    expect((await decodeGaitHash(hash, passThrough)).params).toEqual(gait.params);
    // A gait alone carries no creature.
    expect(hasCreature(await encodeGaitHash(gait))).toBe(false);
  });

  it('refuse a damaged or truncated creature, naming it', async () => {
    const hash = await encodeGaitHash(gait, insect);
    const creature = /creature=([^&]*)/.exec(hash)![1];
    const [version, chars, data] = creature.split('.');
    const damaged = hash.replace(creature, `${version}.${chars}.${data.slice(0, 10)}${data[10] === 'A' ? 'B' : 'A'}${data.slice(11)}`);
    await expect(decodeCreatureHash(damaged)).rejects.toThrow(/the link data is damaged|not a JSON creature/);
    const cut = hash.replace(creature, `${version}.${chars}.${data.slice(0, 20)}`);
    await expect(decodeCreatureHash(cut)).rejects.toThrow(`the link is truncated: it has 20 of its ${chars} characters of data`);
    await expect(decodeCreatureHash('#creature=&gait=1.2.AA')).rejects.toThrow('the link is truncated: it names a creature but carries none');
    await expect(decodeCreatureHash('#creature=2.4.AAAA')).rejects.toThrow('the link is of format version 2; this page reads version 1');
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

describe('gait edits', () => {
  it('are patches: patched() changes the named parameters of a copy', () => {
    const gait = presetGait(schema, 'biped');
    const edited = patched(gait, { period: 1.1, 'legFrame.pitch': [0.1, 0, 0, 0] });
    expect(edited.params.period).toBe(1.1);
    expect(edited.params['legFrame.pitch']).toEqual([0.1, 0, 0, 0]);
    expect(gait.params.period).toBe(0.8);
    expect(sameParams(patched(edited, { period: 0.8, 'legFrame.pitch': [0, 0.05, 0, -0.05] }), gait)).toBe(true);
  });
});
