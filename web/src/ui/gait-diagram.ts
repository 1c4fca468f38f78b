// The gait diagram (thesis Figure 2.1): one bar per leg over one gait cycle, filled while the leg
// is in stance. A leg lifts off at its step trigger (the gait phase of lift-off, §3.1.1) and is
// in swing for 1 − D of the cycle, D being its duty factor, so its stance runs from
// trigger + 1 − D to trigger + 1 (mod 1).
//
// Drag a bar's right end (lift-off) to move the step trigger with the touch-down fixed, its left
// end (touch-down) to change the duty factor with the lift-off fixed, its middle to shift the
// whole stance in the cycle.

export interface LegTiming {
  /** The leg's name, as the schema's morphology gives it (e.g. "frontLeft"). */
  leg: string;
  dutyFactor: number;
  stepTrigger: number;
}

export interface GaitDiagramOptions {
  legs: LegTiming[];
  dutyBounds: [number, number];
  onEditStart(): void;
  onChange(legs: LegTiming[], done: boolean): void;
}

const WIDTH = 340;
const ROW = 20;
const LABEL = 70;
const PAD = 6;
/** Pointer distance (px) within which a press grabs a bar's end rather than its middle. */
const GRAB = 7;

const frac = (x: number) => x - Math.floor(x);

/** Stance of a leg as phases in [0, 1): touch-down `start` and lift-off `end` (end < start when it wraps). */
export function stanceOf(l: LegTiming): { start: number; end: number } {
  return { start: frac(l.stepTrigger + 1 - l.dutyFactor), end: frac(l.stepTrigger) };
}

/**
 * A leg's timing after dragging part of its stance bar to gait phase `phase`: its lift-off end
 * ('end': touch-down stays), its touch-down end ('start': lift-off stays) or the whole bar
 * ('move', grabbed at `grabPhase`: duty factor stays). Duty factors stay within `bounds`.
 */
export function dragTiming(
  original: LegTiming,
  what: 'start' | 'end' | 'move',
  phase: number,
  grabPhase: number,
  [lo, hi]: [number, number],
): LegTiming {
  const clampDuty = (d: number) => Math.min(hi, Math.max(lo, d));
  if (what === 'end') {
    const touchDown = stanceOf(original).start;
    // A zero-length stance is read as a whole cycle (then clamped), never as nothing.
    const duty = clampDuty(frac(phase - touchDown) || 1);
    return { ...original, dutyFactor: duty, stepTrigger: frac(touchDown + duty) };
  }
  if (what === 'start') return { ...original, dutyFactor: clampDuty(frac(original.stepTrigger - phase) || 1) };
  return { ...original, stepTrigger: frac(original.stepTrigger + phase - grabPhase) };
}

export class GaitDiagram {
  readonly element: HTMLElement;
  private readonly canvas: HTMLCanvasElement;
  private legs: LegTiming[];
  private phase: number | null = null;
  private drag: { leg: number; what: 'start' | 'end' | 'move'; grabPhase: number; original: LegTiming } | null = null;

  constructor(private readonly options: GaitDiagramOptions) {
    this.legs = options.legs.map((l) => ({ ...l }));
    this.element = document.createElement('div');
    this.element.className = 'gait-diagram';
    const title = document.createElement('h3');
    title.textContent = 'gait diagram (stance over one cycle)';
    title.title = 'Thesis Figure 2.1. Drag a bar’s right end to move the lift-off (step trigger), its left end to change the duty factor, its middle to shift it.';
    this.canvas = document.createElement('canvas');
    const height = this.height();
    this.canvas.width = WIDTH * 2;
    this.canvas.height = height * 2;
    this.canvas.style.height = `${height}px`;
    this.canvas.setAttribute('aria-label', 'gait diagram: drag the ends of the stance bars');
    this.element.append(title, this.canvas);
    this.canvas.addEventListener('pointerdown', (e) => this.down(e));
    this.canvas.addEventListener('pointermove', (e) => this.move(e));
    this.canvas.addEventListener('pointerup', (e) => this.up(e));
    this.canvas.addEventListener('pointercancel', (e) => this.up(e));
    this.draw();
  }

