// play: a headless avatar walking the motion graph through a scene. At each segment end it picks,
// at random (seeded), one successor whose every frame is collision-free and from which a
// collision-free continuation of kLookAheadSteps more segments exists (a depth-first probe; the
// feasible motion tree of the look-ahead issue replaces this). Every played frame is then re-checked from its FK pose, independently of
// the precomputed volumes, and the run fails if any collides.
#include "commands.hpp"
#include "library/playback.hpp"
#include "library/pose_check.hpp"
#include "world/collision_check.hpp"
#include "world/collision_world.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <cstdio>
#include <random>

namespace foresight::tools {
namespace {

constexpr int kLookAheadSteps = 3;

float choice_weight(uint32_t tags) {
  if (tags & kTagFight) return 0.0f;  // fighting moves are for the NPC fighter, not walking
  if (tags & kTagIdle) return 0.2f;
  if (tags & kTagRun) return 1.0f;    // runs need room a maze rarely has
  if (tags & kTagTurn) return 2.0f;
  return 3.0f;
}

// True when `segment` placed at `start` is free and continues freely for `depth` more segments.
bool feasible_future(const MotionLibrary& lib, const CollisionWorld& world, int segment,
                     const Placement& start, int depth) {
  if (!segment_feasible(world, lib.segment_shapes[segment], start)) return false;
  if (depth == 0) return true;
  const Placement end = start.compose(lib.segment_motion[segment].end);
  for (const Transition& t : lib.graph.successors(segment))
    if (choice_weight(lib.graph.segments[t.to].tags) > 0 &&
        feasible_future(lib, world, t.to, end, depth - 1))
      return true;
  return false;
}

}  // namespace

int command_play(const MotionSource& source, const PlayOptions& o) {
  MotionLibrary lib;
  if (!load_library_or_report(source, lib)) return 1;
  Scene scene;
  CollisionWorld world;
  std::string error;
  if (!scene_load(scene_path(o.scene), scene, error) || !collision_world_build(scene, world, error)) {
    std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
    return 1;
  }

  // Start in the first idle segment (or segment 0) at the scene's first spawn.
  int start_segment = 0;
  for (int s = 0; s < lib.graph.num_segments(); ++s)
    if (lib.graph.segments[s].tags & kTagIdle) {
      start_segment = s;
      break;
    }
  const SpawnPoint& spawn = scene.spawns.front();
  PlaybackState state{start_segment, 0, Placement{spawn.pos_m, spawn.heading_rad}, -1};
  std::printf("library %s (%d segments, %zu transitions), scene %s, spawn (%.2f, %.2f)\n",
              lib.name.c_str(), lib.graph.num_segments(), lib.graph.transitions.size(),
              scene.name.c_str(), spawn.pos_m.x, spawn.pos_m.y);
  if (!segment_feasible(world, lib.segment_shapes[start_segment], state.segment_start)) {
    std::fprintf(stderr, "foresight-motion: the spawn is not free for '%s'\n",
                 lib.graph.segments[start_segment].name.c_str());
    return 1;
  }

  std::mt19937_64 rng(o.seed);
  const float fps = lib.clips[lib.graph.segments[start_segment].clip].fps;
  const long long total_frames = static_cast<long long>(o.seconds * fps);
  PoseCheckScratch check;
  std::vector<int> feasible;
  std::vector<float> weights;
  long long colliding_frames = 0, segments_played = 1;
  float distance_m = 0;
  Placement previous = playback_root(lib, state);
  std::printf("  t=  0.00s  %-26s at (%6.2f, %6.2f) heading %+7.1f deg\n",
              lib.graph.segments[state.segment].name.c_str(), previous.pos_m.x, previous.pos_m.y,
              degrees(previous.heading_rad));

  for (long long frame = 0; frame < total_frames; ++frame) {
    if (playback_at_end(lib, state)) {
      const Placement next_start = playback_next_start(lib, state);
      feasible.clear();
      // The deepest probe that leaves a choice: a corner may allow one more segment, not three.
      const auto succ = lib.graph.successors(state.segment);
      for (int depth = kLookAheadSteps; depth >= 0 && feasible.empty(); --depth) {
        weights.clear();
        for (size_t i = 0; i < succ.size(); ++i) {
          const float w = choice_weight(lib.graph.segments[succ[i].to].tags);
          if (w > 0 && feasible_future(lib, world, succ[i].to, next_start, depth)) {
            feasible.push_back(lib.graph.first_transition[state.segment] + static_cast<int>(i));
            weights.push_back(w);
          }
        }
      }
      if (feasible.empty()) {
        std::printf("  t=%6.2fs  no feasible successor of %s: the avatar stops here\n", frame / fps,
                    lib.graph.segments[state.segment].name.c_str());
        break;
      }
      std::discrete_distribution<size_t> pick(weights.begin(), weights.end());
      playback_take(lib, state, feasible[pick(rng)]);
      ++segments_played;
      const Placement at = playback_root(lib, state);
      std::printf("  t=%6.2fs  %-26s at (%6.2f, %6.2f) heading %+7.1f deg  (%zu of %zu feasible)\n",
                  frame / fps, lib.graph.segments[state.segment].name.c_str(), at.pos_m.x,
                  at.pos_m.y, degrees(at.heading_rad), feasible.size(), succ.size());
    }
    // Independent re-check of the pose actually shown.
    if (shown_pose_collides(lib, world, state, check)) ++colliding_frames;
    const Placement now = playback_root(lib, state);
    distance_m += glm::length(now.pos_m - previous.pos_m);
    previous = now;
    if (o.verbose)
      std::printf("    frame %lld: (%.3f, %.3f) %+.1f deg\n", frame, now.pos_m.x, now.pos_m.y,
                  degrees(now.heading_rad));
    ++state.frame;
  }
  std::printf("played %lld segments, walked %.1f m, %lld colliding frames\n", segments_played,
              distance_m, colliding_frames);
  return colliding_frames == 0 ? 0 : 1;
}

}  // namespace foresight::tools
