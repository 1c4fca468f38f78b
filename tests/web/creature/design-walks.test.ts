// The designer's checks let through what was measured to walk: bodies at the edges of the joint
// ranges and of a single leg frame's inertia (web/src/creature/design.ts) walk 30 s at the
// walking criteria's two speeds, natively (`gaitlab walk --creature`). Needs the native build
// (npm run build).
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import type { CreatureFile } from '../../../web/src/creature/creature-file';
import {
  buildFile,
  checkDesign,
  DEFAULT_DESIGN,
  designFromFile,
  HIP_SWING_MIN,
  KNEE_FLEXION_MIN,
  type CreatureDesign,
} from '../../../web/src/creature/design';

const root = path.join(__dirname, '../../..');
const native = path.join(root, 'build/native/gaitlab');
const shipped = (name: string) => designFromFile(JSON.parse(fs.readFileSync(path.join(root, 'public/creatures', `${name}.json`), 'utf8')) as CreatureFile);

function walk(design: CreatureDesign, speed: number): { fell: boolean; fall_time_s: number | null; mean_speed_m_s: number } {
  if (!fs.existsSync(native)) throw new Error(`${native} is missing: build it first (npm run build)`);
  const file = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-design-')), 'body.json');
  fs.writeFileSync(file, JSON.stringify(buildFile(design)));
  return JSON.parse(execFileSync(native, ['walk', '--json', '--creature', file, '--speed', String(speed), '--seconds', '30'], { encoding: 'utf8' }));
}

describe('bodies at the edges of the designer\'s limits', () => {
  const biped = shipped('biped');
  const edges: [string, CreatureDesign][] = [
    ['the insect with the least knee range', { ...DEFAULT_DESIGN, kneeFlexion: KNEE_FLEXION_MIN.frames }],
    ['the insect with the least hip swing', { ...DEFAULT_DESIGN, hipSwing: HIP_SWING_MIN.frames }],
    ['the biped with the least knee range', { ...biped, kneeFlexion: KNEE_FLEXION_MIN.single }],
    // 0.25 m tall: 0.33 kg·m² about its pitch axis, near the least a single frame may have.
    ['the biped with a flat torso', { ...biped, bodyHeight: 0.25 }],
    // The bird walks on the biped's foot scaled to its legs.
    ['the designer\'s bird', shipped('bird')],
  ];
  for (const [name, design] of edges) {
    it(`${name} passes the checks and walks 30 s at 0.4 and 0.8 m/s`, () => {
      expect(checkDesign(design)).toEqual([]);
      for (const speed of [0.4, 0.8]) {
        const r = walk(design, speed);
        expect(r.fell, `${name} at ${speed} m/s fell at ${r.fall_time_s} s`).toBe(false);
        expect(r.mean_speed_m_s).toBeGreaterThan(0.85 * speed);
      }
    }, 60_000);
  }
});
