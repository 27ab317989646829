#pragma once
// Stateless connection cookies (docs/PROTOCOL.md, "Connecting"). The server answers a
// ConnectRequest with a cookie = SipHash-2-4 (libsodium crypto_shorthash, a keyed PRF) of the
// client's address, port and the current time slot, under a secret drawn at start-up. Only a
// client that receives at that address can echo it; the server keeps nothing per request, so a
// flood of spoofed connects costs it no memory.
#include <array>
#include <cstdint>
#include <span>

namespace foresight::protocol {

inline constexpr size_t kCookieBytes = 8;
using Cookie = std::array<uint8_t, kCookieBytes>;

class CookieJar {
 public:
  /// A random secret (libsodium randombytes); slot_seconds: how long a cookie stays valid (it is
  /// accepted in its own slot and the next one).
  explicit CookieJar(uint32_t slot_seconds = 10);
  /// `address`: the client's IP address bytes (4 or 16), `port` its UDP port, `now_s` seconds on
  /// a monotonic clock.
  Cookie make(std::span<const uint8_t> address, uint16_t port, uint64_t now_s) const;
  bool check(std::span<const uint8_t> cookie, std::span<const uint8_t> address, uint16_t port,
             uint64_t now_s) const;

 private:
  Cookie make_for_slot(std::span<const uint8_t> address, uint16_t port, uint64_t slot) const;
  std::array<uint8_t, 16> key_{};
  uint32_t slot_seconds_;
};

}  // namespace foresight::protocol
