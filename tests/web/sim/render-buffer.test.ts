// The render-buffer reader against hand-built memory laid out like native/src/sim/render_buffer.h,
// written by a JavaScript copy of the C++ writer (Simulation::publish).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { Worker } from 'node:worker_threads';
import { describe, expect, it } from 'vitest';
import { BODY_INFO, HEADER, MATRIX_FLOATS, RenderBufferReader } from '../../../web/src/sim/render-buffer';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../..');

/** Where the test puts the header: not at 0, and 8-aligned as a C++ struct with a double is. */
const HEADER_AT = 64;

/** Memory holding a render buffer for `capacity` bodies, laid out as Simulation's constructor does. */
function layout(capacity: number, memory: ArrayBufferLike = new ArrayBuffer(bytesFor(capacity))) {
  const u32 = new Uint32Array(memory);
  const h = HEADER_AT / 4;
  const matrixBytes = capacity * MATRIX_FLOATS * 4;
  u32[h + HEADER.capacity / 4] = capacity;
  u32[h + HEADER.matrices / 4] = HEADER.size;
  u32[h + HEADER.matrices / 4 + 1] = HEADER.size + matrixBytes;
  u32[h + HEADER.info / 4] = HEADER.size + 2 * matrixBytes;
  return memory;
}

function bytesFor(capacity: number): number {
  const bytes = HEADER_AT + HEADER.size + capacity * (2 * MATRIX_FLOATS * 4 + BODY_INFO.size);
  return Math.ceil(bytes / 8) * 8;
}

/** The writer side, as in Simulation::publish: seq is odd while a frame is being written. */
class Writer {
  private readonly u32: Uint32Array;
  private readonly f32: Float32Array;
  private readonly f64: Float64Array;
  private readonly h = HEADER_AT / 4;
  private back = 0;
  step = 0;

  constructor(memory: ArrayBufferLike) {
    this.u32 = new Uint32Array(memory);
    this.f32 = new Float32Array(memory);
    this.f64 = new Float64Array(memory);
  }

  /** Starts a frame: every matrix element of every body is `value`. */
  begin(bodies: number, value: number): void {
    this.back = 1 - Atomics.load(this.u32, this.h + HEADER.front / 4);
    Atomics.add(this.u32, this.h + HEADER.seq / 4, 1);
    const start = (HEADER_AT + this.u32[this.h + HEADER.matrices / 4 + this.back]) / 4;
    this.f32.fill(value, start, start + bodies * MATRIX_FLOATS);
    this.u32[this.h + HEADER.bodyCount / 4 + this.back] = bodies;
  }

  /** Publishes the frame begun last. */
  end(): void {
    this.step += 1;
    this.u32[this.h + HEADER.stepIndex / 4 + this.back] = this.step;
    this.f64[HEADER_AT / 8 + HEADER.simTime / 8 + this.back] = this.step / 120;
    Atomics.store(this.u32, this.h + HEADER.front / 4, this.back);
    Atomics.add(this.u32, this.h + HEADER.seq / 4, 1);
  }

  publish(bodies: number, value: number): void {
    this.begin(bodies, value);
    this.end();
  }

  /** Appends body `index`'s BodyInfo, as Simulation::addRenderBody does. */
  addBody(index: number, half: [number, number, number], rgba: number, owner: number): void {
    const at = HEADER_AT + this.u32[this.h + HEADER.info / 4] + index * BODY_INFO.size;
    this.f32.set(half, at / 4);
    this.u32[(at + BODY_INFO.rgba) / 4] = rgba;
    new Int32Array(this.u32.buffer)[(at + BODY_INFO.owner) / 4] = owner;
    this.u32[(at + BODY_INFO.shape) / 4] = 0;
    Atomics.add(this.u32, this.h + HEADER.infoVersion / 4, 1);
  }
}

/** A copy target that lets the writer act in the middle of the reader's copy. */
class InterruptedTarget extends Float32Array {
  interrupt: (() => void) | null = null;
  override set(source: ArrayLike<number>, offset?: number): void {
    super.set(source, offset);
    const interrupt = this.interrupt;
    this.interrupt = null;
    interrupt?.();
  }
}

