// Types of bench/peers/comparison.mjs for the TypeScript front end (web/src/bench/peers*.ts).
export interface PeerGrid { legs: Array<2 | 4>; characters: number[]; threads: number[] }
export interface PeerPointSpec { legs: 2 | 4; characters: number; threads: number }
export interface PeerSettings { steps: number; rounds: number; settle: number }
/** One engine's result at a point: timed, or `skipped` with the reason. */
export interface PeerPoint {
  engine: 'gaitlab' | 'jolt-mt' | 'jolt';
  legs: 2 | 4;
  characters: number;
  threads: number;
  ms_per_step?: number;
  ms_min?: number;
  ms_max?: number;
  root_height_m?: number;
  skipped?: string;
  /** Rounds run, when fewer than asked, and why. */
  rounds?: number;
  refused?: string;
}
export interface PeerEngine {
  make(legs: 2 | 4, characters: number, threads: number): { step(steps: number): void; rootHeight(): number; destroy(): void };
  name: PeerPoint['engine'];
  label: string;
  runs(legs: 2 | 4, characters: number, threads: number): boolean;
}
/** The three modules: gaitlab's (its C ABI) and two builds of the jolt-physics package. */
export interface PeerModules { gaitlab: unknown; joltMT: unknown; joltST: unknown }
export const JOLT_MAX_BODIES: number;
export const JOLT_SKIP: string;
export const TABLE_HEAD: string[];
export function peerEngines(modules: PeerModules, options?: { joltSettings?: Record<string, number | boolean> }): PeerEngine[];
export function warmUp(engines: PeerEngine[], legs: Array<2 | 4>, threads: number[]): void;
export function measurePoint(engines: PeerEngine[], point: PeerPointSpec, settings: PeerSettings): PeerPoint[];
export function peerGrid(grid: PeerGrid): PeerPointSpec[];
export function tableGrid(grid: PeerGrid): PeerPointSpec[];
export function describePoint(point: PeerPoint): string;
export function tableRows(points: PeerPoint[], grid: PeerPointSpec[]): string[][];
