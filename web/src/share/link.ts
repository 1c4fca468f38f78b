// A gait in a link: the page's URL hash carries one character's gait, versioned, compressed and
// checked, so that opening the link reproduces exactly the same parameters; and it may carry a
// creature's body with it (a creature file, native/src/body/creature.h), which opening the link
// puts in the scene walking that gait.
//
//   #gait=1.<chars>.<data>
//   #creature=1.<chars>.<data>&gait=1.<chars>.<data>
//
//   1        the link format's version (LINK_VERSION); the gait inside carries the parameter
//            schema's version, which the module migrates if it is older (gl_gait_normalize)
//   <chars>  how many characters <data> has: a link cut short (a chat client wrapping it, a
//            partial copy) is recognised as truncated rather than as some other gait
//   <data>   base64url of: CRC-32 of the JSON (4 bytes, big-endian), then the gait file's JSON
//            (without "meta") compressed with deflate-raw (CompressionStream); the creature's
//            part is packed the same way, its JSON the creature file's
//
// Decoding refuses, with a GaitError naming the problem: a truncated link, corrupt data (bad
// characters, data that does not inflate, a checksum mismatch, text that is not JSON), a link
// or payload that is too long, an unknown link version. The gait inside is then the module's to
// judge (an unknown schema version, a field missing, unknown, out of bounds or not finite): the
// decoder hands its text to a normaliser (gl_gait_normalize through the sim worker) and passes
// a refusal on as problem 'refused' with the module's "FIELD: WHAT". The page then shows the
// message and runs with the presets.
import { GaitError, type GaitFile, type GaitNormalizer } from './gait-file';
import { jsonLimitProblem, MAX_JSON_BYTES as MAX_GAIT_FILE_BYTES } from '../sim/limits';

export const LINK_VERSION = 1;
export const HASH_KEY = 'gait';
export const CREATURE_KEY = 'creature';
/** What each part of a link carries, as its messages name it. */
type Part = 'gait' | 'creature';
/**
 * Longest link data accepted. A gait of one parameter set makes a link of 1,600 (biped) to
 * 2,400 (quadruped) characters, each further speed key adds about 1,600 (the shipped quadruped's
 * eight keys: 12,818), and the most keys a gait may have (native/src/gait/speed_keys.h, 12) about
 * 20,000. The data sits in the URL's fragment,
 * which browsers keep to the page (it is never sent to a server), and Chromium, Firefox and
 * Safari open fragments far longer than this. Anything longer was not made by this page.
 */
export const MAX_LINK_CHARS = 32768;
/**
 * Most bytes the data may inflate to (guards against a small link that inflates to gigabytes):
 * the most a gait file may have (native/src/api/limits.h, web/src/sim/limits.ts).
 */
export const MAX_JSON_BYTES = MAX_GAIT_FILE_BYTES;

// ---- base64url (RFC 4648 §5, no padding) ------------------------------------------------------

export function toBase64Url(bytes: Uint8Array): string {
  let binary = '';
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

export function fromBase64Url(text: string): Uint8Array {
  if (!/^[A-Za-z0-9_-]*$/.test(text)) throw new GaitError('corrupt', 'the link data has characters that base64url does not use');
  if (text.length % 4 === 1) throw new GaitError('corrupt', 'the link data has an impossible length for base64url');
  const binary = atob(text.replace(/-/g, '+').replace(/_/g, '/') + '='.repeat((4 - (text.length % 4)) % 4));
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  return bytes;
}

// ---- CRC-32 (IEEE 802.3, as zlib) ---------------------------------------------------------------

const CRC_TABLE = (() => {
  const table = new Uint32Array(256);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    table[n] = c >>> 0;
  }
  return table;
})();

