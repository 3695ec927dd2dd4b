// Latency percentiles for the service benchmarks (load, replicas, storage).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace seaplan::bench {

// The sample at index round(q * (n - 1)) of the sorted values (q in [0, 1]),
// 0 for no values. Takes a copy: callers keep their samples in arrival order.
inline double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const std::size_t last = values.size() - 1;
  return values[std::min(last,
                         static_cast<std::size_t>(std::lround(q * static_cast<double>(last))))];
}

}  // namespace seaplan::bench
