#pragma once
// A fixed-size histogram with logarithmic bins, for latencies and intervals measured on every
// packet: recording a value never allocates, two histograms merge by adding counts (the bots add
// up all their clients), and a percentile is off by at most one bin (2 %).
#include <array>
#include <cstdint>

namespace foresight::protocol {

class LogHistogram {
 public:
  /// Bin 0 holds everything below kMinValue (including zero and negative values); bin i >= 1
  /// holds [kMinValue * kRatio^(i-1), kMinValue * kRatio^i); the last bin also everything above.
  static constexpr double kMinValue = 0.001;
  static constexpr double kRatio = 1.02;
  static constexpr int kBins = 1100;  ///< Up to ~3e6 (ms: 50 minutes).

  /// Non-finite values are ignored.
  void add(double value);
  void merge(const LogHistogram& other);
  void clear() { *this = LogHistogram{}; }

  uint64_t count() const { return count_; }
  double min() const { return count_ ? min_ : 0.0; }
  double max() const { return count_ ? max_ : 0.0; }
  double mean() const { return count_ ? sum_ / static_cast<double>(count_) : 0.0; }
  /// The value below which a share q in [0, 1] of the samples lie: the geometric middle of the
  /// bin holding that rank, clamped to [min, max]. 0 when empty.
  double percentile(double q) const;

 private:
  std::array<uint32_t, kBins> bins_{};
  uint64_t count_ = 0;
  double sum_ = 0;
  double min_ = 0;
  double max_ = 0;
};

}  // namespace foresight::protocol
