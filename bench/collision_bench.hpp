#pragma once
// The collision benchmark behind `foresight-bench collision --scene NAME [--json]`: segment checks
// of random placements against one compiled scene, on the calling thread, counted honestly.
//
// Counting: frame_checks are frames actually tested against the scene (the per-frame box and
// terrain test). Clips decided by the whole-sweep early-out count as clip checks with zero frame
// checks, and clips stopped at their first colliding frame count only the frames tested. So
// frame_checks_per_sec is the rate of real per-frame tests over the whole timed run (including the
// time spent in early-outs and per-clip setup), never frames skipped.
#include "bench_json.hpp"
#include "world/collision_check.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace foresight::bench {

struct CollisionBenchResult {
  double seconds = 0.0;  ///< Timed wall-clock duration actually run.
  std::uint64_t clip_checks = 0;
  std::uint64_t frame_checks = 0;
  std::uint64_t feasible_clips = 0;
  std::uint64_t early_out_clips = 0;  ///< Decided by the whole-sweep test (0 frames tested).
  double frame_checks_per_sec = 0.0;
  double clip_checks_per_sec = 0.0;
  double feasible_share = 0.0;       ///< feasible_clips / clip_checks.
  double early_out_share = 0.0;      ///< early_out_clips / clip_checks.
  double frames_per_clip = 0.0;      ///< Frames tested per clip check, on average.
  std::uint64_t placements = 0;      ///< Size of the pre-generated placement pool.
  std::uint64_t shapes = 0;
};

/// Checks random placements (random shape, random position in the scene bounds on free ground,
/// random heading; pre-generated before timing, so the timed loop does not allocate) for
/// `seconds` on the calling thread. Deterministic placements for a given seed.
CollisionBenchResult run_collision_bench(const CollisionWorld& world,
                                         std::span<const SegmentCollisionShape> shapes,
                                         double seconds, std::uint64_t seed);

/// {"seconds":...,"clip_checks":...,"frame_checks_per_sec":...,...}: the figures, rounded.
Json to_json(const CollisionBenchResult& result);

}  // namespace foresight::bench
