#include "sim/capacity.h"

#if defined(__EMSCRIPTEN__)
#include <emscripten/heap.h>
#include <malloc.h>
#include <unistd.h>
#endif

namespace gaitlab::sim {

int64_t heapHeadroom() {
#if defined(__EMSCRIPTEN__)
  // Free bytes: those above the allocator's break, which it may still claim, plus the free
  // chunks below it (dlmalloc's fordblks). Fragmentation could make a large block fail earlier,
  // but nothing a spawn does allocates more than a few hundred kilobytes at once.
  const int64_t top = static_cast<int64_t>(reinterpret_cast<uintptr_t>(sbrk(0)));
  const int64_t max = static_cast<int64_t>(emscripten_get_heap_max());
  const int64_t free = (max - top) + static_cast<int64_t>(mallinfo().fordblks);
  return free > kHeapReserve ? free - kHeapReserve : 0;
#else
  return -1;
#endif
}

int64_t affordable(int64_t headroom, int64_t bytes, int bodies, int worldBodies) {
  // k things (k >= 1) fit when headroom - (k-1)·bytes >= bytes + s·(W + k·b), s the solver bytes
  // per body: k·(bytes + s·b) <= headroom - s·W.
  const int64_t left = headroom - kSolverBytesPerBody * worldBodies;
  if (left <= 0) return 0;
  return left / (bytes + kSolverBytesPerBody * bodies);
}

}  // namespace gaitlab::sim
