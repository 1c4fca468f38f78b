// The creature designer's drawing: the design's side and top views (creature/blueprint.ts), to
// scale, with round handles to drag. A drag changes the setting its handle stands for at once
// (the sliders follow, and the preview in the scene is replaced after the designer's pause); a
// handle stops at its slider's range. The scale is kept while a handle is held, so the drawing
// does not move under the pointer, and fitted again when it is let go.
import { blueprint, dragTo, type Blueprint, type Box, type Handle, type Point, type View } from '../creature/blueprint';
import type { CreatureDesign } from '../creature/design';

/** CSS pixels. */
const HEIGHT = 150;
/** The side view's share of the width; the top view has the rest. */
const SIDE_SHARE = 0.62;
/** Around each view, CSS px. */
const MARGIN = 10;
/** A handle's radius, and how near the pointer (a finger: further) must be to take it, CSS px. */
const HANDLE_RADIUS = 5;
const REACH = { mouse: 12, touch: 22 };
const INK = '#e8e8e8';
const HANDLE_FILL = '#ffffff';
const HELD_FILL = '#f5c542';

/** Where each view is drawn: metres to CSS pixels. */
interface Frame {
  /** CSS px per metre. */
  scale: number;
  /** Where the view's origin is, CSS px. */
  side: Point;
  top: Point;
}

export class DesignBlueprint {
  readonly element: HTMLElement;
  private readonly canvas: HTMLCanvasElement;
  private design: CreatureDesign | null = null;
  private drawn: Blueprint | null = null;
  private frame: Frame | null = null;
  private held: Handle | null = null;
  private hover: Handle | null = null;

  constructor(private readonly onDrag: (change: Partial<CreatureDesign>) => void) {
    this.element = document.createElement('div');
    this.element.className = 'designer-blueprint';
    this.canvas = document.createElement('canvas');
    this.canvas.style.height = `${HEIGHT}px`;
    this.canvas.setAttribute('data-testid', 'designer-blueprint');
    this.canvas.setAttribute('role', 'img');
    this.canvas.setAttribute('aria-label', 'the body from the side and from above; drag the round handles to change it');
    this.element.append(this.canvas);
    this.canvas.addEventListener('pointerdown', (e) => this.down(e));
    this.canvas.addEventListener('pointermove', (e) => this.move(e));
    this.canvas.addEventListener('pointerup', (e) => this.up(e));
    this.canvas.addEventListener('pointercancel', (e) => this.up(e));
    // Drawn again when it gets its width (the folder opens) or the panel changes size.
    new ResizeObserver(() => this.draw()).observe(this.canvas);
  }

  /** Shows `design` (the fit is kept while a handle is held). */
  show(design: CreatureDesign): void {
    this.design = design;
    this.drawn = blueprint(design);
    if (!this.held) this.frame = null;
    this.draw();
  }

  /**
   * Where handle `name` is now in the page (CSS px, as a pointer event's clientX and clientY),
   * or null when the design has no such handle or the drawing is not shown: what a test drags.
   */
  handlePosition(name: string): Point | null {
    const h = this.handles().find((x) => x.name === name);
    if (!h || !this.frame || this.canvas.clientWidth === 0) return null;
    const r = this.canvas.getBoundingClientRect();
    const p = this.toCanvas(h);
    return { x: r.left + p.x, y: r.top + p.y };
  }

  private handles(): Handle[] {
    return this.drawn ? [...this.drawn.side.handles, ...this.drawn.top.handles] : [];
  }

  /** The scale that fits both views, each in its part of the canvas. */
  private fit(width: number): Frame {
    const b = this.drawn!;
    const bounds = (view: View) => {
      const points: Point[] = [...view.handles.map((h) => h.at)];
      const box = (x: Box) => points.push({ x: x.centre.x - x.half.x, y: x.centre.y - x.half.y }, { x: x.centre.x + x.half.x, y: x.centre.y + x.half.y });
      view.boxes.forEach(box);
      for (const leg of view.legs) {
        points.push(...leg.joints);
        box(leg.foot);
      }
      const xs = points.map((p) => p.x);
      const ys = points.map((p) => p.y);
      return { minX: Math.min(...xs), maxX: Math.max(...xs), minY: Math.min(...ys), maxY: Math.max(...ys) };
    };
    const side = bounds(b.side);
    const top = bounds(b.top);
    const sideWidth = width * SIDE_SHARE;
    const scale = Math.min(
      (sideWidth - 2 * MARGIN) / Math.max(side.maxX - side.minX, 1e-3),
      (HEIGHT - 2 * MARGIN) / Math.max(side.maxY - side.minY, 1e-3),
      (width - sideWidth - 2 * MARGIN) / Math.max(top.maxX - top.minX, 1e-3),
      (HEIGHT - 2 * MARGIN) / Math.max(top.maxY - top.minY, 1e-3),
    );
    // Each view centred in its part; y grows downwards on the canvas.
    return {
      scale,
      side: { x: sideWidth / 2 - ((side.minX + side.maxX) / 2) * scale, y: HEIGHT / 2 + ((side.minY + side.maxY) / 2) * scale },
      top: { x: sideWidth + (width - sideWidth) / 2 - ((top.minX + top.maxX) / 2) * scale, y: HEIGHT / 2 + ((top.minY + top.maxY) / 2) * scale },
    };
  }

