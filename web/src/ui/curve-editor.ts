// Editor of one motion graph (thesis §3.3): a piecewise-linear function with 4 knots at
// φ = 0, 1/3, 2/3, 1 (native/src/gait/graph.h). Drag a knot up or down, or type its value;
// a typed value outside the schema's bounds is refused (field-check.ts), a dragged one stops at
// them. A vertical line marks the current phase.
import { readNumberField, showFieldMessage } from './field-check';

export interface CurveEditorOptions {
  name: string;
  description: string;
  unit: string;
  min: number;
  max: number;
  values: number[];
  /** Called while a knot moves (live) and when it is let go (`done`). */
  onChange(values: number[], done: boolean): void;
  /** Called when a drag or a typed edit starts: the moment to remember the state for undo. */
  onEditStart(): void;
}

const WIDTH = 340;
const HEIGHT = 84;
const PAD = { left: 8, right: 8, top: 8, bottom: 8 };
const KNOT_RADIUS = 5;

export class CurveEditor {
  readonly element: HTMLElement;
  private readonly canvas: HTMLCanvasElement;
  private readonly inputs: HTMLInputElement[] = [];
  private values: number[];
  private phase: number | null = null;
  private dragging = -1;

  constructor(private readonly options: CurveEditorOptions) {
    this.values = [...options.values];
    this.element = document.createElement('div');
    this.element.className = 'curve-editor';
    this.element.dataset.param = options.name;
    const title = document.createElement('h3');
    title.textContent = `${options.name}${options.unit ? ` (${options.unit})` : ''}`;
    title.title = options.description;
    this.canvas = document.createElement('canvas');
    this.canvas.width = WIDTH * 2; // drawn at 2× for sharpness
    this.canvas.height = HEIGHT * 2;
    this.canvas.style.height = `${HEIGHT}px`;
    this.canvas.title = options.description;
    this.canvas.setAttribute('aria-label', `${options.name}: drag the knots`);
    const inputs = document.createElement('div');
    inputs.className = 'knot-inputs';
    for (let k = 0; k < this.values.length; k++) {
      const input = document.createElement('input');
      input.type = 'number';
      input.step = 'any';
      input.min = String(options.min);
      input.max = String(options.max);
      input.setAttribute('aria-label', `${options.name} knot ${k + 1} (φ = ${['0', '⅓', '⅔', '1'][k] ?? k})`);
      input.addEventListener('change', () => {
        // Refused (empty, not a number, out of range): a message beside the fields, nothing
        // changes, and the field shows the value applied (field-check.ts).
        const reading = readNumberField(input.value, options.min, options.max);
        if ('error' in reading) {
          showFieldMessage(inputs, `${options.name} knot ${k + 1}: ${reading.error}; not applied`);
          input.value = String(Number(this.values[k].toPrecision(5)));
          return;
        }
        showFieldMessage(inputs, null);
        options.onEditStart();
        this.values[k] = reading.value;
        this.syncInputs(true);
        this.draw();
        options.onChange([...this.values], true);
      });
      this.inputs.push(input);
      inputs.append(input);
    }
    this.element.append(title, this.canvas, inputs);
    this.canvas.addEventListener('pointerdown', (e) => this.down(e));
    this.canvas.addEventListener('pointermove', (e) => this.move(e));
    this.canvas.addEventListener('pointerup', (e) => this.up(e));
    this.canvas.addEventListener('pointercancel', (e) => this.up(e));
    this.syncInputs();
    this.draw();
  }

  /**
   * Shows new values (after undo, a preset, another character) without reporting a change. A
   * drag in progress keeps its knot unless `force` (the simulation refused the drag's edit: the
   * editor must show what the simulation has).
   */
  set(values: number[], force = false): void {
    if (this.dragging >= 0 && !force) return;
    this.values = [...values];
    // Every field, the focused one too: after an undo in a field it shows the value undone.
    this.syncInputs(true);
    this.draw();
  }

  /** Moves the phase marker (null hides it). */
  setPhase(phase: number | null): void {
    if (phase === this.phase) return;
    this.phase = phase;
    this.draw();
  }

