#include "graph_build/auto_graph.hpp"
#include "library/motion_library.hpp"
#include "library_build/library_compile.hpp"
#include "library/playback.hpp"
#include "library_checks.hpp"
#include "../graph/graph_test_clips.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

MotionLibrarySource walker_source() {
  MotionLibrarySource lib;
  lib.name = "walker";
  lib.skeleton = test::walker_skeleton();
  lib.clips = {test::walker_clip(lib.skeleton, "a", 90, 30, 0),
               test::walker_clip(lib.skeleton, "b", 90, 30, 10)};
  lib.clip_tags = {kTagLocomotion, kTagLocomotion};
  std::string error;
  EXPECT_TRUE(graph_build_automatic(lib.skeleton, lib.clips, AutoGraphOptions{}, lib.graph,
                                    nullptr, error))
      << error;
  return lib;
}

MotionLibrary walker_library() {
  MotionLibrary lib;
  std::string error;
  EXPECT_TRUE(motion_library_compile(walker_source(), lib, error)) << error;
  return lib;
}

TEST(MotionLibrary, RelativeMovementIsInTheSegmentsOwnFrame) {
  const MotionLibrary lib = walker_library();
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const SegmentMotion& m = lib.segment_motion[s];
    const float seconds = lib.graph.segments[s].num_frames() / 30.0f;
    // The walker goes straight ahead (+Z) at 1.2 m/s and never turns.
    EXPECT_NEAR(m.end.pos_m.y, 1.2f * seconds, 1e-3f);
    EXPECT_NEAR(m.end.pos_m.x, 0.0f, 1e-3f);
    EXPECT_NEAR(m.end.heading_rad, 0.0f, 1e-4f);
    EXPECT_EQ(lib.volumes(s).size(), static_cast<size_t>(lib.graph.segments[s].num_frames() + 1));
  }
}

TEST(MotionLibrary, PlaybackFromARotatedPlacementFollowsIt) {
  const MotionLibrary lib = walker_library();
  PlaybackState s{0, 0, Placement{vec2(5, 5), kPi / 2}, -1};
  const Placement start = playback_root(lib, s);
  EXPECT_NEAR(start.pos_m.x, 5.0f, 1e-4f);
  s.frame = 30;
  const Placement later = playback_root(lib, s);
  // Heading pi/2 faces +X: one second at 1.2 m/s moves 1.2 m along +X.
  EXPECT_NEAR(later.pos_m.x - start.pos_m.x, 1.2f, 1e-3f);
  EXPECT_NEAR(later.pos_m.y - start.pos_m.y, 0.0f, 1e-3f);
}

TEST(MotionLibrary, EdgesAreContinuous) {
  test::expect_continuous_edges(walker_library(), 2.0f, 0.01f);
}

TEST(MotionLibrary, ContentHashChangesWithTheData) {
  const MotionLibrary a = walker_library();
  EXPECT_EQ(a.content_hash, walker_library().content_hash);
  MotionLibrarySource changed = walker_source();
  changed.clips[0].frame_rot(5)[1] = quat(1, 0, 0, 0);
  MotionLibrary b;
  std::string error;
  ASSERT_TRUE(motion_library_compile(std::move(changed), b, error));
  EXPECT_NE(a.content_hash, b.content_hash);
}

TEST(MotionLibrary, CompileRefusesSegmentsOutsideTheirClip) {
  MotionLibrarySource source = walker_source();
  source.graph.segments[0].end_frame = source.clips[source.graph.segments[0].clip].num_frames;
  MotionLibrary lib;
  std::string error;
  EXPECT_FALSE(motion_library_compile(std::move(source), lib, error));
  EXPECT_NE(error.find("outside its clip"), std::string::npos) << error;
  EXPECT_EQ(lib.content_hash, 0u);  // nothing compiled into it
}

}  // namespace
}  // namespace foresight
