#include "snapshot_buffer.hpp"

#include "library_build/library_source.hpp"
#include "protocol/protocol.hpp"

#include <gtest/gtest.h>

namespace foresight::client {
namespace {

const MotionLibrary& library() {
  static const MotionLibrary lib = motion_library_default();
  return lib;
}

// A segment with at least `frames` frames, and a transition out of it.
int long_segment(int frames) {
  const auto& g = library().graph;
  for (size_t t = 0; t < g.transitions.size(); ++t) {
    const int s = g.transitions[t].from;
    if (g.segments[static_cast<size_t>(s)].num_frames() >= frames) return s;
  }
  return 0;
}

AvatarEntry entry(uint32_t id, int segment, int frame) {
  AvatarEntry e;
  e.id = id;
  e.state.segment = segment;
  e.state.frame = frame;
  return e;
}

double shown_frame(const ShownAvatar& a) { return a.state.frame + a.frame_alpha; }

TEST(SnapshotBuffer, InterpolatesFramesBetweenInOrderSnapshots) {
  const int seg = long_segment(12);
  SnapshotBuffer buf;
  for (int i = 0; i < 4; ++i) {
    const AvatarEntry e = entry(7, seg, 2 * i);
    buf.push(0.1 * i, 10.0 + 0.1 * i, {&e, 1});
  }
  std::vector<ShownAvatar> out;
  buf.sample(library(), 0.15, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].id, 7u);
  EXPECT_NEAR(shown_frame(out[0]), 3.0, 1e-4);
  EXPECT_FALSE(out[0].extrapolated);
  // render_time: the newest snapshot's time minus the delay, at its arrival.
  EXPECT_NEAR(buf.render_time(10.3), 0.3 - 0.1, 1e-9);
}

TEST(SnapshotBuffer, LostSnapshotIsBridged) {
  const int seg = long_segment(12);
  SnapshotBuffer buf;
  const AvatarEntry a = entry(1, seg, 0), c = entry(1, seg, 8);
  buf.push(0.0, 0.0, {&a, 1});
  buf.push(0.4, 0.4, {&c, 1});  // 0.1 .. 0.3 lost
  std::vector<ShownAvatar> out;
  buf.sample(library(), 0.2, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(shown_frame(out[0]), 4.0, 1e-4);
}

TEST(SnapshotBuffer, ReorderedSnapshotsAreSortedAndDuplicatesReplace) {
  const int seg = long_segment(12);
  SnapshotBuffer buf;
  const AvatarEntry a = entry(1, seg, 0), b = entry(1, seg, 2), c = entry(1, seg, 4);
  buf.push(0.0, 0.0, {&a, 1});
  buf.push(0.2, 0.2, {&c, 1});
  buf.push(0.1, 0.25, {&b, 1});  // arrives after the newer one
  buf.push(0.1, 0.26, {&b, 1});  // duplicate
  EXPECT_EQ(buf.size(), 3u);
  std::vector<ShownAvatar> out;
  buf.sample(library(), 0.15, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(shown_frame(out[0]), 3.0, 1e-4);
}

TEST(SnapshotBuffer, LateSnapshotsExtrapolateUpToTheCap) {
  const MotionLibrary& lib = library();
  const int seg = long_segment(40);
  const int clip = lib.graph.segments[static_cast<size_t>(seg)].clip;
  const double fps = lib.clips[static_cast<size_t>(clip)].fps;
  const int n = lib.graph.segments[static_cast<size_t>(seg)].num_frames();
  SnapshotBufferConfig config;
  config.max_extrapolation_s = 0.25;
  SnapshotBuffer buf(config);
  const AvatarEntry a = entry(3, seg, 0);
  buf.push(0.0, 0.0, {&a, 1});
  std::vector<ShownAvatar> out;
  buf.sample(lib, 0.1, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].extrapolated);
  EXPECT_NEAR(shown_frame(out[0]), std::min<double>(n, 0.1 * fps), 1e-3);
  buf.sample(lib, 5.0, out);  // far too late: capped
  EXPECT_NEAR(shown_frame(out[0]), std::min<double>(n, 0.25 * fps), 1e-3);
}

TEST(SnapshotBuffer, SegmentChangePlaysTheEarlierSegmentToItsEnd) {
  const MotionLibrary& lib = library();
  const auto& g = lib.graph;
  const int seg = long_segment(6);
  int tr = -1;
  for (size_t t = 0; t < g.transitions.size() && tr < 0; ++t)
    if (g.transitions[t].from == seg) tr = static_cast<int>(t);
  ASSERT_GE(tr, 0);
  const int n = g.segments[static_cast<size_t>(seg)].num_frames();
  AvatarEntry a = entry(1, seg, n - 2);
  AvatarEntry b = entry(1, g.transitions[static_cast<size_t>(tr)].to, 2);
  b.state.incoming_transition = tr;
  b.state.segment_start.pos_m = vec2(1.0f, 2.0f);
  SnapshotBuffer buf;
  buf.push(0.0, 0.0, {&a, 1});
  buf.push(0.4, 0.4, {&b, 1});
  std::vector<ShownAvatar> out;
  buf.sample(lib, 0.1, out);  // 1 of 4 frames: still in the first segment
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].state.segment, seg);
  EXPECT_NEAR(shown_frame(out[0]), n - 1, 1e-4);
  buf.sample(lib, 0.3, out);  // 3 of 4: one frame into the successor, entered by the transition
  EXPECT_EQ(out[0].state.segment, b.state.segment);
  EXPECT_EQ(out[0].state.incoming_transition, tr);
  EXPECT_EQ(out[0].state.segment_start.pos_m, b.state.segment_start.pos_m);
  EXPECT_NEAR(shown_frame(out[0]), 1.0, 1e-4);
}

