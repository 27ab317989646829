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
