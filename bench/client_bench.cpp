// client: the per-frame CPU work of foresight-client's avatar drawing, without a window.
// N avatars play random segment sequences of the default library (each successor a real graph
// transition), one frame per 30 Hz server tick, as the server plays them, steering as the server
// does by default: a third of them turn at 540 deg/s each way, re-drawn every second; a snapshot
// of all of them is pushed into the client's SnapshotBuffer 20 times a second (arriving 40-50 ms
// later). Render frames at 60 fps then time (1) SnapshotBuffer::sample at the frame's render time
// and (2) the pose rebuild, the same calls as Session::draw_avatars (client_app.cpp): a
// PoseStage per avatar (on flat ground, with an empty scene's collision world, as on the arena)
// and Renderer::add_skeleton (a capsule per bone, a shadow per foot). The Renderer is used
// without a GL context: add_skeleton touches no GL; the GPU upload and draw are not timed.
// Snapshot pushes and the simulated server are outside the timed sections; nothing allocates in
// them once warm (warm-up frames run first).
#ifdef FORESIGHT_HAVE_CLIENT

#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "library_build/library_source.hpp"
#include "library/playback.hpp"
#include "library/pose_stage.hpp"
#include "world/collision_world.hpp"
#include "renderer.hpp"
#include "snapshot_buffer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace foresight::bench {

namespace {

constexpr double kTickHz = 30.0;      // server defaults (server_config.hpp)
constexpr int kSnapshotHz = 20;
constexpr double kFrameS = 1.0 / 60.0;  // render frame

}  // namespace