  /** Shows new timings; a drag in progress keeps its bar unless `force` (as CurveEditor.set). */
  set(legs: LegTiming[], force = false): void {
    if (this.drag && !force) return;
    this.legs = legs.map((l) => ({ ...l }));
    this.draw();
  }

  setPhase(phase: number | null): void {
    if (phase === this.phase) return;
    this.phase = phase;
    this.draw();
  }

  private height(): number {
    return PAD * 2 + ROW * this.legs.length;
  }

  private x(phase: number): number {
    return LABEL + (WIDTH - LABEL - PAD) * phase;
  }

  private phaseAt(x: number): number {
    return Math.min(1, Math.max(0, (x - LABEL) / (WIDTH - LABEL - PAD)));
  }

  /** Stance start (touch-down) and end (lift-off) as phases in [0, 1), end possibly < start (wraps). */
  private stance(l: LegTiming): { start: number; end: number } {
    return stanceOf(l);
  }

  private local(e: PointerEvent) {
    const rect = this.canvas.getBoundingClientRect();
    return { x: ((e.clientX - rect.left) / rect.width) * WIDTH, y: ((e.clientY - rect.top) / rect.height) * this.height() };
  }

  private down(e: PointerEvent): void {
    const p = this.local(e);
    const leg = Math.floor((p.y - PAD) / ROW);
    if (leg < 0 || leg >= this.legs.length || p.x < LABEL - GRAB) return;
    const l = this.legs[leg];
    const { start, end } = this.stance(l);
    const near = (phase: number) => Math.min(Math.abs(this.x(phase) - p.x), Math.abs(this.x(phase + (phase < 0.5 ? 1 : -1)) - p.x));
    const what = near(end) <= GRAB ? 'end' : near(start) <= GRAB ? 'start' : 'move';
    this.drag = { leg, what, grabPhase: this.phaseAt(p.x), original: { ...l } };
    this.canvas.setPointerCapture(e.pointerId);
    this.options.onEditStart();
  }

  private move(e: PointerEvent): void {
    const d = this.drag;
    if (!d) return;
    const phase = this.phaseAt(this.local(e).x);
    this.legs[d.leg] = dragTiming(d.original, d.what, phase, d.grabPhase, this.options.dutyBounds);
    this.draw();
    this.options.onChange(this.legs.map((x) => ({ ...x })), false);
  }

  private up(e: PointerEvent): void {
    if (!this.drag) return;
    this.drag = null;
    if (this.canvas.hasPointerCapture(e.pointerId)) this.canvas.releasePointerCapture(e.pointerId);
    this.options.onChange(this.legs.map((x) => ({ ...x })), true);
  }

  private draw(): void {
    const ctx = this.canvas.getContext('2d');
    if (!ctx) return;
    const height = this.height();
    ctx.setTransform(2, 0, 0, 2, 0, 0);
    ctx.clearRect(0, 0, WIDTH, height);
    ctx.fillStyle = '#f4f6f8';
    ctx.fillRect(0, 0, WIDTH, height);
    ctx.font = '11px system-ui, sans-serif';
    ctx.textBaseline = 'middle';
    this.legs.forEach((l, i) => {
      const y = PAD + i * ROW;
      ctx.fillStyle = '#3a444e';
      ctx.fillText(l.leg, 4, y + ROW / 2);
      ctx.fillStyle = '#dde3e9';
      ctx.fillRect(this.x(0), y + 3, this.x(1) - this.x(0), ROW - 6);
      const { start, end } = this.stance(l);
      ctx.fillStyle = '#2f6db5';
      // A stance that wraps past the end of the cycle is drawn in two pieces.
      const pieces = end > start ? [[start, end]] : [[start, 1], [0, end]];
      for (const [a, b] of pieces) ctx.fillRect(this.x(a), y + 3, this.x(b) - this.x(a), ROW - 6);
      ctx.fillStyle = '#1c4a80';
      ctx.fillRect(this.x(end) - 1.5, y + 1, 3, ROW - 2); // lift-off handle
    });
    if (this.phase !== null) {
      ctx.strokeStyle = '#ff7a1a';
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      ctx.moveTo(this.x(this.phase), 2);
      ctx.lineTo(this.x(this.phase), height - 2);
      ctx.stroke();
    }
  }
}
