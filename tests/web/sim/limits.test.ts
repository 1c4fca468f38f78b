// The page's limits (web/src/sim/limits.ts) are native/src/api/limits.h's, and jsonLimitProblem
// judges JSON text as the module's pre-scan does: deep, long and wide texts refused, naming the
// limit, without recursion; valid gait files accepted.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import * as limits from '../../../web/src/sim/limits';
import { presetGait } from '../../../web/src/share/gait-file';
import { schema } from '../fixtures/schema';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../..');

/** kMaxJsonBytes -> MAX_JSON_BYTES. */
const tsName = (cpp: string) => cpp.replace(/^k/, '').replace(/([a-z])([A-Z])/g, '$1_$2').toUpperCase();

describe('limits.ts', () => {
  it('states every limit of native/src/api/limits.h, with the same value', () => {
    const header = fs.readFileSync(path.join(repoDir, 'native/src/api/limits.h'), 'utf8');
    const page = limits as unknown as Record<string, unknown>;
    let compared = 0;
    for (const [, name, value] of header.matchAll(/^constexpr (?:long|int|double) (k\w+) = ([^;]+);/gm)) {
      if (name.startsWith('kMaxBench')) continue; // the benchmark's: not the page's
      expect(page[tsName(name)], name).toBe(Function(`return ${value.replace(/\.0\b/g, '')}`)());
      compared++;
    }
    expect(compared).toBeGreaterThanOrEqual(13);
  });
});

describe('jsonLimitProblem', () => {
  const nested = (depth: number) => '['.repeat(depth) + '0' + ']'.repeat(depth);

  it('accepts gait files, and nesting up to the limit', () => {
    for (const character of ['biped', 'quadruped'] as const) {
      expect(limits.jsonLimitProblem(JSON.stringify(presetGait(schema, character), null, 2))).toBeNull();
    }
    expect(limits.jsonLimitProblem(nested(limits.MAX_JSON_DEPTH))).toBeNull();
    expect(limits.jsonLimitProblem('"[[[[[[[[[[[[[[[[[[[[[[[[[["')).toBeNull(); // brackets in a string
    expect(limits.jsonLimitProblem('["\\"[[[[[[[[[[[[[[[[[[[[[[[[[["]')).toBeNull(); // after an escaped quote
  });

  it('refuses deep, long and wide texts naming the limit, without recursion', () => {
    expect(limits.jsonLimitProblem(nested(limits.MAX_JSON_DEPTH + 1))).toMatch(/nested deeper than 16/);
    expect(limits.jsonLimitProblem('{"a":'.repeat(40000))).toMatch(/nested deeper/);
    expect(limits.jsonLimitProblem(' '.repeat(limits.MAX_JSON_BYTES + 1))).toMatch(/bytes long/);
    // Bytes, not UTF-16 units: 100,000 "é" are 200,000 bytes.
    expect(limits.jsonLimitProblem(`"${'é'.repeat(limits.MAX_JSON_STRING / 2 + 1)}"`)).toMatch(/string is longer/);
    expect(limits.jsonLimitProblem(`[${'0,'.repeat(limits.MAX_JSON_ARRAY)}0]`)).toMatch(/more than 4096 elements/);
    expect(limits.jsonLimitProblem(`[${'0,'.repeat(limits.MAX_JSON_ARRAY - 1)}0]`)).toBeNull();
  });
});
