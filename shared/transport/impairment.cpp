#include "transport/impairment.hpp"

#include "math/splitmix64.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace foresight::protocol {

bool impairment_valid(const ImpairmentConfig& c, std::string& error) {
  const double probabilities[] = {c.loss, c.duplicate, c.reorder};
  for (double p : probabilities)
    if (!(p >= 0.0 && p <= 1.0)) {
      error = "impairment probabilities (loss, duplicate, reorder) must be in [0, 1]";
      return false;
    }
  if (!(c.latency_ms >= 0.0 && c.latency_ms <= 10000.0) || !(c.jitter_ms >= 0.0 && c.jitter_ms <= 10000.0)) {
    error = "impairment latency and jitter must be in [0, 10000] ms";
    return false;
  }
  return true;
}

ImpairedQueue::ImpairedQueue(const ImpairmentConfig& config, uint64_t seed_salt, size_t capacity)
    : config_(config),
      state_(config.seed * 0x9E3779B97F4A7C15ull + seed_salt),
      slots_(std::max<size_t>(capacity, 1)),
      bytes_(slots_.size() * kSlotBytes) {}

double ImpairedQueue::uniform() {
  SplitMix64 g{state_};
  const uint64_t v = g.next();
  state_ = g.state;
  return static_cast<double>(v >> 11) * 0x1.0p-53;
}

void ImpairedQueue::push(std::span<const uint8_t> datagram, Clock::time_point now) {
  ++counters_.pushed;
  if (uniform() < config_.loss) {
    ++counters_.lost;
    return;
  }
  enqueue(datagram, now);
  if (uniform() < config_.duplicate) {
    ++counters_.duplicated;
    enqueue(datagram, now);
  }
}

void ImpairedQueue::enqueue(std::span<const uint8_t> datagram, Clock::time_point now) {
  const auto free = std::find_if(slots_.begin(), slots_.end(), [](const Slot& s) { return !s.used; });
  if (free == slots_.end() || datagram.size() > kSlotBytes) {
    ++counters_.overflowed;
    return;
  }
  double delay_ms = std::max(0.0, config_.latency_ms + (2.0 * uniform() - 1.0) * config_.jitter_ms);
  if (uniform() < config_.reorder) {
    ++counters_.reordered;
    delay_ms += config_.jitter_ms + 20.0;  // later than what is sent in the next 20 ms
  }
  const size_t i = static_cast<size_t>(free - slots_.begin());
  std::memcpy(bytes_.data() + i * kSlotBytes, datagram.data(), datagram.size());
  *free = {now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(delay_ms)),
           next_order_++, static_cast<uint32_t>(datagram.size()), true};
}

int ImpairedQueue::next_due(Clock::time_point now) const {
  int best = -1;
  for (size_t i = 0; i < slots_.size(); ++i) {
    const Slot& s = slots_[i];
    if (!s.used || s.due > now) continue;
    const Slot* b = best < 0 ? nullptr : &slots_[static_cast<size_t>(best)];
    if (b == nullptr || s.due < b->due || (s.due == b->due && s.order < b->order)) best = static_cast<int>(i);
  }
  return best;
}

size_t ImpairedQueue::in_flight() const {
  return static_cast<size_t>(std::count_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.used; }));
}

}  // namespace foresight::protocol