  private clamp(v: number): number {
    return Math.min(this.options.max, Math.max(this.options.min, v));
  }

  /** The fields show the values (`all`: the focused one too, after its own edit was applied). */
  private syncInputs(all = false): void {
    this.inputs.forEach((input, k) => {
      if (all || document.activeElement !== input) input.value = String(Number(this.values[k].toPrecision(5)));
    });
  }

  private x(k: number): number {
    return PAD.left + ((WIDTH - PAD.left - PAD.right) * k) / (this.values.length - 1);
  }

  private y(v: number): number {
    const { min, max } = this.options;
    const t = max > min ? (v - min) / (max - min) : 0.5;
    return HEIGHT - PAD.bottom - t * (HEIGHT - PAD.top - PAD.bottom);
  }

  private valueAt(y: number): number {
    const { min, max } = this.options;
    const t = (HEIGHT - PAD.bottom - y) / (HEIGHT - PAD.top - PAD.bottom);
    return this.clamp(min + t * (max - min));
  }

  private local(e: PointerEvent): { x: number; y: number } {
    const rect = this.canvas.getBoundingClientRect();
    return { x: ((e.clientX - rect.left) / rect.width) * WIDTH, y: ((e.clientY - rect.top) / rect.height) * HEIGHT };
  }

  private down(e: PointerEvent): void {
    const p = this.local(e);
    // The knot nearest in x: knots only move vertically, so x alone picks one.
    let nearest = 0;
    for (let k = 1; k < this.values.length; k++) if (Math.abs(this.x(k) - p.x) < Math.abs(this.x(nearest) - p.x)) nearest = k;
    this.dragging = nearest;
    this.canvas.setPointerCapture(e.pointerId);
    this.options.onEditStart();
    this.move(e);
  }

  private move(e: PointerEvent): void {
    if (this.dragging < 0) return;
    this.values[this.dragging] = this.valueAt(this.local(e).y);
    this.syncInputs();
    this.draw();
    this.options.onChange([...this.values], false);
  }

  private up(e: PointerEvent): void {
    if (this.dragging < 0) return;
    this.dragging = -1;
    if (this.canvas.hasPointerCapture(e.pointerId)) this.canvas.releasePointerCapture(e.pointerId);
    this.options.onChange([...this.values], true);
  }

  private draw(): void {
    const ctx = this.canvas.getContext('2d');
    if (!ctx) return;
    ctx.setTransform(2, 0, 0, 2, 0, 0);
    ctx.clearRect(0, 0, WIDTH, HEIGHT);
    ctx.fillStyle = '#f4f6f8';
    ctx.fillRect(0, 0, WIDTH, HEIGHT);
    // Zero line, if zero is within the bounds.
    const { min, max } = this.options;
    if (min < 0 && max > 0) {
      ctx.strokeStyle = '#c3cad2';
      ctx.beginPath();
      ctx.moveTo(PAD.left, this.y(0));
      ctx.lineTo(WIDTH - PAD.right, this.y(0));
      ctx.stroke();
    }
    if (this.phase !== null) {
      ctx.strokeStyle = '#ff7a1a';
      ctx.lineWidth = 1.5;
      const x = PAD.left + (WIDTH - PAD.left - PAD.right) * this.phase;
      ctx.beginPath();
      ctx.moveTo(x, PAD.top - 4);
      ctx.lineTo(x, HEIGHT - PAD.bottom + 4);
      ctx.stroke();
    }
    ctx.strokeStyle = '#2f6db5';
    ctx.lineWidth = 2;
    ctx.beginPath();
    this.values.forEach((v, k) => (k === 0 ? ctx.moveTo(this.x(k), this.y(v)) : ctx.lineTo(this.x(k), this.y(v))));
    ctx.stroke();
    ctx.fillStyle = '#2f6db5';
    this.values.forEach((v, k) => {
      ctx.beginPath();
      ctx.arc(this.x(k), this.y(v), KNOT_RADIUS, 0, Math.PI * 2);
      ctx.fill();
    });
  }
}