export function crc32(bytes: Uint8Array): number {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

// ---- deflate-raw through the platform's streams ------------------------------------------------

async function deflateRaw(bytes: Uint8Array): Promise<Uint8Array> {
  const stream = new Blob([bytes as BlobPart]).stream().pipeThrough(new CompressionStream('deflate-raw'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

/** Inflates, stopping with 'too-long' past `limit` bytes; any stream error is corrupt data. */
async function inflateRaw(bytes: Uint8Array, limit: number, what: Part): Promise<Uint8Array> {
  const reader = new Blob([bytes as BlobPart]).stream().pipeThrough(new DecompressionStream('deflate-raw')).getReader();
  const chunks: Uint8Array[] = [];
  let total = 0;
  try {
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      total += value.length;
      if (total > limit) {
        await reader.cancel().catch(() => {});
        throw new GaitError('too-long', `the link's ${what} inflates to more than ${limit / 1024} KiB`);
      }
      chunks.push(value);
    }
  } catch (error) {
    if (error instanceof GaitError) throw error;
    throw new GaitError('corrupt', 'the link data is damaged: it does not decompress');
  }
  const out = new Uint8Array(total);
  let offset = 0;
  for (const c of chunks) {
    out.set(c, offset);
    offset += c.length;
  }
  return out;
}

// ---- the link ----------------------------------------------------------------------------------

/** One part of a link: `<version>.<chars>.<data>` of a JSON text. */
async function pack(json: string): Promise<string> {
  const text = new TextEncoder().encode(json);
  const packed = await deflateRaw(text);
  const bytes = new Uint8Array(4 + packed.length);
  new DataView(bytes.buffer).setUint32(0, crc32(text));
  bytes.set(packed, 4);
  const data = toBase64Url(bytes);
  return `${LINK_VERSION}.${data.length}.${data}`;
}

/** The hash (with its leading '#') that carries `gait`, and the body of `creature` if given (a creature file's text). */
export async function encodeGaitHash(gait: GaitFile, creature?: string): Promise<string> {
  // "meta" stays out of links: it is provenance for files, and would only make links longer.
  // Speed keys (schema 4) travel with the parameters.
  const keyed = gait.speed !== undefined || gait.keys !== undefined ? { speed: gait.speed ?? 0, keys: gait.keys ?? [] } : {};
  const json = JSON.stringify({ format: gait.format, version: gait.version, character: gait.character, ...keyed, params: gait.params });
  // The creature file as compact JSON: its layout is the sender's, its values are what count.
  const body = creature === undefined ? '' : `${CREATURE_KEY}=${await pack(JSON.stringify(JSON.parse(creature)))}&`;
  return `#${body}${HASH_KEY}=${await pack(json)}`;
}

/** Whether a URL hash carries a gait at all (a hash without one is not an error). */
export function hasGait(hash: string): boolean {
  return new URLSearchParams(hash.replace(/^#/, '')).has(HASH_KEY);
}

/** Whether a URL hash carries a creature's body. */
export function hasCreature(hash: string): boolean {
  return new URLSearchParams(hash.replace(/^#/, '')).has(CREATURE_KEY);
}

/**
 * The JSON text of part `key` of a URL hash (checked: version, length, characters, checksum, the
 * limits of a gait file, that it parses); throws a GaitError saying what is wrong, naming `what`.
 */
async function unpack(hash: string, key: string, what: Part): Promise<string> {
  const value = new URLSearchParams(hash.replace(/^#/, '')).get(key) ?? '';
  if (value.length > MAX_LINK_CHARS + 32) {
    throw new GaitError('too-long', `the link's ${what} is ${value.length} characters long; at most ${MAX_LINK_CHARS} are accepted`);
  }
  if (value === '') throw new GaitError('truncated', `the link is truncated: it names a ${what} but carries none`);
  const match = /^(\d+)(?:\.(\d*)(?:\.(.*))?)?$/s.exec(value);
  if (!match) throw new GaitError('corrupt', `the link does not have the form ${key}=<version>.<length>.<data>`);
  const [, versionText, lengthText, data] = match;
  const version = Number(versionText);
  if (version !== LINK_VERSION) {
    throw new GaitError('unknown-version', `the link is of format version ${version}; this page reads version ${LINK_VERSION}`);
  }
  if (!lengthText || data === undefined) throw new GaitError('truncated', 'the link is truncated: its data is missing');
  const declared = Number(lengthText);
  if (declared > MAX_LINK_CHARS) {
    throw new GaitError('too-long', `the link's ${what} is ${declared} characters long; at most ${MAX_LINK_CHARS} are accepted`);
  }
  if (data.length < declared) {
    throw new GaitError('truncated', `the link is truncated: it has ${data.length} of its ${declared} characters of data`);
  }
  if (data.length > declared) throw new GaitError('corrupt', `the link has ${data.length - declared} characters more data than it declares`);
  const bytes = fromBase64Url(data);
  if (bytes.length < 5) throw new GaitError('corrupt', `the link data is too short to hold a ${what}`);
  const expected = new DataView(bytes.buffer, bytes.byteOffset).getUint32(0);
  const text = await inflateRaw(bytes.subarray(4), MAX_JSON_BYTES, what);
  if (crc32(text) !== expected) throw new GaitError('corrupt', 'the link data is damaged: its checksum does not match');
  let json: string;
  try {
    json = new TextDecoder('utf-8', { fatal: true }).decode(text);
  } catch {
    throw new GaitError('corrupt', `the link data is not a JSON ${what}`);
  }
  // Within the limits of a gait file before anything parses it: a 1.5 kB link can inflate to a
  // gait nested 100,000 deep, which JSON.parse builds and every later JSON.stringify overflows on.
  const problem = jsonLimitProblem(json);
  if (problem) throw new GaitError(problem.startsWith('nested') ? 'corrupt' : 'too-long', `the link's ${what} is refused: ${problem}`);
  try {
    JSON.parse(json);
  } catch {
    throw new GaitError('corrupt', `the link data is not a JSON ${what}`);
  }
  return json;
}

/**
 * The creature file's text a URL hash carries (call only when hasCreature(hash)); throws a
 * GaitError saying what is wrong with the link. The body itself is the module's to judge, when
 * it is spawned (gl_sim_spawn_creature names the field it refuses).
 */
export function decodeCreatureHash(hash: string): Promise<string> {
  return unpack(hash, CREATURE_KEY, 'creature');
}

/**
 * The gait a URL hash carries, normalised by `normalize` (the module); throws a GaitError saying
 * what is wrong. Call only when hasGait(hash).
 */
export async function decodeGaitHash(hash: string, normalize: GaitNormalizer): Promise<GaitFile> {
  const json = await unpack(hash, HASH_KEY, 'gait');
  try {
    return await normalize(json);
  } catch (error) {
    throw new GaitError('refused', error instanceof Error ? error.message : String(error));
  }
}
