#include "scripted/recording_generator.hpp"

#include "library/body_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace foresight {
namespace {

// Frame time rounded down to the millisecond, never after t: replaying at t then holds exactly
// this frame's input (the previous frame is at least 2 ms earlier).
double stamp_ms(double t_s) {
  double s = std::floor(t_s * 1000.0) / 1000.0;
  if (s > t_s) s -= 0.001;
  return std::max(s, 0.0);
}

bool same_input(const ControlInput& a, const ControlInput& b) {
  return a.camera_dir == b.camera_dir && a.camera_yaw_rad == b.camera_yaw_rad && a.crouch == b.crouch;
}

template <typename Points>
const auto* find_named(const Points& points, const std::string& name) {
  if (points.empty()) return static_cast<decltype(&points.front())>(nullptr);
  if (name.empty()) return &points.front();
  for (const auto& p : points)
    if (p.name == name) return &p;
  return static_cast<decltype(&points.front())>(nullptr);
}

template <typename Points>
std::string names_of(const Points& points) {
  std::string s;
  for (const auto& p : points) s += (s.empty() ? "\"" : ", \"") + p.name + "\"";
  return s.empty() ? "none" : s;
}

}  // namespace

bool recording_generate(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
                        const RecordingGeneratorConfig& config, GeneratedRecording& out,
                        std::string& error) {
  const SpawnPoint* spawn = find_named(scene.spawns, config.spawn);
  if (spawn == nullptr) {
    error = scene.name + ": no spawn \"" + config.spawn + "\" (spawns: " + names_of(scene.spawns) + ")";
    return false;
  }
  const GoalPoint* goal = find_named(scene.goals, config.goal);
  if (goal == nullptr) {
    error = scene.name + ": no goal \"" + config.goal + "\" (goals: " + names_of(scene.goals) + ")";
    return false;
  }
  ReplayConfig rc = config.replay;
  rc.wall_clock_spare_s = 0;  // deterministic budgets only
  rc.stop_at_goal = true;
  const double dt = rc.frame_interval_s;
  if (!(dt >= 0.002 && dt <= 1.0)) {
    error = "recording generator: frame_interval_s must be in [0.002, 1] s";
    return false;
  }

  const Placement start{spawn->pos_m, spawn->heading_rad};
  if (const std::string why = body_fit_problem(library, scene, world, find_fallback_segment(library), start);
      !why.empty()) {
    error = scene.name + ": spawn \"" + spawn->name + "\": " + why;
    return false;
  }
  ScriptedPlayer player;
  if (!player.plan(library, scene, world, start, goal->pos_m, config.player_config(), error)) {
    error = scene.name + ": spawn \"" + spawn->name + "\" -> goal \"" + goal->name + "\": " + error;
    return false;
  }
  GeneratedRecording g;
  g.route = player.route();
  g.route_length_m = player.route_length_m();
  g.route_body_height_m = player.route_body_height_m();

  Recording& rec = g.recording;
  rec.scene = config.scene.empty() ? scene.name : config.scene;
  rec.name = config.name;
  rec.library_hash = library.content_hash;
  rec.start_pos_m = spawn->pos_m;
  rec.start_heading_rad = spawn->heading_rad;
  rec.goal_pos_m = goal->pos_m;
  rec.goal_radius_m = goal->radius_m;

  ReplayRun run(library, world, start, goal->pos_m, goal->radius_m, rc);
  if (!run.ok()) {
    error = run.error();
    return false;
  }

  while (!run.done()) {
    const double t = run.time_s();
    const ControlInput input = player.frame(t, run.avatar().root().pos_m);
    const vec3 camera_pos = player.camera_pos_m();
    if (rec.samples.empty() || !same_input(rec.samples.back().input, input) ||
        rec.samples.back().camera_pos_m != camera_pos)
      rec.samples.push_back({stamp_ms(t), input, camera_pos});
    run.frame(input);
  }
  // Keys up after the last frame (the avatar has arrived, or time is up).
  if (rec.samples.back().input.camera_dir != vec2(0.0f)) {
    CommandSample stop = rec.samples.back();
    stop.t_s = stamp_ms(run.time_s());
    stop.input.camera_dir = vec2(0.0f);
    rec.samples.push_back(stop);
  }
  g.run = run.finish();
  g.reached_goal = g.run.reached_goal;
  out = std::move(g);
  return true;
}

}  // namespace foresight
