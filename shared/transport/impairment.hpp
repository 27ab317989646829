#pragma once
// A network impairment layer in userspace (this kernel has no netem: ../shared/ENVIRONMENT.md),
// applied to real UDP traffic by the client side: ClientConnection puts every datagram it sends
// and every one it receives through an ImpairedQueue, so both directions of a real loopback link
// see loss, latency with jitter, duplication and reordering (bots: --loss 0.05 --latency-ms 50
// --jitter-ms 20 --duplicate 0.01 --reorder 0.01; docs/RELIABILITY.md).
//
// Per datagram, from a seeded generator (the same seed, the same fate for the same traffic):
// lost with probability `loss`; otherwise delayed by latency_ms + uniform(-jitter_ms, +jitter_ms)
// (at least 0), and with probability `reorder` held back a further jitter_ms + 20 ms so that the
// datagrams sent after it overtake it; with probability `duplicate` a second copy follows it
// with its own delay.
#include "protocol/protocol.hpp"

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace foresight::protocol {

struct ImpairmentConfig {
  double loss = 0;        ///< [0, 1]
  double duplicate = 0;   ///< [0, 1]
  double reorder = 0;     ///< [0, 1]
  double latency_ms = 0;  ///< One way. [0, 10000]
  double jitter_ms = 0;   ///< [0, latency_ms] is typical; any [0, 10000] is accepted.
  uint64_t seed = 1;
  bool active() const { return loss > 0 || duplicate > 0 || reorder > 0 || latency_ms > 0 || jitter_ms > 0; }
};
/// False with a reason for values out of range or not finite.
bool impairment_valid(const ImpairmentConfig& config, std::string& error);

struct ImpairmentCounters {
  uint64_t pushed = 0, lost = 0, duplicated = 0, reordered = 0, overflowed = 0, released = 0;
};

/// One direction. Fixed capacity, allocated at construction; a datagram that finds it full is
/// dropped and counted (overflowed).
class ImpairedQueue {
 public:
  using Clock = std::chrono::steady_clock;
  ImpairedQueue(const ImpairmentConfig& config, uint64_t seed_salt, size_t capacity = 128);

  void push(std::span<const uint8_t> datagram, Clock::time_point now);
  /// Calls deliver(span) for every datagram due at `now`, earliest release first.
  template <class Deliver>
  void release(Clock::time_point now, Deliver&& deliver) {
    for (;;) {
      const int i = next_due(now);
      if (i < 0) return;
      Slot& s = slots_[static_cast<size_t>(i)];
      s.used = false;
      ++counters_.released;
      deliver(std::span<const uint8_t>(bytes_.data() + static_cast<size_t>(i) * kSlotBytes, s.size));
    }
  }
  size_t in_flight() const;
  const ImpairmentCounters& counters() const { return counters_; }

 private:
  /// A datagram's room, a multiple of 16 so every slot is aligned as FlatBuffers reads it.
  static constexpr size_t kSlotBytes = (kMaxDatagramBytes + 1 + 15) / 16 * 16;
  struct Slot {
    Clock::time_point due{};
    uint64_t order = 0;  ///< Push order: ties release first in, first out.
    uint32_t size = 0;
    bool used = false;
  };
  double uniform();  ///< [0, 1)
  void enqueue(std::span<const uint8_t> datagram, Clock::time_point now);
  int next_due(Clock::time_point now) const;

  ImpairmentConfig config_;
  uint64_t state_;
  uint64_t next_order_ = 0;
  std::vector<Slot> slots_;
  std::vector<uint8_t> bytes_;
  ImpairmentCounters counters_;
};

}  // namespace foresight::protocol
