#pragma once
// The exact percentile of a set of samples: the benches' figures and the library's pop threshold
// (library_build/pop_budget.hpp). Running network figures use LogHistogram instead
// (transport/histogram.hpp: bounded memory, one bin of error).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace foresight {

/// Percentile p in [0, 100] by linear interpolation between order statistics (0 when empty).
inline double percentile(std::vector<double> samples, double p) {
  if (samples.empty()) return 0.0;
  std::sort(samples.begin(), samples.end());
  const double pos = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(samples.size() - 1);
  const size_t i = static_cast<size_t>(std::floor(pos));
  const size_t j = std::min(i + 1, samples.size() - 1);
  return samples[i] + (pos - static_cast<double>(i)) * (samples[j] - samples[i]);
}

}  // namespace foresight
