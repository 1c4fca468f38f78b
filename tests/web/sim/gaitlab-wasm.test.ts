// The TypeScript binding against the C ABI's header (native/src/api/c_api.h): the settings
// structs' layouts its static_asserts pin, the thread limit, and the error codes and enum values
// the binding writes out. tests/wasm/c-api.test.mjs checks the same header against the built
// module (the wasm32 layout the library really uses).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { CROWD_SHARDS, ERR, INFO, Kind, LEGS, MAX_THREADS, METHOD, MODE, STRUCTS, TERRAIN } from '../../../web/src/sim/gaitlab-wasm';
import { MAX_THREADS as PAGE_MAX_THREADS } from '../../../web/src/sim/protocol';
import { SEARCH_FIELDS } from '../../../web/src/optimize/options';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../..');
const header = fs.readFileSync(path.join(repoDir, 'native/src/api/c_api.h'), 'utf8');

/** The value of enumerator `name` in the header: explicit (`NAME = -3`) or counted from the last. */
function enumerator(name: string): number {
  for (const body of header.matchAll(/enum\s*\{([^}]*)\}/g)) {
    let next = 0;
    for (const item of body[1].replace(/\/\/[^\n]*/g, '').split(',')) {
      const m = /^\s*(\w+)\s*(?:=\s*(-?\d+))?\s*$/.exec(item);
      if (!m) continue;
      const value = m[2] === undefined ? next : Number(m[2]);
      if (m[1] === name) return value;
      next = value + 1;
    }
  }
  throw new Error(`no enumerator ${name} in c_api.h`);
}

describe('the binding of c_api.h', () => {
  it('writes each settings struct at the offsets the header static_asserts', () => {
    const structs = Object.keys(STRUCTS) as Array<keyof typeof STRUCTS>;
    const asserted = new Set<string>();
    for (const m of header.matchAll(/static_assert\(offsetof\((\w+),\s*(\w+)\)\s*==\s*(\d+)/g)) {
      const [, struct, field, offset] = m;
      asserted.add(struct);
      expect(structs, `${struct} is mirrored`).toContain(struct);
      const fields = STRUCTS[struct as keyof typeof STRUCTS].fields as Record<string, readonly [number, string]>;
      expect(fields[field]?.[0], `${struct}.${field}`).toBe(Number(offset));
    }
    for (const struct of structs) {
      expect(asserted, `${struct} has static_asserts`).toContain(struct);
      const size = new RegExp(`static_assert\\(sizeof\\(${struct}\\)\\s*==\\s*(\\d+)`).exec(header);
      expect(Number(size?.[1]), `sizeof(${struct})`).toBe(STRUCTS[struct].size);
      // Every field the binding writes is one the header pins.
      for (const field of Object.keys(STRUCTS[struct].fields)) {
        expect(header, `${struct}.${field}`).toMatch(new RegExp(`offsetof\\(${struct},\\s*${field}\\)`));
      }
    }
  });

  it('states the module\'s thread limit, and the page\'s options use it', () => {
    const define = /^#define GL_MAX_THREADS (\d+)$/m.exec(header);
    expect(Number(define?.[1])).toBe(MAX_THREADS);
    expect(PAGE_MAX_THREADS).toBe(MAX_THREADS);
    expect(SEARCH_FIELDS.threads.max).toBe(MAX_THREADS);
  });

  it('splits a crowd\'s physics over as many shards as the simulation does', () => {
    const shards = fs.readFileSync(path.join(repoDir, 'native/src/sim/physics_shards.h'), 'utf8');
    expect(Number(/^constexpr int kCrowdShards = (\d+);$/m.exec(shards)?.[1])).toBe(CROWD_SHARDS);
  });

  it('has the header\'s error codes and enum values', () => {
    expect(enumerator('GL_OK')).toBe(0);
    expect(ERR).toEqual({
      argument: enumerator('GL_ERR_ARGUMENT'),
      kind: enumerator('GL_ERR_KIND'),
      noCharacter: enumerator('GL_ERR_NO_CHARACTER'),
      invalidParams: enumerator('GL_ERR_INVALID_PARAMS'),
      full: enumerator('GL_ERR_FULL'),
    });
    expect(Object.values(ERR).every((code) => code < 0)).toBe(true);
    expect(Kind).toEqual({
      biped: enumerator('GL_KIND_BIPED'),
      quadruped: enumerator('GL_KIND_QUADRUPED'),
      hexapod: enumerator('GL_KIND_HEXAPOD'),
      octopod: enumerator('GL_KIND_OCTOPOD'),
      box: enumerator('GL_KIND_BOX'),
    });
    expect(METHOD).toEqual({ greedy: enumerator('GL_METHOD_GREEDY'), cmaes: enumerator('GL_METHOD_CMAES') });
    expect(LEGS).toEqual({ mixed: enumerator('GL_LEGS_MIXED'), 2: enumerator('GL_LEGS_BIPED'), 4: enumerator('GL_LEGS_QUADRUPED') });
    expect(MODE).toEqual({ serial: enumerator('GL_MODE_SERIAL'), controller: enumerator('GL_MODE_CONTROLLER'), full: enumerator('GL_MODE_FULL') });
    expect(TERRAIN).toEqual({ flat: enumerator('GL_TERRAIN_FLAT'), slope: enumerator('GL_TERRAIN_SLOPE'), bumps: enumerator('GL_TERRAIN_BUMPS') });
    expect(INFO.fields).toBe(enumerator('GL_INFO_FIELDS'));
    expect(INFO.phase).toBe(enumerator('GL_INFO_PHASE'));
    expect(INFO.fallen).toBe(enumerator('GL_INFO_FALLEN'));
  });
});
