#pragma once
// Wire quantisation (schema/foresight.fbs): what goes on the wire is what the receiver decodes,
// so both sides round the same way. Positions: millimetres; angles: 1/65536 of a turn; input
// directions: -127..127 per axis.
#include "math/types.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace foresight::protocol {

/// Callers send only finite positions; a non-finite one becomes 0 rather than undefined behaviour.
inline int32_t quantize_mm(float metres) {
  if (!std::isfinite(metres)) return 0;
  const double mm = std::nearbyint(static_cast<double>(metres) * 1000.0);
  return static_cast<int32_t>(std::clamp(mm, -2.0e9, 2.0e9));
}
inline float dequantize_mm(int32_t mm) { return static_cast<float>(mm) * 0.001f; }

/// Any finite angle to 1/65536 of a turn (wraps).
inline uint16_t quantize_angle(float radians) {
  if (!std::isfinite(radians)) return 0;
  const double turns = static_cast<double>(radians) / (2.0 * kPi);
  const double wrapped = turns - std::floor(turns);
  return static_cast<uint16_t>(static_cast<uint32_t>(std::nearbyint(wrapped * 65536.0)) & 0xFFFFu);
}
/// In (-pi, pi].
inline float dequantize_angle(uint16_t q) {
  const float turns = static_cast<float>(q) / 65536.0f;
  return wrap_angle(turns * 2.0f * kPi);
}

inline int8_t quantize_unit(float v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int8_t>(std::nearbyint(std::clamp(v, -1.0f, 1.0f) * 127.0f));
}
inline float dequantize_unit(int8_t q) { return static_cast<float>(q) / 127.0f; }

/// A unit rotation in 32 bits, "smallest three": the largest component is dropped (2 bits say
/// which; its sign is made positive, q and -q being the same rotation) and the other three, each
/// in [-1/sqrt2, 1/sqrt2], take 10 bits (the usual game-networking packing). Error under a quarter of a
/// degree per joint (a few millimetres at the end of a limb chain), which is
/// what an adapted fighter pose needs to reach the client unchanged to the eye.
uint32_t quantize_rotation(quat q);
quat dequantize_rotation(uint32_t packed);

}  // namespace foresight::protocol
