// What the timing probes share: the thread's CPU clock, a quantile as `gaitlab bench` takes it,
// and a crowd named on the command line. Probes are built only on request (native/CMakeLists.txt)
// and measure what docs/parallel.md and docs/peers.md report.
#pragma once
#include <algorithm>
#include <ctime>
#include <string>
#include <vector>

#include "sim/simulation.h"

namespace gaitlab::probe {

// CPU seconds this thread has run: unlike the wall clock, it does not count the time another
// process held the core (the machine these figures come from is shared).
inline double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The q-quantile of `x` by nearest rank, as gaitlab bench takes its percentiles
// (sim/experiment.cpp); 0 for no samples.
inline double quantile(std::vector<double> x, double q) {
  if (x.empty()) return 0;
  std::sort(x.begin(), x.end());
  size_t rank = static_cast<size_t>(q * static_cast<double>(x.size()) + 0.999999);
  if (rank == 0) rank = 1;
  return x[std::min(x.size(), rank) - 1];
}

// The crowd of a LEGS argument as `gaitlab bench --legs` names it: "2", "4" or "mixed".
inline sim::Crowd crowdOf(const std::string& legs) {
  return legs == "2" ? sim::Crowd::Bipeds : legs == "4" ? sim::Crowd::Quadrupeds : sim::Crowd::Mixed;
}

}  // namespace gaitlab::probe
