// The library's own accelerations, its pop threshold and steering's per-frame limit
// (library_build/pop_budget.hpp). That the limit keeps steered frames under the threshold is
// tested where steering runs (LookaheadAvatar.SteeringAddsNoPopToAFrameWithRoomForIt).
#include "library_build/library_source.hpp"
#include "library_build/pop_budget.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight {
namespace {

const MotionLibrary& library() {
  static const MotionLibrary lib = motion_library_default();
  return lib;
}

TEST(PopBudget, TheLibrarysPopThresholdIsItsOwnClipsNinetyNinePointNinthPercentile) {
  const MotionLibrary& lib = library();
  EXPECT_GT(lib.pop_threshold_m, 0.01f);  // above walking's few mm per frame^2
  EXPECT_LT(lib.pop_threshold_m, 0.4f);   // below NoJointPops' per-frame bound x 2
  ASSERT_EQ(lib.frame_acceleration_m.size(), lib.root_track.size());
  int64_t inner = 0, over = 0;
  for (size_t c = 0; c < lib.clips.size(); ++c) {
    const int frames = lib.clips[c].num_frames;
    ASSERT_GE(frames, 3);
    const int clip = static_cast<int>(c);
    // A clip's ends have one neighbour only: they take the next inner frame's acceleration.
    EXPECT_EQ(lib.frame_acceleration_at(clip, 0), lib.frame_acceleration_at(clip, 1));
    EXPECT_EQ(lib.frame_acceleration_at(clip, frames - 1), lib.frame_acceleration_at(clip, frames - 2));
    EXPECT_EQ(lib.frame_acceleration_at(clip, frames + 5), lib.frame_acceleration_at(clip, frames - 1))
        << "past the end: the last frame";
    for (int f = 1; f + 1 < frames; ++f, ++inner) over += lib.frame_acceleration_at(clip, f) > lib.pop_threshold_m;
  }
  // By definition about 0.1 % of the clips' inner frames are over it (ties and rounding aside).
  EXPECT_GT(over, 0);
  EXPECT_LE(over, inner / 500);
}

// The limit binds where a clip has little room (a fast run) and not where it has plenty
// (standing, the start of a walk, a side step); it never drops under the floor and changes by at
// most the ramp from one frame to the next.
TEST(PopBudget, SteeringsLimitIsFlooredRampedAndTightestWhereTheClipHasLeastRoom) {
  const MotionLibrary& lib = library();
  ASSERT_EQ(lib.steer_limit_rad.size(), lib.root_track.size());
  const float full = radians(540.0f) / 30.0f;  // the default steering rate, per frame
  for (size_t c = 0; c < lib.clips.size(); ++c) {
    const int clip = static_cast<int>(c);
    for (int f = 0; f < lib.clips[c].num_frames; ++f) {
      EXPECT_GE(lib.steer_limit_at(clip, f), kSteerLimitFloor_rad);
      if (f > 0) {
        EXPECT_LE(std::abs(lib.steer_limit_at(clip, f) - lib.steer_limit_at(clip, f - 1)), kSteerLimitRamp_rad + 1e-6f)
            << lib.clips[c].name << " frame " << f;
      }
    }
  }
  const auto tightest = [&](const char* segment) {
    const Segment& s = lib.graph.segments[static_cast<size_t>(lib.graph.find_segment(segment))];
    float least = kPi;
    for (int f = s.first_frame; f < s.end_frame; ++f) least = std::min(least, lib.steer_limit_at(s.clip, f));
    return least;
  };
  EXPECT_LT(tightest("run_l"), full / 2.0f) << "a run is fast";
  EXPECT_GE(tightest("idle"), full) << "standing has room for any turn";
  EXPECT_GT(tightest("walk_l"), tightest("run_l"));
  // A side step is steered at a third of the rate (LookaheadAvatar::kSidewaysSteerShare); its
  // frames leave room for that throughout. Its swings once took 0.1 s each (own acceleration 112
  // of the 121 threshold, no room: the floor turned them anyway, and 9 of the built-in library's
  // 14 pops in 800 closed-loop runs were side steps' knees and toes; docs/MOTION_QUALITY.md,
  // "Side steps with room to steer").
  for (const char* side_step : {"side_step_left", "side_step_right"})
    EXPECT_GE(tightest(side_step), full / 3.0f) << side_step;
}

}  // namespace
}  // namespace foresight
