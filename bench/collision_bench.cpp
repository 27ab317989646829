#include "collision_bench.hpp"

#include <chrono>
#include <random>

namespace foresight::bench {
namespace {

struct BenchTask {
  std::uint32_t shape = 0;
  Placement start;
};

// A power of two so the loop wraps with a mask; big enough that branch predictors cannot learn
// the outcomes, small enough (128 KiB) to stay in L2 beside the world.
constexpr std::size_t kPoolSize = 8192;
// Clock reads are ~20-50 ns; reading once per batch keeps them out of the measurement.
constexpr int kClipsPerClockRead = 1024;

std::vector<BenchTask> make_tasks(const CollisionWorld& world, std::size_t num_shapes,
                                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> ux(world.bounds.min_m.x, world.bounds.max_m.x);
  std::uniform_real_distribution<float> uz(world.bounds.min_m.y, world.bounds.max_m.y);
  std::uniform_real_distribution<float> uh(-kPi, kPi);
  std::uniform_int_distribution<std::uint32_t> us(0, static_cast<std::uint32_t>(num_shapes - 1));
  std::vector<BenchTask> tasks(kPoolSize);
  for (BenchTask& t : tasks) {
    t.shape = us(rng);
    // On free ground: where a thin standing body fits (a planner never starts a clip inside a
    // wall). Give up after a while in a scene with almost no free ground.
    for (int attempt = 0; attempt < 256; ++attempt) {
      t.start.pos_m = {ux(rng), uz(rng)};
      float g = 0.0f;
      if (ground_height_at(world, t.start.pos_m, g) &&
          !frame_collides(world, {t.start.pos_m, 0.3f, g + 0.05f, g + 1.0f}, g))
        break;
    }
    t.start.heading_rad = uh(rng);
  }
  return tasks;
}

}  // namespace

CollisionBenchResult run_collision_bench(const CollisionWorld& world,
                                         std::span<const SegmentCollisionShape> shapes,
                                         double seconds, std::uint64_t seed) {
  CollisionBenchResult r;
  r.shapes = shapes.size();
  if (shapes.empty() || world.empty()) return r;
  const std::vector<BenchTask> tasks = make_tasks(world, shapes.size(), seed);
  r.placements = tasks.size();

  using Clock = std::chrono::steady_clock;
  CheckStats stats;
  std::size_t next = 0;
  const Clock::time_point t0 = Clock::now();
  Clock::time_point now = t0;
  do {
    for (int i = 0; i < kClipsPerClockRead; ++i) {
      const BenchTask& t = tasks[next];
      next = (next + 1) & (kPoolSize - 1);
      segment_feasible(world, shapes[t.shape], t.start, &stats);
    }
    now = Clock::now();
  } while (std::chrono::duration<double>(now - t0).count() < seconds);

  r.seconds = std::chrono::duration<double>(now - t0).count();
  r.clip_checks = stats.clip_checks;
  r.frame_checks = stats.frame_checks;
  r.feasible_clips = stats.feasible_clips;
  r.early_out_clips = stats.sweep_early_outs;
  r.frame_checks_per_sec = static_cast<double>(r.frame_checks) / r.seconds;
  r.clip_checks_per_sec = static_cast<double>(r.clip_checks) / r.seconds;
  const double clips = static_cast<double>(r.clip_checks);
  r.feasible_share = static_cast<double>(r.feasible_clips) / clips;
  r.early_out_share = static_cast<double>(r.early_out_clips) / clips;
  r.frames_per_clip = static_cast<double>(r.frame_checks) / clips;
  return r;
}

Json to_json(const CollisionBenchResult& r) {
  return {{"seconds", rounded(r.seconds, 3)},
          {"clip_checks", r.clip_checks},
          {"frame_checks", r.frame_checks},
          {"feasible_clips", r.feasible_clips},
          {"early_out_clips", r.early_out_clips},
          {"frame_checks_per_sec", rounded(r.frame_checks_per_sec, 0)},
          {"clip_checks_per_sec", rounded(r.clip_checks_per_sec, 0)},
          {"feasible_share", rounded(r.feasible_share, 4)},
          {"early_out_share", rounded(r.early_out_share, 4)},
          {"frames_per_clip", rounded(r.frames_per_clip, 3)},
          {"placements", r.placements},
          {"shapes", r.shapes}};
}

}  // namespace foresight::bench