// Steering mode turns a playing segment: its start changes from one snapshot to the next while
// the frame runs on. That is one play-through, shown turning, not the segment played to its end
// and started again; a start that moved by a whole play-through still is a new one.
TEST(SnapshotBuffer, ASteeredStartTurnsWithinOnePlayThrough) {
  const MotionLibrary& lib = library();
  const int seg = long_segment(12);
  const int n = lib.graph.segments[static_cast<size_t>(seg)].num_frames();
  AvatarEntry a = entry(1, seg, 2), b = entry(1, seg, 5);  // 0.1 s apart: 3 frames at 30 fps
  b.state.segment_start = Placement{vec2(0.02f, -0.01f), 0.5f};
  SnapshotBuffer buf;
  buf.push(0.0, 0.0, {&a, 1});
  buf.push(0.1, 0.1, {&b, 1});
  std::vector<ShownAvatar> out;
  buf.sample(lib, 0.05, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].state.segment, seg);
  EXPECT_NEAR(shown_frame(out[0]), 3.5, 1e-4);
  EXPECT_NEAR(out[0].state.segment_start.heading_rad, 0.25f, 1e-5f);
  EXPECT_NEAR(out[0].state.segment_start.pos_m.x, 0.01f, 1e-5f);

  // Half a second on (15 frames) the same segment one frame later: played to its end and again.
  AvatarEntry c = entry(2, seg, 1), d = entry(2, seg, 2);
  d.state.segment_start = Placement{vec2(0.0f, 0.7f), 0.0f};
  SnapshotBuffer again;
  again.push(0.0, 0.0, {&c, 1});
  again.push(static_cast<double>(n) / 30.0, 1.0, {&d, 1});
  again.sample(lib, 0.1, out);  // 3 frames in: still the first play-through, at its own start
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].state.segment_start.pos_m, c.state.segment_start.pos_m);
  EXPECT_GT(shown_frame(out[0]), 2.5);
}

TEST(SnapshotBuffer, AvatarsAppearAndDisappear) {
  const int seg = long_segment(12);
  SnapshotBuffer buf;
  const AvatarEntry s0[] = {entry(1, seg, 0), entry(2, seg, 0)};
  const AvatarEntry s1[] = {entry(2, seg, 2), entry(3, seg, 0)};  // 1 left, 3 joined
  buf.push(0.0, 0.0, s0);
  buf.push(0.1, 0.1, s1);
  std::vector<ShownAvatar> out;
  buf.sample(library(), 0.05, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].id, 1u);
  EXPECT_EQ(out[1].id, 2u);
  EXPECT_NEAR(shown_frame(out[1]), 1.0, 1e-4);
  buf.sample(library(), 0.12, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].id, 2u);
  EXPECT_EQ(out[1].id, 3u);
}

TEST(SnapshotBuffer, FullBufferDropsTheOldestAndTooOldSnapshots) {
  SnapshotBufferConfig config;
  config.capacity = 4;
  SnapshotBuffer buf(config);
  const AvatarEntry a = entry(1, 0, 0);
  for (int i = 0; i < 10; ++i) buf.push(0.05 * i, 0.05 * i, {&a, 1});
  EXPECT_EQ(buf.size(), 4u);
  EXPECT_NEAR(buf.newest_time(), 0.45, 1e-9);
  buf.push(0.0, 0.5, {&a, 1});  // older than all kept
  EXPECT_EQ(buf.size(), 4u);
  buf.push(0.325, 0.5, {&a, 1});  // between kept ones: the oldest goes
  EXPECT_EQ(buf.size(), 4u);
  EXPECT_NEAR(buf.newest_time(), 0.45, 1e-9);
}

TEST(SnapshotBuffer, AFarAvatarIsShownBetweenItsSparseSnapshots) {
  // A near avatar (1) in every snapshot, a far one (2, flagged kAvatarFar) in every 4th: the far
  // one is shown all along, interpolated between its own snapshots.
  const int seg = long_segment(30);
  SnapshotBuffer buf;
  for (int i = 0; i <= 12; ++i) {
    std::vector<AvatarEntry> es{entry(1, seg, i)};
    if (i % 4 == 0) {
      es.push_back(entry(2, seg, 2 * i));
      es.back().flags = protocol::kAvatarFar;
    }
    buf.push(0.05 * i, 0.05 * i, es);
  }
  std::vector<ShownAvatar> out;
  for (double t = 0.0; t <= 0.6; t += 0.01) {
    buf.sample(library(), t, out);
    ASSERT_EQ(out.size(), 2u) << "at " << t;
    EXPECT_EQ(out[0].id, 1u);
    EXPECT_EQ(out[1].id, 2u);
    EXPECT_NEAR(shown_frame(out[1]), 2 * t / 0.05, 0.05) << "at " << t;
  }
  // Without the flag a missing avatar is gone (it left).
  SnapshotBuffer plain;
  for (int i = 0; i <= 4; ++i) {
    std::vector<AvatarEntry> es{entry(1, seg, i)};
    if (i == 0) es.push_back(entry(2, seg, 0));
    plain.push(0.05 * i, 0.05 * i, es);
  }
  plain.sample(library(), 0.12, out);
  EXPECT_EQ(out.size(), 1u);
}

}  // namespace
}  // namespace foresight::client
