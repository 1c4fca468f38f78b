// 64-bit FNV-1a over raw bytes: the state hash of a simulation and the terrain's content hash
// ("same inputs, same bits", docs/design.md). Not for security; cheap and order-sensitive.
#pragma once

#include <cstddef>
#include <cstdint>

namespace gaitlab {

struct Fnv1a {
  uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  }
};

}  // namespace gaitlab
