// Types of bench/lib/analysis.mjs for the TypeScript front end (web/src/bench).
export interface Stat { mean: number; sd: number }
export interface Point {
  legs: 2 | 4 | 'mixed';
  characters: number;
  threads: number;
  mode: 'serial' | 'controller' | 'full';
  shards: number;
  steps: number;
  runs: number;
  controller_ms: Stat;
  physics_ms: Stat;
  step_ms: Stat & { p50: number; p99: number; max: number; p99_median_over_runs?: number };
  controller_us_per_character: number;
  memory: { heap_bytes: number; scene_heap_bytes: number; rss_bytes: number | null };
  state_hash: string;
  deterministic: boolean;
  frames?: Record<'controller_ms' | 'physics_ms' | 'step_ms', { mean: number[]; sd: number[] }>;
}
export interface BenchDocument {
  schema: 'gaitlab-bench/1';
  date: string;
  machine: Record<string, unknown> & { runtime: string; cores: number };
  inputs: Record<string, unknown>;
  points: Point[];
}
export type TimeField = 'controller_ms' | 'physics_ms' | 'step_ms';
export const STEP_BUDGET_MS: number;
export const CSV_COLUMNS: string[];
export function validate(value: unknown, kind?: 'document' | 'results'): string[];
export function overlayDocuments(value: unknown): BenchDocument[];
export function toCsv(doc: BenchDocument): string;
export function seriesKey(p: Point): string;
export function curves(doc: BenchDocument, legs: Point['legs']): Map<string, Point[]>;
export function fitLine(xs: number[], ys: number[]): { a: number; b: number; r2: number };
export function capacityBracket(points: Point[]): { within: Point | null; over: Point | null };
export function nextCapacityProbe(points: Point[], options?: { cap?: number; tolerance?: number }): number | null;
export function capacity(points: Point[]): {
  measured: number; fitted: number | null; extrapolated: boolean; line: { a: number; b: number; r2: number };
};
export function find(doc: BenchDocument, q: { legs: Point['legs']; characters: number; mode: Point['mode']; threads?: number }): Point | undefined;
export function ratioTable(doc: BenchDocument, legs: Point['legs'], field?: TimeField): Array<{
  series: string; from: number; to: number; fromMs: number; toMs: number; ratio: number | null;
}>;
export function speedup(doc: BenchDocument, legs: Point['legs'], characters: number, threads: number, mode?: Point['mode'], field?: TimeField): number | null;
export function legsName(legs: Point['legs']): string;
