// TypeScript mirror of native/src/sim/render_buffer.h: the render transforms the sim worker
// publishes into WASM memory and the main thread reads every animation frame (docs/design.md, data
// flow steps 2–3). The offsets below are the ones the header static_asserts.
//
// Reading protocol (a seqlock over two buffers). The writer increments `seq` when it starts
// filling the buffer that is not `front` (seq is odd while it writes), then sets `front` to that
// buffer and increments `seq` again. A reader notes `seq`, copies buffer `front`, and notes `seq`
// again. The writer only ever writes the buffer that is not front, so the buffer the reader
// copies is rewritten no earlier than the start of the writer's *next* frame — by which time seq
// has advanced by at least 2 from what the reader noted. An advance of 0 or 1 proves the copy
// is whole; 2 or more means retry.

/** Byte offsets of RenderHeader's fields. */
export const HEADER = {
  seq: 0,
  front: 4,
  capacity: 8,
  infoVersion: 12,
  bodyCount: 16, // uint32[2]
  stepIndex: 24, // uint32[2]
  simTime: 32, // float64[2]
  matrices: 48, // uint32[2], byte offsets from the header
  info: 56, // uint32, byte offset from the header
  size: 64,
} as const;

/** Byte offsets of BodyInfo's fields. */
export const BODY_INFO = {
  halfExtents: 0, // float32[3]
  rgba: 12, // uint32, 0xRRGGBBAA
  owner: 16, // int32, character id or -1 for a prop
  shape: 20, // uint32, 0 = box
  size: 24,
} as const;

/** Floats per body in a matrix buffer: a column-major 4×4 matrix with the box scale baked in. */
export const MATRIX_FLOATS = 16;

export interface BodyInfo {
  halfExtents: [number, number, number];
  rgba: number;
  owner: number;
  shape: number;
}

/** What a successful read found, besides the matrices it copied. */
export interface FrameMeta {
  seq: number;
  bodyCount: number;
  stepIndex: number;
  simTime: number;
}

/** The newest complete frame could not be copied in this many attempts (writer too busy). */
const MAX_ATTEMPTS = 16;

export class RenderBufferReader {
  readonly capacity: number;
  private readonly u32: Uint32Array;
  private readonly f64: Float64Array;
  private readonly i32: Int32Array;
  private readonly f32: Float32Array;
  private readonly base32: number;
  private readonly base64: number;
  /** Float index of each frame buffer's first matrix element. */
  private readonly matrixStart: [number, number];
  /** Byte address of BodyInfo[0]. */
  private readonly infoAddress: number;

  /**
   * @param memory the WASM memory (Module.HEAPU8.buffer, shared with the worker)
   * @param header byte address of the RenderHeader (gl_sim_render_buffer)
   */
  constructor(memory: ArrayBufferLike, header: number) {
    if (!Number.isInteger(header) || header <= 0 || header % 8 !== 0 || header + HEADER.size > memory.byteLength) {
      throw new RangeError(`render header at ${header} is not an aligned address inside ${memory.byteLength} bytes of memory`);
    }
    this.u32 = new Uint32Array(memory);
    this.i32 = new Int32Array(memory);
    this.f32 = new Float32Array(memory);
    this.f64 = new Float64Array(memory);
    this.base32 = header >> 2;
    this.base64 = header >> 3;

    // The layout fields are written once, when the simulation is created; check them so that a
    // mismatch with the C++ side fails here, loudly, rather than as garbage on the screen.
    const word = (offset: number) => this.u32[this.base32 + offset / 4];
    this.capacity = word(HEADER.capacity);
    const matrices: [number, number] = [word(HEADER.matrices), word(HEADER.matrices + 4)];
    const info = word(HEADER.info);
    const inside = (offset: number, bytes: number) =>
      offset % 4 === 0 && offset >= HEADER.size && header + offset + bytes <= memory.byteLength;
    const matrixBytes = this.capacity * MATRIX_FLOATS * 4;
    if (!inside(matrices[0], matrixBytes) || !inside(matrices[1], matrixBytes) || !inside(info, this.capacity * BODY_INFO.size)) {
      throw new RangeError(
        `render header at ${header} has an impossible layout (capacity ${this.capacity}, matrices ${matrices.join('/')}, info ${info})`,
      );
    }
    this.matrixStart = [(header + matrices[0]) >> 2, (header + matrices[1]) >> 2];
    this.infoAddress = header + info;
  }

  /** Frames published so far (changes whenever a new frame is available). */
  seq(): number {
    return Atomics.load(this.u32, this.base32 + HEADER.seq / 4);
  }

  /** Increments whenever bodies are added or removed, i.e. when BodyInfo must be read again. */
  infoVersion(): number {
    return Atomics.load(this.u32, this.base32 + HEADER.infoVersion / 4);
  }

  /**
   * Copies the newest complete frame's matrices into `target` (bodyCount × 16 floats, from index
   * 0: the layout of InstancedMesh.instanceMatrix.array) and returns its metadata, or null if
   * the writer kept overtaking the copy (then `target` may hold a partial copy; read again next
   * frame). Frames with more bodies than `target` holds are truncated to fit.
   */
  readFrame(target: Float32Array): FrameMeta | null {
    const seqIndex = this.base32 + HEADER.seq / 4;
    const frontIndex = this.base32 + HEADER.front / 4;
    for (let attempt = 0; attempt < MAX_ATTEMPTS; attempt++) {
      const seq = Atomics.load(this.u32, seqIndex);
      const front = Atomics.load(this.u32, frontIndex) & 1;
      const bodyCount = Math.min(
        this.u32[this.base32 + HEADER.bodyCount / 4 + front],
        this.capacity,
        Math.floor(target.length / MATRIX_FLOATS),
      );
      const stepIndex = this.u32[this.base32 + HEADER.stepIndex / 4 + front];
      const simTime = this.f64[this.base64 + HEADER.simTime / 8 + front];
      const start = this.matrixStart[front];
      target.set(this.f32.subarray(start, start + bodyCount * MATRIX_FLOATS));
      if (((Atomics.load(this.u32, seqIndex) - seq) >>> 0) < 2) return { seq, bodyCount, stepIndex, simTime };
    }
    return null;
  }

  /** BodyInfo of body `index` (< capacity). */
  bodyInfo(index: number): BodyInfo {
    if (!(index >= 0 && index < this.capacity)) throw new RangeError(`body ${index} is outside the capacity ${this.capacity}`);
    const address = this.infoAddress + index * BODY_INFO.size;
    const f = (address + BODY_INFO.halfExtents) >> 2;
    return {
      halfExtents: [this.f32[f], this.f32[f + 1], this.f32[f + 2]],
      rgba: this.u32[(address + BODY_INFO.rgba) >> 2],
      owner: this.i32[(address + BODY_INFO.owner) >> 2],
      shape: this.u32[(address + BODY_INFO.shape) >> 2],
    };
  }
}
