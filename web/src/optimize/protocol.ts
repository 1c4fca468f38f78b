// Messages between the optimize panel (main thread) and the optimizer worker.
import type { OptimizeOptions } from './options';

/** Main thread → optimizer worker. One worker runs one search; Stop terminates it. */
export type OptimizerCommand = {
  type: 'start';
  /** URL of the ES6 WASM glue, as the sim worker gets it. */
  wasmUrl: string;
  options: OptimizeOptions;
  /** The gait file to start from (the selected character's), or null for the preset. */
  startJson: string | null;
  /** A creature file's text whose body the search learns for (the designer's), or null. */
  creature: string | null;
};

/** One generation done (gl_opt_step returned). */
export interface GenerationReport {
  /** 1-based. */
  generation: number;
  /** Evaluations so far (K per generation). */
  evaluations: number;
  /** Best objective so far, after this generation (eq. 3.10, lower is better). */
  best: number;
  /** Wall-clock seconds of this generation in the worker. */
  seconds: number;
  /** Whether this generation found a better candidate (the first always reports one). */
  improved: boolean;
  /** The best parameters as a gait file's JSON (gl_opt_best_json), when they changed; else null. */
  gait: string | null;
}

/** Optimizer worker → main thread. */
export type OptimizerEvent =
  /** The module is loaded and the search created; `loadSeconds` is how long that took. */
  | { type: 'started'; loadSeconds: number }
  | ({ type: 'generation' } & GenerationReport)
  /** Every generation asked for is done. */
  | { type: 'done' }
  | { type: 'error'; message: string };
