// The optimize panel's inputs, checked before a search starts, and the figures it shows while
// one runs (time per generation, time left). Pure functions: unit-tested in tests/web.
//
// The objective settings (names, bounds, defaults, units, descriptions) are the module's own
// table (gl_opt_settings_json, native/src/optimize/objective.h): nothing of it is written out
// here. What is the panel's own is the search's size: generations, candidates, seed, threads
// (the same bounds as `gaitlab optimize`, native/src/api/cli.cpp).
import { CHARACTER_TYPES, type CharacterType } from '../gait/character';
import { MAX_THREADS } from '../sim/protocol';

/** One objective setting as gl_opt_settings_json describes it. */
export interface SettingSpec {
  name: string;
  min: number;
  max: number;
  default: number;
  unit: string;
  description: string;
  /** Whole numbers only (e.g. `starts`). */
  integer: boolean;
}

/** gl_opt_settings_json: the objective settings and the goal speeds' range. */
export interface OptimizerSchema {
  settings: SettingSpec[];
  speeds: { min: number; max: number; default: number[]; unit: string; description: string };
}

export type Method = 'greedy' | 'cmaes';
export const METHODS: readonly Method[] = ['greedy', 'cmaes'];
/** Where the search starts: the type's preset, or the selected character's gait as it runs now. */
export type StartFrom = 'preset' | 'selected';
export const START_FROM: readonly StartFrom[] = ['preset', 'selected'];

/** A checked search, ready for gl_opt_create. */
export interface OptimizeOptions {
  character: CharacterType;
  method: Method;
  generations: number;
  candidates: number;
  seed: number;
  threads: number;
  start: StartFrom;
  /** Every scalar objective setting of the schema (gl_opt_create's settings object). */
  settings: Record<string, number>;
  /** Goal speeds, m/s: every candidate walks an episode at each. */
  speeds: number[];
}

/**
 * The form as typed: text (or numbers, from the test hook). Keys: character, method, start,
 * generations, candidates, seed, threads, speeds (comma-separated), and one per objective
 * setting, by its schema name.
 */
export type OptimizeForm = Record<string, string | number>;

/** Bounds of the search's own fields (as `gaitlab optimize` has them). */
export const SEARCH_FIELDS = {
  generations: { min: 1, max: 1_000_000, label: 'generations', description: 'generations to run (the thesis ran 100–300)' },
  candidates: { min: 2, max: 1000, label: 'candidates', description: 'candidates per generation, K (thesis: the best and 9 perturbed copies)' },
  seed: { min: 0, max: 4_294_967_295, label: 'seed', description: 'seed of the search: the same seed and options give the same search' },
  threads: { min: 1, max: MAX_THREADS, label: 'threads', description: 'threads evaluating the candidates of a generation' },
} as const;

export interface FieldProblem {
  /** The form key it is about. */
  field: string;
  message: string;
}

export type Checked = { ok: true; options: OptimizeOptions } | { ok: false; problems: FieldProblem[] };

