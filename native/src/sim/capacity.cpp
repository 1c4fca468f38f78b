#include "sim/capacity.h"

#if defined(__EMSCRIPTEN__)
#include <emscripten/heap.h>
#include <malloc.h>
#include <unistd.h>
#endif

namespace gaitlab::sim {

int64_t heapHeadroom() {
#if defined(__EMSCRIPTEN__)
  // Free bytes: only those above the allocator's break, which it may still claim in one piece.
  // The free chunks below it (dlmalloc's fordblks) are not counted: most are the solver pools'
  // old copies, freed as the pools grew, each too small for the next growth (which needs a
  // block larger than any before it), so counting them promised 110 MB that a spawn could not
  // get. A character's own small allocations reuse them, which only makes this estimate safer.
  const int64_t top = static_cast<int64_t>(reinterpret_cast<uintptr_t>(sbrk(0)));
  const int64_t max = static_cast<int64_t>(emscripten_get_heap_max());
  const int64_t free = max - top;
  return free > kHeapReserve ? free - kHeapReserve : 0;
#else
  return -1;
#endif
}

int64_t affordable(int64_t headroom, int64_t bytes, int bodies, int worldBodies) {
  // k things (k >= 1) fit when headroom - (k-1)·bytes >= bytes + s·(W + k·b), s the solver bytes
  // per body: k·(bytes + s·b) <= headroom - s·W.
  // The world reserves its pools for its bodies rounded up to 32 (physics/world.cpp).
  const int64_t left = headroom - kSolverBytesPerBody * (worldBodies + 32);
  if (left <= 0) return 0;
  return left / (bytes + kSolverBytesPerBody * bodies);
}

}  // namespace gaitlab::sim
