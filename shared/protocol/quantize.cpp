#include "protocol/quantize.hpp"

namespace foresight::protocol {
namespace {

constexpr float kRange = 0.70710678f;  // |smaller components| <= 1/sqrt(2)
constexpr uint32_t kBits = 10;
constexpr uint32_t kMax = (1u << kBits) - 1u;

uint32_t pack_component(float v) {
  const float unit = (std::clamp(v, -kRange, kRange) + kRange) / (2.0f * kRange);
  return static_cast<uint32_t>(std::nearbyint(unit * static_cast<float>(kMax)));
}
float unpack_component(uint32_t bits) {
  return static_cast<float>(bits & kMax) / static_cast<float>(kMax) * (2.0f * kRange) - kRange;
}

}  // namespace

uint32_t quantize_rotation(quat q) {
  float c[4] = {q.x, q.y, q.z, q.w};
  const float len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
  if (!std::isfinite(len) || len < 1e-6f) return quantize_rotation(quat(1.0f, 0.0f, 0.0f, 0.0f));
  uint32_t largest = 0;
  for (uint32_t i = 1; i < 4; ++i)
    if (std::abs(c[i]) > std::abs(c[largest])) largest = i;
  const float sign = c[largest] < 0.0f ? -1.0f : 1.0f;
  uint32_t packed = largest << 30;
  uint32_t shift = 20;
  for (uint32_t i = 0; i < 4; ++i) {
    if (i == largest) continue;
    packed |= pack_component(sign * c[i] / len) << shift;
    shift -= kBits;
  }
  return packed;
}

quat dequantize_rotation(uint32_t packed) {
  const uint32_t largest = packed >> 30;
  float c[4];
  float sum = 0.0f;
  uint32_t shift = 20;
  for (uint32_t i = 0; i < 4; ++i) {
    if (i == largest) continue;
    c[i] = unpack_component(packed >> shift);
    sum += c[i] * c[i];
    shift -= kBits;
  }
  c[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
  return glm::normalize(quat(c[3], c[0], c[1], c[2]));  // glm: (w, x, y, z)
}

}  // namespace foresight::protocol
