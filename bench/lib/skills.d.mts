// Types of bench/lib/skills.mjs for the TypeScript tests (tests/web/bench/skills.test.ts).
export interface SweepRow {
  goal: number;
  fell: boolean;
  fall_time_s: number | null;
  mean_speed_m_s: number;
  footfall: string;
  duty_factor_measured: number[];
  flight_fraction: number;
  standing_fraction: number;
}
export interface SkillCheck { what: string; ok: boolean; value: string }
export const WALK_RANGE: [number, number];
export const RUN_FROM: number;
export const TROT_TO: number;
export const GALLOP_FROM: number;
export const FLIGHT: number;
export const STAND_SHARE: number;
export const GET_UP_SECONDS: number;
export const GET_UP_SHARE: number;
/** A box-hit trial of the walking benchmark: its falls and, watched, how many it got up from. */
export interface BoxTrial { speed: number; falls: number; get_ups?: number; get_up_median_s?: number | null }
export function skillChecks(
  character: 'biped' | 'quadruped',
  sweep: { step: number; rows: SweepRow[] },
  skills: { pace?: Array<{ goal: number; fell: boolean; fall_time_s: number | null; mean_speed_m_s: number; footfall: string }> } | null,
  options: { seconds: number; paceFile: string; paceSpeeds: number[] },
  boxes?: { trials: BoxTrial[] } | null,
): SkillCheck[];
