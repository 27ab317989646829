// Wire quantisation: what a sender writes is what the receiver decodes, within half a step, and
// hostile or degenerate values never produce undefined behaviour.
#include "protocol/input_packet.hpp"
#include "protocol/quantize.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace foresight::protocol {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(Quantize, MillimetresRoundTripWithinHalfAMillimetre) {
  for (float m : {0.0f, 0.0004f, -0.0006f, 1.2345f, -17.5f, 999.999f, -12345.678f}) {
    EXPECT_NEAR(dequantize_mm(quantize_mm(m)), m, 0.0005f + std::abs(m) * 1e-6f) << m;
  }
  EXPECT_EQ(quantize_mm(1.0f), 1000);
  EXPECT_EQ(quantize_mm(-0.0016f), -2);  // rounded, not truncated towards zero
}

TEST(Quantize, MillimetresOfNonFiniteOrHugeValuesAreSafe) {
  EXPECT_EQ(quantize_mm(kNan), 0);
  EXPECT_EQ(quantize_mm(kInf), 0);
  EXPECT_EQ(quantize_mm(1e30f), 2000000000);
  EXPECT_EQ(quantize_mm(-1e30f), -2000000000);
}

TEST(Quantize, AnglesRoundTripWithinHalfAStepAndWrap) {
  const float step = kTwoPi / 65536.0f;
  for (float deg = -720.0f; deg <= 720.0f; deg += 7.3f) {
    const float a = radians(deg);
    const float back = dequantize_angle(quantize_angle(a));
    EXPECT_NEAR(wrap_angle(back - a), 0.0f, 0.5f * step + 1e-5f) << deg;
    EXPECT_GT(back, -kPi - 1e-6f);
    EXPECT_LE(back, kPi + 1e-6f);
  }
  EXPECT_EQ(quantize_angle(0.0f), 0);
  EXPECT_EQ(quantize_angle(kTwoPi), 0);
  EXPECT_EQ(quantize_angle(kPi / 2), 16384);
  EXPECT_EQ(quantize_angle(-kPi / 2), 49152);
  EXPECT_EQ(quantize_angle(kNan), 0);
  EXPECT_EQ(quantize_angle(-kInf), 0);
}

TEST(Quantize, UnitValuesRoundTripAndClamp) {
  for (float v = -1.0f; v <= 1.0f; v += 0.01f) {
    EXPECT_NEAR(dequantize_unit(quantize_unit(v)), v, 0.5f / 127.0f + 1e-6f) << v;
  }
  EXPECT_EQ(quantize_unit(1.0f), 127);
  EXPECT_EQ(quantize_unit(-1.0f), -127);
  EXPECT_EQ(quantize_unit(5.0f), 127);
  EXPECT_EQ(quantize_unit(-5.0f), -127);
  EXPECT_EQ(quantize_unit(kNan), 0);
}

TEST(Quantize, ControlInputRoundTripsThroughAnInputCommand) {
  ControlInput in;
  in.camera_dir = vec2(-0.70710677f, 0.70710677f);
  in.camera_yaw_rad = radians(-135.0f);
  in.crouch = true;
  const wire::InputCommand c = input_command_from(in, 42);
  EXPECT_EQ(c.sequence(), 42u);
  const ControlInput out = control_input_from_command(c);
  EXPECT_NEAR(out.camera_dir.x, in.camera_dir.x, 0.5f / 127.0f);
  EXPECT_NEAR(out.camera_dir.y, in.camera_dir.y, 0.5f / 127.0f);
  EXPECT_NEAR(wrap_angle(out.camera_yaw_rad - in.camera_yaw_rad), 0.0f, 1e-4f);
  EXPECT_TRUE(out.crouch);
  EXPECT_TRUE(control_input_valid(out));

  const ControlInput stop = control_input_from_command(input_command_from(ControlInput{}, 1));
  EXPECT_EQ(stop.camera_dir, vec2(0.0f));
  EXPECT_FALSE(stop.crouch);
}

TEST(Quantize, AnyCommandBytesDecodeToAValidInput) {
  // A peer may send (127, 127) or (-128, -128): the decoded direction is still at most unit.
  for (int x : {-128, -127, 0, 90, 127}) {
    for (int y : {-128, -127, 0, 90, 127}) {
      const wire::InputCommand c(1, 12345, static_cast<int8_t>(x), static_cast<int8_t>(y),
                                 wire::Buttons::ANY);
      EXPECT_TRUE(control_input_valid(control_input_from_command(c))) << x << "," << y;
    }
  }
}

}  // namespace
}  // namespace foresight::protocol

namespace foresight::protocol {
namespace {

float rotation_error_deg(quat a, quat b) {
  const float d = std::min(1.0f, std::abs(glm::dot(glm::normalize(a), glm::normalize(b))));
  return glm::degrees(2.0f * std::acos(d));
}

TEST(Quantize, RotationsRoundTripWithinAQuarterOfADegree) {
  uint32_t seed = 12345u;
  auto next = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return static_cast<float>(seed >> 8) / static_cast<float>(1u << 24) * 2.0f - 1.0f;
  };
  float worst = 0.0f;
  for (int i = 0; i < 20000; ++i) {
    const quat q = glm::normalize(quat(next(), next(), next(), next()));
    const quat back = dequantize_rotation(quantize_rotation(q));
    worst = std::max(worst, rotation_error_deg(q, back));
  }
  EXPECT_LT(worst, 0.25f);
  // Components land where they were (not permuted): a rotation about +Y stays about +Y.
  const quat about_y = glm::angleAxis(0.7f, vec3(0.0f, 1.0f, 0.0f));
  const quat back = dequantize_rotation(quantize_rotation(about_y));
  EXPECT_NEAR(back.y, about_y.y, 2e-3f);
  EXPECT_NEAR(back.w, about_y.w, 2e-3f);
  EXPECT_NEAR(back.x, 0.0f, 2e-3f);
  // q and -q are one rotation; identity and broken input decode to a unit quaternion.
  EXPECT_LT(rotation_error_deg(dequantize_rotation(quantize_rotation(-about_y)), about_y), 0.25f);
  const quat nan_q = dequantize_rotation(quantize_rotation(quat(NAN, 0.0f, 0.0f, 0.0f)));
  EXPECT_NEAR(glm::length(nan_q), 1.0f, 1e-5f);
  EXPECT_NEAR(std::abs(nan_q.w), 1.0f, 1e-3f);
}

}  // namespace
}  // namespace foresight::protocol