  private toCanvas(h: { view: 'side' | 'top'; at: Point }): Point {
    const f = this.frame!;
    const o = h.view === 'side' ? f.side : f.top;
    return { x: o.x + h.at.x * f.scale, y: o.y - h.at.y * f.scale };
  }

  private toView(view: 'side' | 'top', p: Point): Point {
    const f = this.frame!;
    const o = view === 'side' ? f.side : f.top;
    return { x: (p.x - o.x) / f.scale, y: (o.y - p.y) / f.scale };
  }

  private draw(): void {
    const width = this.canvas.clientWidth;
    if (!this.drawn || width === 0) return;
    const ratio = window.devicePixelRatio || 1;
    this.canvas.width = Math.round(width * ratio);
    this.canvas.height = Math.round(HEIGHT * ratio);
    this.frame ??= this.fit(width);
    const g = this.canvas.getContext('2d');
    if (!g) return;
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, width, HEIGHT);
    const f = this.frame;
    const drawView = (name: 'side' | 'top', view: View) => {
      const at = (p: Point) => this.toCanvas({ view: name, at: p });
      const box = (b: Box, alpha = 1) => {
        const c = at({ x: b.centre.x - b.half.x, y: b.centre.y + b.half.y });
        g.globalAlpha = alpha;
        g.fillStyle = b.colour;
        g.fillRect(c.x, c.y, 2 * b.half.x * f.scale, 2 * b.half.y * f.scale);
        g.globalAlpha = 1;
      };
      if (view.ground !== null) {
        const y = at({ x: 0, y: view.ground }).y;
        g.strokeStyle = '#777';
        g.lineWidth = 1;
        g.beginPath();
        g.moveTo(name === 'side' ? 0 : width * SIDE_SHARE, y);
        g.lineTo(name === 'side' ? width * SIDE_SHARE : width, y);
        g.stroke();
      }
      // From above, the feet under the body; from the side, the legs over it.
      if (name === 'top') for (const leg of view.legs) box(leg.foot);
      for (const b of view.boxes) box(b, name === 'top' ? 0.85 : 1);
      for (const leg of view.legs) {
        g.strokeStyle = leg.colour;
        g.lineWidth = Math.max(2, 0.04 * f.scale);
        g.lineCap = 'round';
        g.beginPath();
        leg.joints.forEach((p, k) => (k === 0 ? g.moveTo(at(p).x, at(p).y) : g.lineTo(at(p).x, at(p).y)));
        g.stroke();
        if (name === 'side') box(leg.foot);
        else {
          const hip = at(leg.joints[0]);
          g.fillStyle = leg.colour;
          g.beginPath();
          g.arc(hip.x, hip.y, 3, 0, 2 * Math.PI);
          g.fill();
        }
      }
      for (const h of view.handles) {
        const p = at(h.at);
        g.fillStyle = h === this.held ? HELD_FILL : HANDLE_FILL;
        g.strokeStyle = '#222';
        g.lineWidth = h === this.hover || h === this.held ? 2.5 : 1.5;
        g.beginPath();
        g.arc(p.x, p.y, HANDLE_RADIUS, 0, 2 * Math.PI);
        g.fill();
        g.stroke();
      }
    };
    drawView('side', this.drawn.side);
    drawView('top', this.drawn.top);
    g.fillStyle = INK;
    g.font = '10px system-ui, sans-serif';
    g.fillText('side', 4, 12);
    g.fillText('above', width * SIDE_SHARE + 4, 12);
  }

  /** The handle under `e`, if one is within reach. */
  private pick(e: PointerEvent): Handle | null {
    if (!this.frame) return null;
    const r = this.canvas.getBoundingClientRect();
    const p = { x: e.clientX - r.left, y: e.clientY - r.top };
    let best: Handle | null = null;
    let nearest = e.pointerType === 'touch' ? REACH.touch : REACH.mouse;
    for (const h of this.handles()) {
      const c = this.toCanvas(h);
      const d = Math.hypot(c.x - p.x, c.y - p.y);
      if (d <= nearest) {
        nearest = d;
        best = h;
      }
    }
    return best;
  }

  private down(e: PointerEvent): void {
    const h = this.pick(e);
    if (!h) return;
    this.held = h;
    this.canvas.setPointerCapture(e.pointerId);
    e.preventDefault();
    this.draw();
  }

  private move(e: PointerEvent): void {
    if (!this.held) {
      const h = this.pick(e);
      if (h !== this.hover) {
        this.hover = h;
        this.canvas.style.cursor = h ? 'grab' : '';
        this.canvas.title = h ? h.label : '';
        this.draw();
      }
      return;
    }
    if (!this.design || !this.frame) return;
    const r = this.canvas.getBoundingClientRect();
    const point = this.toView(this.held.view, { x: e.clientX - r.left, y: e.clientY - r.top });
    const change = dragTo(this.design, this.held.name, point);
    const setting = this.held.setting;
    if (change[setting] !== undefined && change[setting] !== this.design[setting]) {
      const name = this.held.name;
      this.onDrag(change);
      // The designer shows the new design (show()); the held handle is the same one in it.
      this.held = this.handles().find((x) => x.name === name) ?? null;
      this.draw();
    }
  }

  private up(e: PointerEvent): void {
    if (!this.held) return;
    this.held = null;
    if (this.canvas.hasPointerCapture(e.pointerId)) this.canvas.releasePointerCapture(e.pointerId);
    this.frame = null;
    this.draw();
  }
}
