#include "transport/histogram.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::protocol {

namespace {

int bin_of(double value) {
  if (!(value >= LogHistogram::kMinValue)) return 0;
  const double i = std::floor(std::log(value / LogHistogram::kMinValue) / std::log(LogHistogram::kRatio));
  return static_cast<int>(std::min(i + 1.0, static_cast<double>(LogHistogram::kBins - 1)));
}

double bin_middle(int bin) {
  if (bin == 0) return 0.0;
  return LogHistogram::kMinValue * std::pow(LogHistogram::kRatio, bin - 0.5);
}

}  // namespace

void LogHistogram::add(double value) {
  if (!std::isfinite(value)) return;
  // Saturate rather than wrap: a bin that has seen 4 billion samples is already decisive.
  uint32_t& b = bins_[static_cast<size_t>(bin_of(value))];
  if (b != UINT32_MAX) ++b;
  min_ = count_ ? std::min(min_, value) : value;
  max_ = count_ ? std::max(max_, value) : value;
  ++count_;
  sum_ += value;
}

void LogHistogram::merge(const LogHistogram& other) {
  if (other.count_ == 0) return;
  for (size_t i = 0; i < bins_.size(); ++i) {
    const uint64_t sum = uint64_t{bins_[i]} + other.bins_[i];
    bins_[i] = static_cast<uint32_t>(std::min<uint64_t>(sum, UINT32_MAX));
  }
  min_ = count_ ? std::min(min_, other.min_) : other.min_;
  max_ = count_ ? std::max(max_, other.max_) : other.max_;
  count_ += other.count_;
  sum_ += other.sum_;
}

double LogHistogram::percentile(double q) const {
  if (count_ == 0) return 0.0;
  q = std::clamp(q, 0.0, 1.0);
  // Rank of the wanted sample, 1-based: the smallest sample for q = 0, the largest for q = 1.
  const uint64_t rank = std::max<uint64_t>(1, static_cast<uint64_t>(std::ceil(q * static_cast<double>(count_))));
  uint64_t seen = 0;
  for (int i = 0; i < kBins; ++i) {
    seen += bins_[static_cast<size_t>(i)];
    if (seen >= rank) return std::clamp(bin_middle(i), min_, max_);
  }
  return max_;
}

}  // namespace foresight::protocol