int bench_client(const ClientBenchOptions& o) {
  const MotionLibrary lib = motion_library_default();
  const auto n = static_cast<size_t>(o.avatars);
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<float> pos(-20.0f, 20.0f);
  std::uniform_real_distribution<float> angle(-kPi, kPi);
  std::uniform_int_distribution<int> segment(0, lib.graph.num_segments() - 1);

  // The simulated server: avatars spawned into random segments at random frames.
  std::vector<client::AvatarEntry> server(n);
  std::vector<float> turn_rad_per_tick(n, 0.0f);
  const float steer = radians(540.0f) / static_cast<float>(kTickHz);
  for (size_t i = 0; i < n; ++i) {
    auto& a = server[i];
    a.id = static_cast<uint32_t>(i + 1);
    a.state.segment = segment(rng);
    a.state.segment_start = {vec2(pos(rng), pos(rng)), angle(rng)};
    a.state.frame = std::uniform_int_distribution<int>(
        0, lib.graph.segments[static_cast<size_t>(a.state.segment)].num_frames() - 1)(rng);
  }
  int64_t ticks = 0;
  auto server_tick = [&] {
    ++ticks;
    for (size_t i = 0; i < n; ++i) {
      auto& a = server[i];
      if ((ticks + static_cast<int64_t>(i)) % static_cast<int64_t>(kTickHz) == 0)
        turn_rad_per_tick[i] = steer * static_cast<float>(std::uniform_int_distribution<int>(-1, 1)(rng));
      if (turn_rad_per_tick[i] != 0.0f) a.state.segment_start = playback_turned_start(lib, a.state, turn_rad_per_tick[i]);
      ++a.state.frame;
      if (!playback_at_end(lib, a.state)) continue;
      const int first = lib.graph.first_transition[static_cast<size_t>(a.state.segment)];
      const int count = lib.graph.first_transition[static_cast<size_t>(a.state.segment) + 1] - first;
      if (count == 0) {  // a dead end: stay on its last frame (the server idles instead)
        --a.state.frame;
        continue;
      }
      playback_take(lib, a.state, first + std::uniform_int_distribution<int>(0, count - 1)(rng));
    }
  };

  client::SnapshotBuffer buffer;
  std::vector<client::ShownAvatar> shown;
  shown.reserve(n);
  client::Renderer renderer;  // no init(): no GL objects, nothing to delete
  const vec3 colour(0.3f, 0.5f, 0.9f);
  Scene empty;
  empty.bounds = {vec2(-30.0f), vec2(30.0f)};
  CollisionWorld world;
  std::string error;
  if (!collision_world_build(empty, world, error)) return std::fprintf(stderr, "%s\n", error.c_str()), 1;
  std::vector<PoseStage> stages;  // per avatar id - 1, as the client keeps one per id
  stages.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    stages.emplace_back(lib);
    stages.back().set_ground(&empty.terrain);
    stages.back().set_obstacles(&world);
  }

  // Snapshots in flight: (arrival local time, server time, copy of the avatars); at most a few.
  struct InFlight {
    double arrival_s = 0, server_s = 0;
    std::vector<client::AvatarEntry> avatars;
  };
  std::vector<InFlight> in_flight(8);
  for (auto& f : in_flight) f.avatars.reserve(n);
  size_t in_flight_head = 0, in_flight_count = 0;
  std::uniform_real_distribution<double> latency(0.040, 0.050);

  int64_t tick = 0;
  const double local_offset_s = 1000.0;  // the client's clock differs from the server's
  std::vector<double> sample_us, pose_us, frame_ms;
  const size_t max_frames = 1000000;
  sample_us.reserve(max_frames);
  pose_us.reserve(max_frames);
  frame_ms.reserve(max_frames);
  size_t instances = 0, extrapolated = 0, fractional = 0, shown_total = 0;

  using Clock = std::chrono::steady_clock;
  const int warm_frames = 120;
  Clock::time_point t0{}, end{};
  for (int64_t frame = 0;; ++frame) {
    if (frame == warm_frames) {
      t0 = Clock::now();
      end = t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.seconds));
    }
    const bool measured = frame >= warm_frames;
    if (measured && (Clock::now() >= end || sample_us.size() >= max_frames)) break;
    const double server_now = static_cast<double>(frame) * kFrameS;
    // Server ticks up to now; a snapshot on the ticks where the 20 Hz schedule falls.
    while (static_cast<double>(tick + 1) / kTickHz <= server_now) {
      ++tick;
      server_tick();
      if ((tick * kSnapshotHz) / static_cast<int64_t>(kTickHz) !=
          ((tick - 1) * kSnapshotHz) / static_cast<int64_t>(kTickHz)) {
        if (in_flight_count == in_flight.size()) return std::fprintf(stderr, "in flight full\n"), 1;
        InFlight& f = in_flight[(in_flight_head + in_flight_count++) % in_flight.size()];
        f.server_s = static_cast<double>(tick) / kTickHz;
        f.arrival_s = f.server_s + latency(rng);
        f.avatars.assign(server.begin(), server.end());
      }
    }
    const double local_now = server_now + local_offset_s;
    while (in_flight_count > 0 && in_flight[in_flight_head].arrival_s <= server_now) {
      const InFlight& f = in_flight[in_flight_head];
      buffer.push(f.server_s, f.arrival_s + local_offset_s, f.avatars);
      in_flight_head = (in_flight_head + 1) % in_flight.size();
      --in_flight_count;
    }

    // Timed: what Session::draw_avatars does on the CPU each frame.
    const auto a = Clock::now();
    buffer.sample(lib, buffer.render_time(local_now), shown);
    const auto b = Clock::now();
    renderer.begin_frame();
    for (const client::ShownAvatar& s : shown)
      renderer.add_skeleton(lib.skeleton.parents,
                            stages[s.id - 1].update(s.state, frame == 0 ? 0.0f : static_cast<float>(kFrameS), s.frame_alpha),
                            colour);
    const auto c = Clock::now();
    if (!measured) continue;
    sample_us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    pose_us.push_back(std::chrono::duration<double, std::micro>(c - b).count());
    frame_ms.push_back(std::chrono::duration<double, std::milli>(c - a).count());
    instances += renderer.avatar_instances();
    shown_total += shown.size();
    for (const auto& s : shown) {
      extrapolated += s.extrapolated ? 1 : 0;
      fractional += s.frame_alpha > 0.0f ? 1 : 0;
    }
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  const size_t frames = sample_us.size();
  if (frames == 0) return std::fprintf(stderr, "no frame measured\n"), 1;
  std::vector<double> frame_sorted = frame_ms;
  std::sort(frame_sorted.begin(), frame_sorted.end());
  const double frame_p99 = frame_sorted[std::min(frames - 1, frames * 99 / 100)];
  const double sample_med = median(sample_us), pose_med = median(pose_us), frame_med = median(frame_ms);
  const double per = 1.0 / static_cast<double>(n);
  const double shown_mean = static_cast<double>(shown_total) / static_cast<double>(frames);
  const double instances_mean = static_cast<double>(instances) / static_cast<double>(frames);
  const double fractional_share = static_cast<double>(fractional) / static_cast<double>(std::max<size_t>(1, shown_total));
  const double extrapolated_share = static_cast<double>(extrapolated) / static_cast<double>(std::max<size_t>(1, shown_total));

  print_machine_line();
  std::printf("%d avatars (%d joints), default library, %zu frames at 60 fps render time in %.1f s "
              "(20 Hz snapshots, 30 Hz ticks, 100 ms delay)\n",
              o.avatars, lib.num_joints(), frames, seconds);
  std::printf("  per frame (median): sample %.3f ms (%.3f us/avatar), pose rebuild %.3f ms "
              "(%.3f us/avatar), both %.3f ms (p99 %.3f ms)\n",
              sample_med / 1e3, sample_med * per, pose_med / 1e3, pose_med * per, frame_med, frame_p99);
  std::printf("  shown %.0f avatars, %.0f bone instances per frame; %.0f%% on fractional frames "
              "(two poses + two FKs), %.1f%% extrapolated\n",
              shown_mean, instances_mean, 100.0 * fractional_share, 100.0 * extrapolated_share);
  std::printf("  CPU share of a 16.7 ms frame: %.1f%%\n", 100.0 * frame_med / (1000.0 * kFrameS));
  if (o.json)
    print_json_line({{"bench", "client"},
                     {"avatars", o.avatars},
                     {"joints", lib.num_joints()},
                     {"frames", frames},
                     {"seconds", rounded(seconds, 3)},
                     {"sample_us_per_avatar", rounded(sample_med * per, 4)},
                     {"pose_rebuild_us_per_avatar", rounded(pose_med * per, 4)},
                     {"sample_ms", rounded(sample_med / 1e3, 4)},
                     {"pose_rebuild_ms", rounded(pose_med / 1e3, 4)},
                     {"frame_ms_for_all_avatars", rounded(frame_med, 4)},
                     {"frame_ms_p99", rounded(frame_p99, 4)},
                     {"bone_instances", rounded(instances_mean, 0)},
                     {"fractional_share", rounded(fractional_share, 3)},
                     {"extrapolated_share", rounded(extrapolated_share, 4)}});
  return 0;
}

}  // namespace foresight::bench

#endif  // FORESIGHT_HAVE_CLIENT
