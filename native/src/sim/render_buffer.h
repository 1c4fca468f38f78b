// Render transforms shared with the browser's main thread through WASM memory (README.md,
// architecture). The sim worker writes (sim/render_publisher.h); the main thread reads the newest
// complete frame straight out of the SharedArrayBuffer: no message and no copy on the way.
//
// Two frame buffers: the writer increments `seq`, fills the buffer that is not `front`, sets
// `front` to it and increments `seq` again. A reader notes `seq`, then reads `front` and that
// buffer, and notes `seq` again: if it advanced by 2 or more, the writer may have started to
// reuse that buffer meanwhile and the reader retries (a seqlock over two buffers). The layout is mirrored in
// web/src/sim/render-buffer.ts; the static_asserts below pin it.
#pragma once
#include <atomic>
#include <cstddef>
#include <cstdint>

namespace gaitlab {

// Static description of one body: changes only when bodies are added or removed
// (RenderHeader::infoVersion increments then).
struct BodyInfo {
  float halfExtents[3];  // box half extents, metres
  uint32_t rgba;         // colour, 0xRRGGBBAA
  int32_t owner;         // character id, or -1 for a prop
  uint32_t shape;        // 0 = box (the only shape so far)
};
static_assert(sizeof(BodyInfo) == 24, "BodyInfo layout is mirrored in render-buffer.ts");

struct RenderHeader {
  std::atomic<uint32_t> seq;   // 2 x frames published (+1 while one is being written)
  std::atomic<uint32_t> front; // 0 or 1: the buffer holding the newest complete frame
  uint32_t capacity;           // bodies the buffers can hold
  std::atomic<uint32_t> infoVersion;
  uint32_t bodyCount[2];       // bodies in each buffer's frame
  uint32_t stepIndex[2];       // fixed-step index of each buffer's frame
  double simTime[2];           // simulated seconds of each buffer's frame
  uint32_t matrices[2];        // byte offset from this header of float[capacity][16], column-major,
                               // box scale baked in (three.js InstancedMesh layout)
  uint32_t info;               // byte offset from this header of BodyInfo[capacity]
  uint32_t reserved;
};
static_assert(offsetof(RenderHeader, seq) == 0, "layout");
static_assert(offsetof(RenderHeader, front) == 4, "layout");
static_assert(offsetof(RenderHeader, capacity) == 8, "layout");
static_assert(offsetof(RenderHeader, infoVersion) == 12, "layout");
static_assert(offsetof(RenderHeader, bodyCount) == 16, "layout");
static_assert(offsetof(RenderHeader, stepIndex) == 24, "layout");
static_assert(offsetof(RenderHeader, simTime) == 32, "layout");
static_assert(offsetof(RenderHeader, matrices) == 48, "layout");
static_assert(offsetof(RenderHeader, info) == 56, "layout");
static_assert(sizeof(RenderHeader) == 64, "layout");

}  // namespace gaitlab