describe('render buffer layout', () => {
  it('matches the static_asserts of native/src/sim/render_buffer.h', () => {
    const header = fs.readFileSync(path.join(repoDir, 'native/src/sim/render_buffer.h'), 'utf8');
    const asserted = new Map<string, number>();
    for (const match of header.matchAll(/offsetof\(RenderHeader,\s*(\w+)\)\s*==\s*(\d+)/g)) {
      asserted.set(match[1], Number(match[2]));
    }
    expect(asserted.size).toBeGreaterThanOrEqual(9);
    for (const [field, offset] of asserted) {
      expect(HEADER[field as keyof typeof HEADER], `RenderHeader.${field}`).toBe(offset);
    }
    expect(header).toMatch(new RegExp(`sizeof\\(RenderHeader\\)\\s*==\\s*${HEADER.size}\\b`));
    expect(header).toMatch(new RegExp(`sizeof\\(BodyInfo\\)\\s*==\\s*${BODY_INFO.size}\\b`));
  });
});

describe('RenderBufferReader', () => {
  it('reads the published frame and its metadata', () => {
    const memory = layout(4);
    const writer = new Writer(memory);
    writer.publish(3, 1.5);
    const reader = new RenderBufferReader(memory, HEADER_AT);
    expect(reader.capacity).toBe(4);

    const target = new Float32Array(4 * MATRIX_FLOATS);
    const frame = reader.readFrame(target);
    expect(frame).toEqual({ seq: 2, bodyCount: 3, stepIndex: 1, simTime: 1 / 120 });
    expect(Array.from(target.subarray(0, 3 * MATRIX_FLOATS)).every((v) => v === 1.5)).toBe(true);
    expect(target[3 * MATRIX_FLOATS]).toBe(0); // beyond bodyCount: untouched

    writer.publish(4, 2.5); // the other buffer
    expect(reader.readFrame(target)).toMatchObject({ seq: 4, bodyCount: 4, stepIndex: 2 });
    expect(Array.from(target).every((v) => v === 2.5)).toBe(true);
  });

  it('truncates a frame to the target it copies into', () => {
    const memory = layout(4);
    new Writer(memory).publish(4, 7);
    const target = new Float32Array(2 * MATRIX_FLOATS);
    expect(new RenderBufferReader(memory, HEADER_AT).readFrame(target)?.bodyCount).toBe(2);
  });

  it('decodes BodyInfo', () => {
    const memory = layout(4);
    const writer = new Writer(memory);
    writer.addBody(0, [0.5, 0.25, 0.125], 0xe0c068ff, -1);
    writer.addBody(1, [0.1, 0.2, 0.3], 0x336699ff, 7);
    const reader = new RenderBufferReader(memory, HEADER_AT);
    expect(reader.infoVersion()).toBe(2);
    expect(reader.bodyInfo(0)).toEqual({ halfExtents: [0.5, 0.25, 0.125], rgba: 0xe0c068ff, owner: -1, shape: 0 });
    expect(reader.bodyInfo(1).owner).toBe(7);
    expect(reader.bodyInfo(1).rgba).toBe(0x336699ff);
    expect(() => reader.bodyInfo(4)).toThrow(RangeError);
  });

  it('keeps a copy during which the writer only started the next frame (in the other buffer)', () => {
    const memory = layout(2);
    const writer = new Writer(memory);
    writer.publish(2, 1);
    const target = new InterruptedTarget(2 * MATRIX_FLOATS);
    target.interrupt = () => writer.begin(2, 9);
    const frame = new RenderBufferReader(memory, HEADER_AT).readFrame(target);
    expect(frame).toMatchObject({ seq: 2, stepIndex: 1 });
    expect(Array.from(target).every((v) => v === 1)).toBe(true);
  });

  it('retries a copy the writer may have overwritten, and returns the newer frame', () => {
    const memory = layout(2);
    const writer = new Writer(memory);
    writer.publish(2, 1);
    const target = new InterruptedTarget(2 * MATRIX_FLOATS);
    // Mid-copy the writer publishes one frame and starts the next in the buffer being copied.
    target.interrupt = () => {
      writer.publish(2, 2);
      writer.begin(1, 3);
    };
    const frame = new RenderBufferReader(memory, HEADER_AT).readFrame(target);
    expect(frame).toMatchObject({ stepIndex: 2, bodyCount: 2 });
    expect(Array.from(target).every((v) => v === 2)).toBe(true);
  });

  it('gives up (null) when the writer overtakes every attempt', () => {
    const memory = layout(1);
    const writer = new Writer(memory);
    writer.publish(1, 1);
    const target = new (class extends Float32Array {
      override set(source: ArrayLike<number>, offset?: number): void {
        super.set(source, offset);
        writer.publish(1, 2);
        writer.publish(1, 3);
      }
    })(MATRIX_FLOATS);
    expect(new RenderBufferReader(memory, HEADER_AT).readFrame(target)).toBeNull();
  });

  it('rejects a header that cannot be right', () => {
    const memory = layout(4);
    expect(() => new RenderBufferReader(memory, 0)).toThrow(RangeError);
    expect(() => new RenderBufferReader(memory, HEADER_AT + 4)).toThrow(RangeError);
    expect(() => new RenderBufferReader(memory, memory.byteLength)).toThrow(RangeError);
    new Uint32Array(memory)[(HEADER_AT + HEADER.capacity) / 4] = 1 << 20; // buffers past the end
    expect(() => new RenderBufferReader(memory, HEADER_AT)).toThrow(/impossible layout/);
  });

  it('never accepts a torn frame from a writer running on another thread', async () => {
    // Large enough that a copy takes long compared with the writer's gaps between frames.
    const capacity = 1024;
    const memory = layout(capacity, new SharedArrayBuffer(bytesFor(capacity)));
    // The writer thread publishes frames whose every element equals the frame's step index.
    const writerSource = `
      const { workerData } = require('node:worker_threads');
      const { memory, at, capacity, stop, H } = workerData;
      const u32 = new Uint32Array(memory), f32 = new Float32Array(memory), f64 = new Float64Array(memory);
      const h = at / 4, flag = new Int32Array(stop);
      for (let step = 1; Atomics.load(flag, 0) === 0; step++) {
        const back = 1 - Atomics.load(u32, h + H.front / 4);
        Atomics.add(u32, h + H.seq / 4, 1);
        const start = (at + u32[h + H.matrices / 4 + back]) / 4;
        f32.fill(step, start, start + capacity * 16);
        u32[h + H.bodyCount / 4 + back] = capacity;
        u32[h + H.stepIndex / 4 + back] = step;
        f64[at / 8 + H.simTime / 8 + back] = step / 120;
        Atomics.store(u32, h + H.front / 4, back);
        Atomics.add(u32, h + H.seq / 4, 1);
      }`;
    const stop = new SharedArrayBuffer(4);
    const worker = new Worker(writerSource, {
      eval: true,
      workerData: { memory, at: HEADER_AT, capacity, stop, H: HEADER },
    });
    try {
      const reader = new RenderBufferReader(memory, HEADER_AT);
      const target = new Float32Array(capacity * MATRIX_FLOATS);
      let accepted = 0;
      const deadline = Date.now() + 1500;
      while (Date.now() < deadline && accepted < 20000) {
        const frame = reader.readFrame(target);
        if (!frame || frame.stepIndex === 0) continue;
        accepted++;
        for (let i = 0; i < capacity * MATRIX_FLOATS; i++) {
          if (target[i] !== frame.stepIndex) {
            throw new Error(`torn frame: element ${i} is ${target[i]}, frame ${frame.stepIndex}`);
          }
        }
      }
      expect(accepted).toBeGreaterThan(100);
    } finally {
      Atomics.store(new Int32Array(stop), 0, 1);
      await worker.terminate();
    }
  });
});