/** A decimal number as people type it (no hex, no "1e", no empty string meaning 0). */
const NUMBER = /^[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?$/;

/** `text` as a number, or why not. */
export function parseNumber(text: string | number): { value: number } | { problem: string } {
  if (typeof text === 'number') return Number.isFinite(text) ? { value: text } : { problem: `${text} is not a finite number` };
  const t = String(text).trim();
  if (t === '') return { problem: 'is empty' };
  if (!NUMBER.test(t)) return { problem: `'${t}' is not a number` };
  const value = Number(t);
  return Number.isFinite(value) ? { value } : { problem: `'${t}' is too large` };
}

const show = (x: number) => String(Number(x.toPrecision(6)));

function checkNumber(
  form: OptimizeForm,
  field: string,
  label: string,
  bounds: { min: number; max: number; integer?: boolean },
  problems: FieldProblem[],
): number {
  const raw = form[field];
  const parsed = parseNumber(raw ?? '');
  let problem: string | null = null;
  if ('problem' in parsed) problem = parsed.problem;
  else if (bounds.integer && !Number.isInteger(parsed.value)) problem = `${show(parsed.value)} is not a whole number`;
  else if (parsed.value < bounds.min) problem = `${show(parsed.value)} is below the minimum, ${show(bounds.min)}`;
  else if (parsed.value > bounds.max) problem = `${show(parsed.value)} is above the maximum, ${show(bounds.max)}`;
  if (problem !== null) {
    problems.push({ field, message: `${label}: ${problem}` });
    return NaN;
  }
  return (parsed as { value: number }).value;
}

function checkChoice<T extends string>(form: OptimizeForm, field: string, choices: readonly T[], problems: FieldProblem[]): T {
  const value = String(form[field] ?? '');
  if (!(choices as readonly string[]).includes(value)) {
    problems.push({ field, message: `${field}: '${value}' is not one of ${choices.join(', ')}` });
  }
  return value as T;
}

/**
 * Checks the form against the bounds (the module's for the objective, the CLI's for the
 * search) and says every problem, each naming its field; or gives the options for a search.
 * `selected` is the selected character's type (null: none), needed when starting from it.
 */
export function checkOptimizeForm(form: OptimizeForm, schema: OptimizerSchema, selected: CharacterType | null): Checked {
  const problems: FieldProblem[] = [];
  const character = checkChoice<CharacterType>(form, 'character', CHARACTER_TYPES, problems);
  const method = checkChoice<Method>(form, 'method', METHODS, problems);
  const start = checkChoice<StartFrom>(form, 'start', START_FROM, problems);
  if (start === 'selected') {
    if (selected === null) {
      problems.push({ field: 'start', message: 'start: no character is selected (click one, or start from the preset)' });
    } else if (problems.every((p) => p.field !== 'character') && selected !== character) {
      problems.push({ field: 'start', message: `start: the selected character is a ${selected}, not a ${character}` });
    }
  }
  const search = {} as Record<keyof typeof SEARCH_FIELDS, number>;
  for (const [field, f] of Object.entries(SEARCH_FIELDS) as [keyof typeof SEARCH_FIELDS, (typeof SEARCH_FIELDS)[keyof typeof SEARCH_FIELDS]][]) {
    search[field] = checkNumber(form, field, f.label, { ...f, integer: true }, problems);
  }
  const settings: Record<string, number> = {};
  for (const spec of schema.settings) {
    settings[spec.name] = checkNumber(form, spec.name, spec.name, spec, problems);
  }
  const speeds: number[] = [];
  const speedText = String(form.speeds ?? '').trim();
  if (speedText === '') {
    problems.push({ field: 'speeds', message: 'speeds: give at least one goal speed (m/s), e.g. 1 or 0.5, 1' });
  } else {
    for (const part of speedText.split(',')) {
      const speed = checkNumber({ speeds: part }, 'speeds', 'speeds', schema.speeds, problems);
      speeds.push(speed);
    }
  }
  if (problems.length > 0) return { ok: false, problems };
  return { ok: true, options: { character, method, start, ...search, settings, speeds } };
}

/** The form as it starts: the module's defaults, and a small search. */
export function defaultForm(schema: OptimizerSchema, threads: number): Record<string, string> {
  const form: Record<string, string> = {
    character: 'biped',
    method: 'greedy',
    start: 'preset',
    generations: '20',
    candidates: '10',
    seed: '1',
    threads: String(threads),
    speeds: schema.speeds.default.join(', '),
  };
  for (const s of schema.settings) form[s.name] = String(Number(s.default.toPrecision(6)));
  return form;
}

/**
 * Seconds the rest of a search should take: the mean of the last few generations' times (a
 * generation's cost changes as the search goes: a candidate that falls ends its episode early,
 * one that walks runs the whole episode) times the generations left. Null before the first.
 */
export function estimateSecondsLeft(secondsPerGeneration: readonly number[], total: number, window = 5): number | null {
  const done = secondsPerGeneration.length;
  if (done === 0) return null;
  const recent = secondsPerGeneration.slice(-Math.max(1, window));
  const mean = recent.reduce((a, b) => a + b, 0) / recent.length;
  return Math.max(0, total - done) * mean;
}

/** A duration for people: "0.4 s", "12 s", "3 min 5 s", "1 h 2 min". */
export function formatDuration(seconds: number): string {
  if (!Number.isFinite(seconds) || seconds < 0) return '–';
  if (seconds < 10) return `${seconds.toFixed(1)} s`;
  const s = Math.round(seconds);
  if (s < 60) return `${s} s`;
  if (s < 3600) return `${Math.floor(s / 60)} min${s % 60 ? ` ${s % 60} s` : ''}`;
  const m = Math.round(s / 60);
  return `${Math.floor(m / 60)} h${m % 60 ? ` ${m % 60} min` : ''}`;
}

