// Smoothed rate of a growing quantity per wall-clock second: frames per second, or simulated
// seconds per wall second (the real-time factor: 1 = real time, 0.5 = half speed).
//
// The rate is measured over windows of at least `window` seconds (a single frame's delta is too
// noisy: timers and vsync jitter) and the windows are blended exponentially so the overlay reads
// steadily but still follows a change within a few seconds.

export class RateMeter {
  private readonly window: number;
  private readonly blend: number;
  private startValue = 0;
  private startTime: number | null = null;
  private smoothed: number | null = null;

  /**
   * @param window seconds per measurement
   * @param blend weight of a new measurement in the smoothed rate (1 = no smoothing)
   */
  constructor(window = 0.5, blend = 0.5) {
    this.window = window;
    this.blend = blend;
  }

  /** Forgets history: the next samples start a new measurement (e.g. after a reset). */
  reset(): void {
    this.startTime = null;
    this.smoothed = null;
  }

  /** Records that the quantity is `value` at wall time `now` (seconds). */
  sample(value: number, now: number): void {
    if (this.startTime === null || value < this.startValue || now < this.startTime) {
      // First sample, or the quantity went backwards (a new simulation): start over from here.
      if (this.startTime !== null) this.smoothed = null;
      this.startValue = value;
      this.startTime = now;
      return;
    }
    const elapsed = now - this.startTime;
    if (elapsed < this.window) return;
    const rate = (value - this.startValue) / elapsed;
    this.smoothed = this.smoothed === null ? rate : this.smoothed + this.blend * (rate - this.smoothed);
    this.startValue = value;
    this.startTime = now;
  }

  /** The smoothed rate, or 0 before the first full window. */
  get rate(): number {
    return this.smoothed ?? 0;
  }
}
