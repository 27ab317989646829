// The strike sidecar (strike_annotation.hpp): round trips, and one test per way a file is broken,
// each checking that the message names the file and the field.
#include "author/default_skeleton.hpp"
#include "fighter_build/strike_annotation.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace foresight {
namespace {

StrikeSidecar sample() {
  StrikeSidecar s;
  ClipStrikes take;
  take.clip = "take.bvh";
  StrikeMark a;
  a.hit_joint = "LeftHand";
  a.kind = StrikeKind::kPunch;
  a.side = StrikeSide::kLeft;
  a.height = StrikeHeight::kHigh;
  a.hit_frame = 12;
  a.start_frame = 3;
  a.end_frame = 20;
  StrikeMark b;
  b.hit_joint = "RightFoot";
  b.kind = StrikeKind::kKick;
  b.side = StrikeSide::kRight;
  b.hit_frame = 40;  // height and window left to the loader
  take.strikes = {a, b};
  ClipStrikes cuts;
  cuts.clip = "cuts.bvh";
  cuts.skip = true;
  s.clips = {cuts, take};  // sorted by name
  return s;
}

// A one-strike sidecar with `strike` as the strike object's JSON.
std::string with_strike(const std::string& strike) {
  return R"({"format": "foresight-strikes", "version": 1, "clips": {"take.bvh": {"strikes": [)" + strike + "]}}}";
}

std::string parse_error(const std::string& text) {
  StrikeSidecar s;
  std::string error;
  EXPECT_FALSE(strike_sidecar_parse(text, "folder/strikes.json", s, error));
  return error;
}

TEST(StrikeSidecar, RoundTripsThroughText) {
  const StrikeSidecar s = sample();
  const std::string text = strike_sidecar_write(s);
  StrikeSidecar back;
  std::string error;
  ASSERT_TRUE(strike_sidecar_parse(text, "mem", back, error)) << error;
  EXPECT_EQ(back, s);
  EXPECT_EQ(strike_sidecar_write(back), text);  // stable text: diffs of edited files stay small
  ASSERT_NE(back.find("take.bvh"), nullptr);
  EXPECT_FALSE(back.find("take.bvh")->strikes[1].height.has_value());
  EXPECT_EQ(back.find("take.bvh")->strikes[1].start_frame, -1);
  EXPECT_EQ(back.find("missing.bvh"), nullptr);
}

TEST(StrikeSidecar, RoundTripsThroughAFileAndCanBeEdited) {
  const std::filesystem::path path = test::scratch_dir() / "strikes.json";
  StrikeSidecar s = sample();
  std::string error;
  ASSERT_TRUE(strike_sidecar_save(path, s, error)) << error;
  StrikeSidecar back;
  ASSERT_TRUE(strike_sidecar_load(path, back, error)) << error;
  EXPECT_EQ(back, s);
  // Edit one hit frame, save, reload: the edit is there.
  back.clips[1].strikes[0].hit_frame = 13;
  ASSERT_TRUE(strike_sidecar_save(path, back, error)) << error;
  StrikeSidecar again;
  ASSERT_TRUE(strike_sidecar_load(path, again, error)) << error;
  EXPECT_EQ(again.clips[1].strikes[0].hit_frame, 13);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
}

TEST(StrikeSidecar, ReadsAPerClipFile) {
  const std::string text =
      R"({"format": "foresight-strikes", "version": 1, "_note": "hand edited",
          "strikes": [{"hit_joint": "LeftHand", "kind": "punch", "side": "left", "hit_frame": 5}]})";
  ClipStrikes c;
  std::string error;
  ASSERT_TRUE(strike_clip_sidecar_parse(text, "take.strikes.json", "take.bvh", c, error)) << error;
  EXPECT_EQ(c.clip, "take.bvh");
  ASSERT_EQ(c.strikes.size(), 1u);
  EXPECT_EQ(c.strikes[0].hit_frame, 5);
}

TEST(StrikeSidecar, MalformedJsonNamesFileLineAndColumn) {
  const std::string error = parse_error("{\"format\": \"foresight-strikes\",\n  \"version\": 1,,\n}");
  EXPECT_NE(error.find("folder/strikes.json"), std::string::npos) << error;
  EXPECT_NE(error.find("line 2"), std::string::npos) << error;
}

TEST(StrikeSidecar, BadKindNamesTheField) {
  const std::string error = parse_error(with_strike(R"({"hit_joint": "LeftHand", "kind": "slap", "side": "left", "hit_frame": 3})"));
  EXPECT_NE(error.find("folder/strikes.json: clips.take.bvh.strikes[0].kind"), std::string::npos) << error;
  EXPECT_NE(error.find("\"slap\""), std::string::npos) << error;
}

