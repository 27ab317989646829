#include "transport/cookie.hpp"

#include <sodium.h>

#include <cstdlib>
#include <cstring>

namespace foresight::protocol {

CookieJar::CookieJar(uint32_t slot_seconds) : slot_seconds_(slot_seconds == 0 ? 1 : slot_seconds) {
  static_assert(sizeof(key_) == crypto_shorthash_KEYBYTES);
  static_assert(kCookieBytes == crypto_shorthash_BYTES);
  if (sodium_init() < 0) std::abort();  // no usable random source: nothing safe to do
  crypto_shorthash_keygen(key_.data());
}

Cookie CookieJar::make_for_slot(std::span<const uint8_t> address, uint16_t port, uint64_t slot) const {
  // address (up to 16 bytes) | port | slot
  std::array<uint8_t, 16 + 2 + 8 + 1> msg{};
  const size_t n = std::min(address.size(), size_t{16});
  std::memcpy(msg.data(), address.data(), n);
  msg[16] = static_cast<uint8_t>(port >> 8);
  msg[17] = static_cast<uint8_t>(port & 0xFF);
  for (int i = 0; i < 8; ++i) msg[18 + i] = static_cast<uint8_t>(slot >> (8 * i));
  msg[26] = static_cast<uint8_t>(n);
  Cookie out{};
  crypto_shorthash(out.data(), msg.data(), msg.size(), key_.data());
  return out;
}

Cookie CookieJar::make(std::span<const uint8_t> address, uint16_t port, uint64_t now_s) const {
  return make_for_slot(address, port, now_s / slot_seconds_);
}

bool CookieJar::check(std::span<const uint8_t> cookie, std::span<const uint8_t> address,
                      uint16_t port, uint64_t now_s) const {
  if (cookie.size() != kCookieBytes) return false;
  const uint64_t slot = now_s / slot_seconds_;
  for (uint64_t s : {slot, slot - 1}) {
    const Cookie expected = make_for_slot(address, port, s);
    if (sodium_memcmp(expected.data(), cookie.data(), kCookieBytes) == 0) return true;
  }
  return false;
}

}  // namespace foresight::protocol
