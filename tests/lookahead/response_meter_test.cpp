// The responsiveness measure (ResponseMeter, docs/LAB.md) on points moved by hand: when a change
// of command counts as followed, and which changes are not counted.
#include "scripted/response_meter.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace foresight {
namespace {

constexpr double kFrame_s = 1.0 / 30.0;
constexpr float kSpeed_mps = 1.2f;

// A point walking +X at 1.2 m/s for a second, then (from `turn_frame`) +Z, under `command_at`
// (the command for each frame); the frames on which a response was recorded, and their ms.
struct Walk {
  std::vector<Response> responses;
  std::vector<int> frames;
};
Walk walk(int turn_frame, int frames, vec2 (*command_at)(int)) {
  ResponseMeter meter(kFrame_s);
  Walk w;
  vec2 p(0.0f);
  for (int f = 0; f < frames; ++f) {
    p += (f < turn_frame ? vec2(1.0f, 0.0f) : vec2(0.0f, 1.0f)) * kSpeed_mps * static_cast<float>(kFrame_s);
    if (meter.frame(f * kFrame_s, command_at(f), p, f)) {
      w.responses.push_back(meter.last());
      w.frames.push_back(f);
    }
  }
  return w;
}

TEST(ResponseMeter, AnInstantTurnIsFollowedWhenTheLastFifthOfASecondPointsWithin30Degrees) {
  // The command turns +X -> +Z at frame 30 and the point turns with it on that very frame: the
  // velocity over the last 6 frames (0.2 s) is within 30 deg of +Z once 4 of its 6 steps go that
  // way (atan 4/2 = 63 deg from +X; 3 of 6 is 45), 3 frames later: 100 ms, the measure's floor
  // for a 90 deg turn (a point that turns a frame later: 133 ms).
  const Walk w = walk(30, 60, [](int f) { return f < 30 ? vec2(1.0f, 0.0f) : vec2(0.0f, 1.0f); });
  ASSERT_EQ(w.responses.size(), 2u) << "the first command (after standing) and the turn";
  EXPECT_EQ(w.responses[0].change_deg, 180.0f) << "a command after a stop";
  EXPECT_NEAR(w.responses[0].ms, 200.0, 1e-6) << "once the window (6 steps) is full";
  EXPECT_NEAR(w.responses[1].at_s, 30 * kFrame_s, 1e-9);
  EXPECT_NEAR(w.responses[1].change_deg, 90.0f, 1e-3f);
  EXPECT_NEAR(w.responses[1].ms, 100.0, 0.01);
  EXPECT_EQ(w.responses[1].segment_at_change, 30);
  EXPECT_EQ(w.responses[1].segment_at_response, 33);
  const Walk late = walk(31, 60, [](int f) { return f < 30 ? vec2(1.0f, 0.0f) : vec2(0.0f, 1.0f); });
  ASSERT_EQ(late.responses.size(), 2u);
  EXPECT_NEAR(late.responses[1].ms, 133.333, 0.01) << "turning a frame after the command";
}

TEST(ResponseMeter, ChangesNotFollowedOrCancelledAreNotCounted) {
  // The command turns to +Z at frame 30 but the point keeps going +X: no response.
  const Walk ignored = walk(1000, 60, [](int f) { return f < 30 ? vec2(1.0f, 0.0f) : vec2(0.0f, 1.0f); });
  EXPECT_EQ(ignored.responses.size(), 1u) << "only the first command";
  // Released (no command) for a frame before the point turned: the turn's change is cancelled;
  // the command after the release is a new change (after a stop).
  const Walk released = walk(32, 60, [](int f) {
    if (f == 31) return vec2(0.0f);
    return f < 30 ? vec2(1.0f, 0.0f) : vec2(0.0f, 1.0f);
  });
  ASSERT_EQ(released.responses.size(), 2u);
  EXPECT_EQ(released.responses[1].change_deg, 180.0f);
  EXPECT_NEAR(released.responses[1].at_s, 32 * kFrame_s, 1e-9);
  // A small change (20 deg) is not a change: the point is already following it.
  const Walk small = walk(1000, 60, [](int f) { return f < 30 ? vec2(1.0f, 0.0f) : vec2(1.0f, 0.36f); });
  EXPECT_EQ(small.responses.size(), 1u);
}

}  // namespace
}  // namespace foresight
