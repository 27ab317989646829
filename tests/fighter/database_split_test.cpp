// Splitting captured takes into one strike per entry (strike_split.hpp) on the real Bandai takes:
// the punch takes hold 5 punches each, the kick take 3 kicks (each followed by a spin).
#include "import/bvh_import.hpp"
#include "anim/fk.hpp"
#include "anim/root_motion.hpp"
#include "fighter_build/strike_split.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

struct LoadedTake {
  Skeleton skeleton;
  Clip clip;
  FighterRig rig;
  std::vector<vec3> global;
  std::vector<Placement> track;
  TakeMotionView view() const {
    TakeMotionView v;
    v.rig = &rig;
    v.global_pos_m = global;
    v.root_track = track;
    v.num_joints = clip.num_joints;
    v.num_frames = clip.num_frames;
    v.fps = clip.fps;
    return v;
  }
};

void load(const std::string& file, LoadedTake& t) {
  std::string error;
  ASSERT_TRUE(clip_load_bvh(test::mocap_dir() / "fighting" / file, {}, t.skeleton, t.clip, nullptr, error)) << error;
  ASSERT_TRUE(fighter_rig_from_skeleton(t.skeleton, t.rig, error)) << error;
  fk_clip_positions(t.skeleton, t.clip, t.global);
  extract_root_track(t.clip, find_forward_axis(t.skeleton, t.clip), t.track);
}

std::string describe(const Skeleton& s, const std::vector<DetectedStrike>& found) {
  std::string out;
  for (const DetectedStrike& d : found)
    out += s.joint_names[static_cast<std::size_t>(d.hit_joint)] + " " + std::to_string(d.start_frame) + ".." +
           std::to_string(d.hit_frame) + ".." + std::to_string(d.end_frame) + " (" +
           std::to_string(d.peak_speed_mps) + " m/s)\n";
  return out;
}

void expect_strikes(const std::string& file, int count, StrikeKind kind, StrikeSide side) {
  LoadedTake t;
  load(file, t);
  if (::testing::Test::HasFatalFailure()) return;
  const std::vector<DetectedStrike> found = strike_detect(t.view(), StrikeSplitParams{});
  const std::string text = describe(t.skeleton, found);
  ASSERT_EQ(static_cast<int>(found.size()), count) << file << ":\n" << text;
  const int effector = kind == StrikeKind::kPunch ? t.rig.arm[static_cast<std::size_t>(side)].end
                                                  : t.rig.leg[static_cast<std::size_t>(side)].end;
  for (std::size_t i = 0; i < found.size(); ++i) {
    const DetectedStrike& d = found[i];
    EXPECT_EQ(d.kind, kind) << text;
    EXPECT_EQ(d.side, side) << text;
    EXPECT_EQ(d.hit_joint, effector) << text;
    EXPECT_LT(d.start_frame, d.hit_frame) << text;
    EXPECT_LT(d.hit_frame, d.end_frame) << text;
    if (i > 0) {
      EXPECT_LT(found[i - 1].end_frame, d.start_frame) << "windows overlap:\n" << text;
    }
  }
}

TEST(StrikeSplit, FindsTheFiveLeftPunches) {
  FORESIGHT_REQUIRE_MOCAP();
  expect_strikes("bandai_dataset-1_punch_normal_001.bvh", 5, StrikeKind::kPunch, StrikeSide::kLeft);
}

TEST(StrikeSplit, FindsTheFiveRightPunches) {
  FORESIGHT_REQUIRE_MOCAP();
  expect_strikes("bandai_dataset-1_punch_normal_002.bvh", 5, StrikeKind::kPunch, StrikeSide::kRight);
}

TEST(StrikeSplit, FindsTheThreeRightKicksAndNotTheSpins) {
  FORESIGHT_REQUIRE_MOCAP();
  expect_strikes("bandai_dataset-1_kick_normal_001.bvh", 3, StrikeKind::kKick, StrikeSide::kRight);
}

TEST(StrikeSplit, AKickLandsAtChestHeight) {
  FORESIGHT_REQUIRE_MOCAP();
  LoadedTake t;
  load("bandai_dataset-1_kick_normal_001.bvh", t);
  const std::vector<DetectedStrike> kicks = strike_detect(t.view(), StrikeSplitParams{});
  // The README measures the kicking foot's peaks at 0.97-1.04 m.
  for (const DetectedStrike& d : kicks) {
    EXPECT_GT(t.view().pos(d.hit_frame, d.hit_joint).y, 0.8f);
    EXPECT_LT(t.view().pos(d.hit_frame, d.hit_joint).y, 1.2f);
  }
}

TEST(StrikeSplit, AStillTakeHasNoStrike) {
  FORESIGHT_REQUIRE_MOCAP();
  LoadedTake t;
  load("bandai_dataset-1_punch_normal_001.bvh", t);
  // Freeze the take on its first frame: nothing moves, so nothing is struck.
  const std::size_t j = static_cast<std::size_t>(t.clip.num_joints);
  for (int f = 1; f < t.clip.num_frames; ++f) {
    std::copy(t.global.begin(), t.global.begin() + static_cast<std::ptrdiff_t>(j),
              t.global.begin() + static_cast<std::ptrdiff_t>(f * j));
    t.track[static_cast<std::size_t>(f)] = t.track[0];
  }
  EXPECT_TRUE(strike_detect(t.view(), StrikeSplitParams{}).empty());
}

TEST(StrikeSplit, AGivenHitGetsAWindowAroundIt) {
  FORESIGHT_REQUIRE_MOCAP();
  LoadedTake t;
  load("bandai_dataset-1_punch_normal_002.bvh", t);
  const std::vector<DetectedStrike> found = strike_detect(t.view(), StrikeSplitParams{});
  ASSERT_FALSE(found.empty());
  int start = -1, end = -1;
  strike_window(t.view(), found[0].hit_joint, found[0].hit_frame, StrikeSplitParams{}, start, end);
  EXPECT_LT(start, found[0].hit_frame);
  EXPECT_GT(end, found[0].hit_frame);
  // Frames the sidecar gives are kept.
  start = 3;
  end = found[0].hit_frame + 2;
  strike_window(t.view(), found[0].hit_joint, found[0].hit_frame, StrikeSplitParams{}, start, end);
  EXPECT_EQ(start, 3);
  EXPECT_EQ(end, found[0].hit_frame + 2);
}

}  // namespace
}  // namespace foresight
