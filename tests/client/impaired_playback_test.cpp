// Interpolation under a hostile network (issue 8): the snapshots of an avatar looping one walk
// segment, 20 a second, go through the impairment layer (5 % loss, 50 +- 20 ms, 1 % duplicates,
// 1 % reordered) into the client's SnapshotBuffer, which is sampled at 60 frames a second as the
// client draws. What the player sees stays on the server's timeline (within a frame nearly always)
// and never steps back: no stutter from lost, late, duplicated or reordered snapshots.
#include "snapshot_buffer.hpp"

#include "library_build/library_source.hpp"
#include "transport/impairment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace foresight::client {
namespace {

using Clock = protocol::ImpairedQueue::Clock;

struct Playback {
  int frames_total = 0, frames_within_one = 0;
  double worst_error_frames = 0, worst_step_back_frames = 0;
};

// A segment with a transition to itself (a walk cycle), and that transition.
bool self_loop(const MotionLibrary& lib, int& segment, int& transition) {
  const auto& t = lib.graph.transitions;
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i].from == t[i].to && lib.graph.segments[static_cast<size_t>(t[i].from)].num_frames() >= 10) {
      segment = t[i].from;
      transition = static_cast<int>(i);
      return true;
    }
  return false;
}

Playback play(const MotionLibrary& lib, const protocol::ImpairmentConfig& link, double seconds) {
  int segment = -1, transition = -1;
  EXPECT_TRUE(self_loop(lib, segment, transition));
  const int n = lib.graph.segments[static_cast<size_t>(segment)].num_frames();
  const double fps = 30.0;
  protocol::ImpairedQueue wire(link, 1);
  SnapshotBuffer buffer;
  std::vector<ShownAvatar> shown;
  Playback p;
  const Clock::time_point t0{};
  double last_shown = -1;  // unwrapped frames shown
  int next_snapshot = 0;
  for (int render = 0; render < static_cast<int>(seconds * 60); ++render) {
    const double local_s = render / 60.0;
    const Clock::time_point now = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(local_s));
    // The server: a snapshot every 50 ms of (segment, frame) of the loop at server time = local time.
    while (next_snapshot * 0.05 <= local_s) {
      const int frame = static_cast<int>(std::lround(next_snapshot * 0.05 * fps)) % n;
      uint8_t bytes[8];
      std::memcpy(bytes, &next_snapshot, sizeof next_snapshot);
      std::memcpy(bytes + 4, &frame, sizeof frame);
      wire.push(bytes, now);
      ++next_snapshot;
    }
    wire.release(now, [&](std::span<const uint8_t> d) {
      int index = 0, frame = 0;
      std::memcpy(&index, d.data(), sizeof index);
      std::memcpy(&frame, d.data() + 4, sizeof frame);
      AvatarEntry e;
      e.id = 1;
      e.state.segment = segment;
      e.state.frame = frame;
      e.state.incoming_transition = transition;
      buffer.push(index * 0.05, local_s, {&e, 1});
    });
    if (buffer.size() < 2) continue;
    const double t = buffer.render_time(local_s);
    buffer.sample(lib, t, shown);
    if (shown.size() != 1 || t < 0.5) continue;  // the first half second settles the clock
    const double frame = shown[0].state.frame + shown[0].frame_alpha;
    // The server's frame at the time shown, and ours unwrapped next to the previous one.
    const double truth = std::fmod(t * fps, n);
    double error = std::abs(frame - truth);
    error = std::min(error, n - error);
    double unwrapped = frame;
    if (last_shown >= 0) {
      while (unwrapped < last_shown - n / 2.0) unwrapped += n;
      p.worst_step_back_frames = std::max(p.worst_step_back_frames, last_shown - unwrapped);
    }
    last_shown = unwrapped;
    ++p.frames_total;
    p.frames_within_one += error <= 1.0;
    p.worst_error_frames = std::max(p.worst_error_frames, error);
  }
  return p;
}

TEST(ImpairedPlayback, InterpolationStaysOnTheServersTimelineAndNeverStepsBack) {
  const MotionLibrary lib = motion_library_default();
  const Playback clean = play(lib, protocol::ImpairmentConfig{}, 60.0);
  protocol::ImpairmentConfig hostile;
  hostile.loss = 0.05, hostile.latency_ms = 50, hostile.jitter_ms = 20, hostile.duplicate = 0.01, hostile.reorder = 0.01;
  hostile.seed = 4;
  const Playback rough = play(lib, hostile, 60.0);
  ASSERT_GT(clean.frames_total, 3000);
  ASSERT_GT(rough.frames_total, 3000);
  EXPECT_EQ(clean.frames_within_one, clean.frames_total);
  EXPECT_GE(rough.frames_within_one, rough.frames_total * 98 / 100)
      << rough.frames_within_one << " of " << rough.frames_total << " within a frame";
  EXPECT_LT(rough.worst_error_frames, 3.0);
  EXPECT_LT(rough.worst_step_back_frames, 0.25) << "the shown motion went backwards";
  std::printf("[          ] hostile link: %d of %d render frames within one clip frame of the server, worst %.2f frames, "
              "worst step back %.3f frames\n",
              rough.frames_within_one, rough.frames_total, rough.worst_error_frames, rough.worst_step_back_frames);
}

}  // namespace
}  // namespace foresight::client
