// play: a headless avatar wandering through a scene with look-ahead. A seeded "player" holds a
// random direction for a few seconds, then picks another; the feasible motion tree keeps the
// avatar out of the walls. Every shown pose is re-checked from FK (pose_check.hpp) and the run
// fails if any collides.
#include "commands.hpp"
#include "library/body_fit.hpp"
#include "library/pose_check.hpp"
#include "lookahead/lookahead_avatar.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <cstdio>
#include <random>

namespace foresight::tools {

int command_play(const MotionSource& source, const PlayOptions& o) {
  MotionLibrary lib;
  if (!load_library_or_report(source, lib)) return 1;
  Scene scene;
  CollisionWorld world;
  std::string error;
  if (!scene_world_load(o.scene, scene, world, error)) {
    std::fprintf(stderr, "foresight-motion: %s\n", error.c_str());
    return 1;
  }
  // Start idle if the library has an idle segment free at the spawn (a captured library may
  // not: then the first segment that is free there).
  const SpawnPoint& spawn = scene.spawns.front();
  const Placement start{spawn.pos_m, spawn.heading_rad};
  int start_segment = find_fallback_segment(lib);
  if (start_segment < 0 || !segment_feasible(world, lib.segment_shapes[start_segment], start)) {
    start_segment = -1;
    for (int s = 0; s < lib.graph.num_segments() && start_segment < 0; ++s)
      if (segment_feasible(world, lib.segment_shapes[s], start)) start_segment = s;
  }
  if (start_segment < 0) {
    const std::string why = body_fit_problem(lib, scene, world, std::max(find_fallback_segment(lib), 0), start);
    std::fprintf(stderr, "foresight-motion: no segment is free at the spawn of %s: %s\n", scene.name.c_str(),
                 why.c_str());
    return 1;
  }
  LookaheadAvatar avatar(lib, world, MotionTreeConfig{}, start_segment, start);
  std::printf("library %s (%d segments, %zu transitions), scene %s, spawn (%.2f, %.2f)\n",
              lib.name.c_str(), lib.graph.num_segments(), lib.graph.transitions.size(),
              scene.name.c_str(), spawn.pos_m.x, spawn.pos_m.y);

  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<float> angle(-kPi, kPi), hold_s(1.5f, 4.0f);
  const float fps = lib.clips[lib.graph.segments[start_segment].clip].fps;
  const long long total_frames = static_cast<long long>(o.seconds * fps);
  ControlInput input;  // camera yaw 0: the direction is a world direction
  long long next_change = 0, colliding_frames = 0, segments = 1;
  PoseCheckScratch check;
  vec2 previous = avatar.root().pos_m;
  float distance_m = 0;
  bool previous_was_fallback = false;
  for (long long frame = 0; frame < total_frames; ++frame) {
    if (frame == next_change) {
      const float a = angle(rng);
      input.camera_dir = vec2(std::sin(a), std::cos(a));
      next_change += static_cast<long long>(hold_s(rng) * fps);
    }
    avatar.set_input(input);
    avatar.grow(GrowBudget::expansions(o.expansions_per_frame));
    const AvatarStepResult step = avatar.step();
    if (shown_pose_collides(lib, world, avatar.playback(), check)) ++colliding_frames;
    const Placement at = avatar.root();
    distance_m += glm::length(at.pos_m - previous);
    previous = at.pos_m;
    if (o.verbose)
      std::printf("    frame %lld: (%.3f, %.3f) %+.1f deg\n", frame, at.pos_m.x, at.pos_m.y,
                  degrees(at.heading_rad));
    // A held pose (nothing feasible, no idle) re-decides every frame: report it once.
    const bool repeated_hold = step.fallback && previous_was_fallback;
    previous_was_fallback = step.fallback;
    if (!step.segment_changed || repeated_hold) continue;
    ++segments;
    std::printf("  t=%6.2fs  %-24s at (%6.2f, %6.2f) heading %+7.1f deg  tree %5d nodes%s\n",
                frame / fps, lib.graph.segments[avatar.playback().segment].name.c_str(), at.pos_m.x,
                at.pos_m.y, degrees(at.heading_rad), avatar.tree().num_nodes(),
                step.fallback ? "  (nothing feasible: stopped)" : "");
  }
  std::printf("played %lld segments, walked %.1f m, %d stops with nothing feasible, %lld colliding "
              "frames\n",
              segments, distance_m, avatar.fallbacks(), colliding_frames);
  return colliding_frames == 0 ? 0 : 1;
}

}  // namespace foresight::tools
