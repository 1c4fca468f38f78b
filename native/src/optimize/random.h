// The optimiser's random numbers (thesis §3.3: "each random generator is initialized ... with a
// seed value which is constant between application runs for a deterministic optimization").
//
// std::mt19937_64's output sequence is fixed by the C++ standard, but std::uniform_real_
// distribution and std::normal_distribution are not: libstdc++, libc++ and Emscripten's library
// may map the same engine output to different numbers. The mappings are therefore written here,
// so a seed names the same search everywhere.
#pragma once
#include <cmath>
#include <cstdint>
#include <random>

namespace gaitlab::optimize {

class Random {
 public:
  explicit Random(uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1): the top 53 bits of one engine output, exactly representable.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Standard normal by the Box–Muller transform (one of the pair is kept, so each call uses
  // exactly two engine outputs and the stream never depends on call history).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
  uint64_t next() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace gaitlab::optimize
