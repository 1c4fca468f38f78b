// Real-time pacing of the fixed-step simulation (docs/design.md: fixed step of 1/120 s).
//
// Wall time is accumulated and spent in whole fixed steps, so simulated time follows the wall
// clock however irregularly the worker's timer fires. When the machine cannot keep up, the
// catch-up per tick is capped and the backlog beyond it is dropped: the simulation then runs
// slower than real time instead of spiralling (each late tick asking for ever more steps, which
// make the next tick later still).

export interface FixedStepClockOptions {
  /** Simulated seconds per fixed step. */
  step: number;
  /** Most steps one tick may ask for; any further backlog is dropped. */
  maxStepsPerTick: number;
}

export interface Tick {
  /** Whole fixed steps to take now (0 … maxStepsPerTick). */
  steps: number;
  /** Steps owed that were given up because they exceeded maxStepsPerTick. */
  dropped: number;
  /** Wall seconds until the next step is due (when to schedule the next tick). */
  wait: number;
}

export class FixedStepClock {
  readonly step: number;
  readonly maxStepsPerTick: number;
  /** Wall seconds owed to the simulation, not yet covered by steps. */
  private owed = 0;
  /** Wall clock (seconds) at the previous tick; null when stopped. */
  private last: number | null = null;

  constructor({ step, maxStepsPerTick }: FixedStepClockOptions) {
    if (!(step > 0)) throw new RangeError(`step must be positive, got ${step}`);
    if (!(Number.isInteger(maxStepsPerTick) && maxStepsPerTick >= 1)) {
      throw new RangeError(`maxStepsPerTick must be a positive integer, got ${maxStepsPerTick}`);
    }
    this.step = step;
    this.maxStepsPerTick = maxStepsPerTick;
  }

  /**
   * (Re)starts timing at wall time `now` (seconds) with nothing owed — after creation, a pause
   * or a reset, so that the time spent away is not caught up.
   */
  start(now: number): void {
    this.last = now;
    this.owed = 0;
  }

  /** Stops timing (pause); tick() takes no steps until start() is called again. */
  stop(): void {
    this.last = null;
    this.owed = 0;
  }

  get running(): boolean {
    return this.last !== null;
  }

  /** Accounts for the wall time since the previous tick and says how many steps to take now. */
  tick(now: number): Tick {
    if (this.last === null) return { steps: 0, dropped: 0, wait: this.step };
    // A clock that went backwards (it should not) counts as no time passing.
    this.owed += Math.max(0, now - this.last);
    this.last = now;
    // The small epsilon keeps float round-off from leaving a step owed by 1e-17 s.
    const owedSteps = Math.floor(this.owed / this.step + 1e-9);
    const steps = Math.min(owedSteps, this.maxStepsPerTick);
    const dropped = owedSteps - steps;
    this.owed = Math.max(0, this.owed - owedSteps * this.step);
    return { steps, dropped, wait: Math.max(0, this.step - this.owed) };
  }
}