TEST(StrikeSidecar, BadSideAndHeightNameTheField) {
  std::string error = parse_error(with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "up", "hit_frame": 3})"));
  EXPECT_NE(error.find("strikes[0].side"), std::string::npos) << error;
  error = parse_error(
      with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "left", "height": "top", "hit_frame": 3})"));
  EXPECT_NE(error.find("strikes[0].height"), std::string::npos) << error;
}

TEST(StrikeSidecar, MissingAndMistypedFieldsAreNamed) {
  std::string error = parse_error(with_strike(R"({"kind": "punch", "side": "left", "hit_frame": 3})"));
  EXPECT_NE(error.find("hit_joint"), std::string::npos) << error;
  error = parse_error(with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "left"})"));
  EXPECT_NE(error.find("hit_frame"), std::string::npos) << error;
  error = parse_error(with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "left", "hit_frame": "3"})"));
  EXPECT_NE(error.find("strikes[0].hit_frame: expected an integer"), std::string::npos) << error;
  error = parse_error(with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "left", "hit_frame": 3, "hit_time": 1})"));
  EXPECT_NE(error.find("hit_time"), std::string::npos) << error;
}

TEST(StrikeSidecar, FramesOutOfOrderOrNegativeAreRefused) {
  std::string error = parse_error(with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "left", "hit_frame": -1})"));
  EXPECT_NE(error.find("strikes[0].hit_frame"), std::string::npos) << error;
  error = parse_error(
      with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "left", "hit_frame": 5, "start_frame": 9})"));
  EXPECT_NE(error.find("strikes[0].start_frame: 9 is after hit_frame 5"), std::string::npos) << error;
  error = parse_error(
      with_strike(R"({"hit_joint": "LeftHand", "kind": "punch", "side": "left", "hit_frame": 5, "end_frame": 2})"));
  EXPECT_NE(error.find("strikes[0].end_frame: 2 is before hit_frame 5"), std::string::npos) << error;
}

TEST(StrikeSidecar, WrongFormatOrVersionIsRefused) {
  std::string error = parse_error(R"({"format": "scene", "version": 1, "clips": {}})");
  EXPECT_NE(error.find("format"), std::string::npos) << error;
  error = parse_error(R"({"format": "foresight-strikes", "version": 2, "clips": {}})");
  EXPECT_NE(error.find("version 2 is not supported"), std::string::npos) << error;
  error = parse_error(R"({"format": "foresight-strikes", "version": 1, "clips": []})");
  EXPECT_NE(error.find("clips: expected an object"), std::string::npos) << error;
  error = parse_error(R"({"format": "foresight-strikes", "version": 1, "clips": {"a.bvh": {"skip": "yes"}}})");
  EXPECT_NE(error.find("clips.a.bvh.skip"), std::string::npos) << error;
}

TEST(StrikeSidecar, UnknownJointAndFrameOutOfRangeNeedTheClip) {
  const Skeleton skeleton = author::default_skeleton();
  ClipStrikes c;
  c.clip = "take.bvh";
  StrikeMark m;
  m.hit_joint = "LeftHand";
  m.hit_frame = 10;
  c.strikes = {m};
  std::string error;
  EXPECT_TRUE(strike_marks_check(c, skeleton, 30, "folder/strikes.json", error)) << error;

  c.strikes[0].hit_joint = "LeftFist";
  EXPECT_FALSE(strike_marks_check(c, skeleton, 30, "folder/strikes.json", error));
  EXPECT_NE(error.find("folder/strikes.json: take.bvh: strikes[0].hit_joint: no joint \"LeftFist\""), std::string::npos)
      << error;

  c.strikes[0].hit_joint = "LeftHand";
  c.strikes[0].end_frame = 30;
  EXPECT_FALSE(strike_marks_check(c, skeleton, 30, "folder/strikes.json", error));
  EXPECT_NE(error.find("strikes[0].end_frame: 30 is out of range: the clip has 30 frames"), std::string::npos) << error;
}

TEST(StrikeSidecar, AMissingFileIsNamed) {
  StrikeSidecar s;
  std::string error;
  EXPECT_FALSE(strike_sidecar_load(test::scratch_dir() / "nope.json", s, error));
  EXPECT_NE(error.find("nope.json"), std::string::npos) << error;
}

}  // namespace
}  // namespace foresight
