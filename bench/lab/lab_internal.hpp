#pragma once
// Small helpers shared by the lab's experiment files (not part of the lab's interface).
#include "lookahead/strategy.hpp"

#include <chrono>
#include <numeric>
#include <string>
#include <vector>

namespace foresight::lab::detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

inline double mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

/// "1 command": the paper's type number and the strategy's name.
inline std::string strategy_label(int s) {
  return std::to_string(s) + " " + std::string(strategy_name(static_cast<Strategy>(s)));
}


}  // namespace foresight::lab::detail
