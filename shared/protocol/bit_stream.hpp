#pragma once
// Bit-level writing and reading for the packed parts of messages (avatar_delta.hpp). Bits go
// least significant first into consecutive bytes; the last byte is zero-padded.
//
// Codes: fixed widths (put / get); Elias gamma for small positive numbers (ids' gaps, frame
// residuals: 1 costs 1 bit, 5 costs 5; the bits below the leading one come least significant
// first); a 6-bit bit length and the bits below the leading one
// for wider numbers (positions, headings: 700 costs 15 bits). Signed values are zigzag-coded.
//
// The reader never reads past its span: a read beyond it returns 0 and sets failed(), which the
// caller checks once at the end of what it decodes.
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

namespace foresight::protocol {

inline uint32_t zigzag(int32_t v) { return (static_cast<uint32_t>(v) << 1) ^ static_cast<uint32_t>(v >> 31); }
inline int32_t unzigzag(uint32_t v) { return static_cast<int32_t>(v >> 1) ^ -static_cast<int32_t>(v & 1u); }

class BitWriter {
 public:
  /// Writes into `out` (cleared): reserve it once and the writer allocates nothing. The bytes
  /// are complete after finish().
  explicit BitWriter(std::vector<uint8_t>& out) : out_(out) { out_.clear(); }

  /// The low `bits` bits of `value` (bits <= 32).
  void put(uint32_t value, int bits) {
    if (bits == 0) return;
    acc_ |= (static_cast<uint64_t>(value) & ((uint64_t{1} << bits) - 1)) << fill_;
    fill_ += bits;  // < 64: fill_ < 32 before, bits <= 32
    if (fill_ >= 32) {  // four bytes at a time, not a push_back per byte
      const uint8_t word[4] = {static_cast<uint8_t>(acc_), static_cast<uint8_t>(acc_ >> 8),
                               static_cast<uint8_t>(acc_ >> 16), static_cast<uint8_t>(acc_ >> 24)};
      out_.insert(out_.end(), word, word + 4);
      acc_ >>= 32;
      fill_ -= 32;
    }
    used_ += static_cast<size_t>(bits);
  }
  void put_bit(bool b) { put(b ? 1u : 0u, 1); }
  /// v >= 1 with n significant bits: n - 1 zeros, a one, then v's low n - 1 bits.
  void put_gamma(uint64_t v) {
    const int n = 64 - std::countl_zero(v);
    put_zeros(n - 1);
    put(1u, 1);
    if (n > 33) put(static_cast<uint32_t>(v), 32), put(static_cast<uint32_t>(v >> 32), n - 33);
    else put(static_cast<uint32_t>(v), n - 1);
  }
  /// Its bit length in 6 bits, then the bits below its leading one.
  void put_wide(uint32_t v) {
    const int n = 32 - std::countl_zero(v);
    put(static_cast<uint32_t>(n), 6);
    if (n > 1) put(v, n - 1);
  }
  void put_signed_gamma(int32_t v) { put_gamma(static_cast<uint64_t>(zigzag(v)) + 1); }
  void put_signed_wide(int32_t v) { put_wide(zigzag(v)); }
  /// Writes the last, partial byte (zero-padded). Nothing may be put after it.
  void finish() {
    for (; fill_ > 0; fill_ -= 8, acc_ >>= 8) out_.push_back(static_cast<uint8_t>(acc_));
    acc_ = 0;
    fill_ = 0;
  }

  size_t bits() const { return used_; }
  /// Bytes the finished stream takes.
  size_t bytes() const { return (used_ + 7) / 8; }

 private:
  void put_zeros(int n) {
    for (; n > 32; n -= 32) put(0, 32);
    put(0, n);
  }
  std::vector<uint8_t>& out_;
  uint64_t acc_ = 0;  ///< Bits not yet in out_, the first in bit 0.
  int fill_ = 0;
  size_t used_ = 0;
};

class BitReader {
 public:
  explicit BitReader(std::span<const uint8_t> in) : in_(in), size_(in.size() * 8) {}

  /// bits <= 32.
  uint32_t get(int bits) {
    if (bits == 0) return 0;
    if (size_ - pos_ < static_cast<size_t>(bits)) {
      failed_ = true;
      pos_ = size_;
      return 0;
    }
    const uint32_t v = static_cast<uint32_t>(window() & ((uint64_t{1} << bits) - 1));
    pos_ += static_cast<size_t>(bits);
    return v;
  }
  bool get_bit() { return get(1) != 0; }
  /// 0 (and failed()) for a code longer than 64 bits or cut off.
  uint64_t get_gamma() {
    // The zeros before the leading one, up to 32 at a time (not a bit at a time).
    int zeros = 0;
    for (;;) {
      const int n = static_cast<int>(std::min<size_t>(size_ - pos_, 32));
      if (n == 0) {
        failed_ = true;
        return 0;
      }
      const uint32_t ahead = static_cast<uint32_t>(window() & ((uint64_t{1} << n) - 1));
      const int z = ahead != 0 ? std::countr_zero(ahead) : n;
      zeros += z;
      pos_ += static_cast<size_t>(ahead != 0 ? z + 1 : z);
      if (zeros > 63) {
        failed_ = true;
        return 0;
      }
      if (ahead != 0) break;
    }
    if (zeros > 32) {
      const uint64_t low = get(32);
      return (uint64_t{1} << zeros) | low | (static_cast<uint64_t>(get(zeros - 32)) << 32);
    }
    return (uint64_t{1} << zeros) | get(zeros);
  }
  uint32_t get_wide() {
    const int n = static_cast<int>(get(6));
    if (n == 0) return 0;
    if (n > 32) {
      failed_ = true;
      return 0;
    }
    return (1u << (n - 1)) | get(n - 1);
  }
  int32_t get_signed_gamma() {
    const uint64_t v = get_gamma();
    if (v == 0 || v - 1 > UINT32_MAX) {
      failed_ = true;
      return 0;
    }
    return unzigzag(static_cast<uint32_t>(v - 1));
  }
  int32_t get_signed_wide() { return unzigzag(get_wide()); }

  bool failed() const { return failed_; }
  /// Bits left (the last byte's padding included).
  size_t remaining_bits() const { return size_ - pos_; }

 private:
  /// The bits from pos_ on, at least 32 of them where the input has them, the first in bit 0.
  uint64_t window() const {
    const size_t first = pos_ >> 3;
    uint64_t w = 0;
    if (std::endian::native == std::endian::little && first + 8 <= in_.size()) {
      std::memcpy(&w, in_.data() + first, 8);  // one load (a byte loop stays eight)
    } else {
      for (size_t i = 0; first + i < in_.size(); ++i) w |= static_cast<uint64_t>(in_[first + i]) << (8 * i);
    }
    return w >> (pos_ & 7u);
  }

  std::span<const uint8_t> in_;
  size_t size_ = 0;
  size_t pos_ = 0;
  bool failed_ = false;
};

}  // namespace foresight::protocol
