#include "lab/motion_quality.hpp"

#include "bench_json.hpp"
#include "anim/canonical_skeleton.hpp"
#include "lab/lab_experiments.hpp"
#include "library/foot_contact.hpp"
#include "library/pose_check.hpp"
#include "scripted/replay.hpp"
#include "scripted/response_meter.hpp"
#include "scripted/scripted_player.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace foresight::lab {
namespace {

// A pop is added (not the clips' own) when the shown acceleration exceeds the played clip
// frames' own by more than this factor: steering and the stage's springs change a frame's
// acceleration by a few per cent without adding anything a player would see.
constexpr float kAddedPopMargin = 1.1f;

constexpr float kBoneSlack_m = 0.01f;

// The largest joint acceleration of one frame of shown positions.
float largest_acceleration(const std::vector<vec3>& before, const std::vector<vec3>& now,
                           const std::vector<vec3>& after) {
  float largest = 0.0f;
  for (size_t j = 0; j < now.size(); ++j)
    largest = std::max(largest, glm::length(after[j] - 2.0f * now[j] + before[j]));
  return largest;
}

// A leg whose bones changed length or whose knee bends the other way from the animation's.
bool leg_violates(std::span<const vec3> shown, std::span<const vec3> animated, size_t hip) {
  const size_t knee = hip + 1, ankle = hip + 2;
  const auto bone = [](std::span<const vec3> p, size_t a, size_t b) { return glm::length(p[b] - p[a]); };
  if (std::abs(bone(shown, hip, knee) - bone(animated, hip, knee)) > kBoneSlack_m ||
      std::abs(bone(shown, knee, ankle) - bone(animated, knee, ankle)) > kBoneSlack_m)
    return true;
  const auto bend = [&](std::span<const vec3> p) { return offset_from_line(p[knee], p[hip], p[ankle]); };
  const vec3 a = bend(animated), s = bend(shown);
  // Only a clearly bent animated knee has a side to keep (a straight one may flip by noise).
  return glm::length(a) > 0.02f && glm::dot(a, s) < 0.0f;
}

struct Accumulator {
  std::vector<double> skate_cm_per_s, ground_cm, response_ms, shown_response_ms;
  MotionQualityResult r;
};

void measure_run(const MotionLibrary& lib, const CollisionWorld& world, const Scene& scene, const GoalPoint& goal,
                 const MotionQualityController& c, const MotionQualityOptions& o, uint64_t seed, Accumulator& acc) {
  const SpawnPoint& spawn = scene.spawns.front();
  const Placement start{spawn.pos_m, spawn.heading_rad};
  ScriptedPlayerConfig pc;
  pc.seed = seed;
  ScriptedPlayer player;
  std::string error;
  if (!player.plan(lib, scene, world, start, goal.pos_m, pc, error)) return;
  ReplayConfig rc;
  rc.tree = c.tree;
  rc.expansions_per_frame = o.expansions_per_frame;
  rc.max_seconds = o.max_seconds;
  ReplayRun run(lib, world, start, goal.pos_m, goal.radius_m, rc);
  if (!run.ok()) return;
  PoseStageConfig sc;
  sc.foot_locking = sc.inertialization = sc.turn_easing = sc.orientation_warping = sc.ground_adaptation =
      sc.acceleration_guard = c.pose_stage;
  PoseStage stage(lib, sc);
  stage.set_ground(&world.terrain);
  stage.set_obstacles(&world);
  const float dt = static_cast<float>(rc.frame_interval_s);
  const size_t n = static_cast<size_t>(lib.num_joints());
  std::vector<vec3> before(n), now(n), after(n), unguarded_before(n), unguarded_now(n), unguarded_after(n);
  uint8_t contact_before = 0;
  int64_t frame = 0;
  float own[3] = {0, 0, 0};  // the played clip frames' own accelerations: before, now, after
  ResponseMeter shown_response(rc.frame_interval_s);  // of the shown pelvis
  while (!run.done()) {
    const double t_s = run.time_s();
    run.frame(player.frame(t_s, run.avatar().root().pos_m));
    const PlaybackState& played = run.avatar().playback();
    const std::span<const vec3> shown = stage.update(played, frame == 0 ? 0.0f : dt);
    if (shown_response.frame(t_s, control_world_direction(run.avatar().input()), ground(shown[0]), played.segment))
      acc.shown_response_ms.push_back(shown_response.last().ms);
    const uint8_t contact = stage.contact();
    before.swap(now);
    now.swap(after);
    std::copy(shown.begin(), shown.end(), after.begin());
    unguarded_before.swap(unguarded_now);
    unguarded_now.swap(unguarded_after);
    std::copy(stage.unguarded().begin(), stage.unguarded().end(), unguarded_after.begin());
    for (size_t j = 0; j < n; ++j)
      acc.r.guard_offset_cm_max = std::max(acc.r.guard_offset_cm_max, 100.0 * glm::length(after[j] - unguarded_after[j]));
    if (frame >= 2 && largest_acceleration(unguarded_before, unguarded_now, unguarded_after) > lib.pop_threshold_m)
      ++acc.r.unguarded_pops;
    const Segment& seg = lib.graph.segments[played.segment];
    own[0] = own[1], own[1] = own[2], own[2] = lib.frame_acceleration_at(seg.clip, seg.first_frame + played.frame);
    if (const float a = frame >= 2 ? largest_acceleration(before, now, after) : 0.0f; a > lib.pop_threshold_m) {
      ++acc.r.pops;
      if (a > kAddedPopMargin * std::max({own[0], own[1], own[2]})) ++acc.r.added_pops;
    }
    if (shown_joints_collide(lib, world, shown)) ++acc.r.shown_collisions;
    if (frame >= 1 && n > kCanonRightToeEnd) {
      for (int foot = 0; foot < 2; ++foot) {
        const bool ball = contact & foot_ball_bit(foot), heel = contact & foot_heel_bit(foot);
        if (!ball && !heel) continue;
        const int joint = ball ? foot_ball_joint(foot) : foot_heel_joint(foot);
        const uint8_t bit = ball ? foot_ball_bit(foot) : foot_heel_bit(foot);
        const vec3 p = after[static_cast<size_t>(joint)];
        float ground = 0.0f;
        if (ground_height_at(world, vec2(p.x, p.z), ground))
          acc.ground_cm.push_back(100.0 * std::abs(p.y - (ground + stage.animated()[static_cast<size_t>(joint)].y)));
        if (!(contact_before & bit)) continue;  // planted this frame: no speed yet
        const vec3 q = now[static_cast<size_t>(joint)];
        acc.skate_cm_per_s.push_back(100.0 * std::hypot(p.x - q.x, p.z - q.z) / dt);
      }
      if (leg_violates(shown, stage.animated(), kCanonLeftUpLeg) || leg_violates(shown, stage.animated(), kCanonRightUpLeg))
        ++acc.r.limit_violations;
    }
    contact_before = contact;
    ++frame;
  }
  const ReplayResult res = run.finish();
  acc.r.runs += 1;
  acc.r.goals_reached += res.reached_goal ? 1 : 0;
  acc.r.minutes += res.seconds / 60.0;
  acc.r.played_collisions += res.colliding_frames;
  acc.r.discontinuities += stage.discontinuities();
  acc.r.guarded_frames += stage.guarded_frames();
  for (const double ms : response_ms(res)) acc.response_ms.push_back(ms);
}

}  // namespace

bool shift_steps(Scene& scene, CollisionWorld& world, float dz_m, std::string& error) {
  for (StepBlock& step : scene.terrain.steps) step.min_m.z += dz_m, step.max_m.z += dz_m;
  return collision_world_build(scene, world, error);
}

std::vector<MotionQualityController> motion_quality_controllers(float steer_rad_per_s) {
  MotionTreeConfig paper;
  MotionTreeConfig steered;
  steered.steer_rad_per_s = steer_rad_per_s;
  return {{"look-ahead 1 command (the paper's)", paper, false},
          {"look-ahead 1 + steering, no pose stage", steered, false},
          {"look-ahead 1 + steering + pose stage", steered, true}};
}

std::vector<MotionQualityResult> measure_motion_quality(const MotionLibrary& library, const Scene& scene,
                                                        const CollisionWorld& world,
                                                        const std::vector<MotionQualityController>& controllers,
                                                        const MotionQualityOptions& options, std::string& error) {
  const auto named = std::find_if(scene.goals.begin(), scene.goals.end(),
                                  [&](const GoalPoint& g) { return options.goal.empty() || g.name == options.goal; });
  if (scene.spawns.empty() || named == scene.goals.end()) {
    error = "motion quality: scene '" + scene.name + "' needs a spawn and " +
            (options.goal.empty() ? std::string("a goal") : "a goal named '" + options.goal + "'");
    return {};
  }
  const GoalPoint& goal = *named;
  ScriptedPlayer probe;
  if (!probe.plan(library, scene, world, {scene.spawns.front().pos_m, scene.spawns.front().heading_rad},
                  goal.pos_m, ScriptedPlayerConfig{}, error))
    return {};
  std::vector<MotionQualityResult> results;
  for (const MotionQualityController& c : controllers) {
    Accumulator acc;
    acc.r.controller = c.name;
    acc.r.pose_stage = c.pose_stage;
    acc.r.pop_threshold_m = library.pop_threshold_m;
    for (int seed = 1; seed <= options.seeds; ++seed)
      measure_run(library, world, scene, goal, c, options, static_cast<uint64_t>(seed), acc);
    MotionQualityResult& r = acc.r;
    r.contact_samples = static_cast<int64_t>(acc.skate_cm_per_s.size());
    r.foot_skate_cm_per_s_p50 = percentile(acc.skate_cm_per_s, 50);
    r.foot_skate_cm_per_s_p95 = percentile(acc.skate_cm_per_s, 95);
    r.foot_skate_cm_per_s_max = acc.skate_cm_per_s.empty()
                                    ? 0.0
                                    : *std::max_element(acc.skate_cm_per_s.begin(), acc.skate_cm_per_s.end());
    r.ground_error_cm_p95 = percentile(acc.ground_cm, 95);
    r.ground_error_cm_max = acc.ground_cm.empty() ? 0.0 : *std::max_element(acc.ground_cm.begin(), acc.ground_cm.end());
    r.pops_per_min = r.minutes > 0.0 ? static_cast<double>(r.pops) / r.minutes : 0.0;
    r.added_pops_per_min = r.minutes > 0.0 ? static_cast<double>(r.added_pops) / r.minutes : 0.0;
    r.unguarded_pops_per_min = r.minutes > 0.0 ? static_cast<double>(r.unguarded_pops) / r.minutes : 0.0;
    r.response_ms_p50 = percentile(acc.response_ms, 50);
    r.response_ms_p95 = percentile(acc.response_ms, 95);
    r.responses = static_cast<int64_t>(acc.response_ms.size());
    r.responses_over_aim = std::count_if(acc.response_ms.begin(), acc.response_ms.end(), [](double ms) { return ms > kResponseAim_ms; });
    r.shown_response_ms_p50 = percentile(acc.shown_response_ms, 50);
    r.shown_response_ms_p95 = percentile(acc.shown_response_ms, 95);
    r.collisions = std::max(r.played_collisions, r.shown_collisions);
    r.goals_reached_share = r.runs > 0 ? static_cast<double>(r.goals_reached) / r.runs : 0.0;
    results.push_back(r);
  }
  return results;
}

std::string motion_quality_text(const std::vector<MotionQualityResult>& results) {
  std::string text;
  char line[512];
  std::snprintf(line, sizeof line, "  %-40s %7s %22s %13s %15s %7s %12s %12s %7s %9s\n", "controller", "goals",
                "skate cm/s p50/p95/max", "ground p95/max", "pops/min (added)", "limits", "resp p50/p95",
                "shown resp", "collide",
                "inertial.");
  text += line;
  for (const MotionQualityResult& r : results) {
    std::snprintf(line, sizeof line,
                  "  %-40s %3d/%-3d %6.2f / %5.2f / %6.1f %5.2f / %5.1f %7.2f (%5.2f) %7lld %5.0f / %5.0f %5.0f / %5.0f %7lld %9lld\n",
                  r.controller.c_str(), r.goals_reached, r.runs, r.foot_skate_cm_per_s_p50, r.foot_skate_cm_per_s_p95,
                  r.foot_skate_cm_per_s_max, r.ground_error_cm_p95, r.ground_error_cm_max, r.pops_per_min,
                  r.added_pops_per_min,
                  static_cast<long long>(r.limit_violations), r.response_ms_p50, r.response_ms_p95,
                  r.shown_response_ms_p50, r.shown_response_ms_p95,
                  static_cast<long long>(r.collisions), static_cast<long long>(r.discontinuities));
    text += line;
  }
  for (const MotionQualityResult& r : results) {
    std::snprintf(line, sizeof line, "  %s: %lld of %lld responses over %.0f ms (a p95 within it allows %lld)\n",
                  r.controller.c_str(), static_cast<long long>(r.responses_over_aim), static_cast<long long>(r.responses),
                  kResponseAim_ms, static_cast<long long>(r.responses / 20));
    text += line;
  }
  for (const MotionQualityResult& r : results)
    if (r.guarded_frames > 0) {
      std::snprintf(line, sizeof line,
                    "  %s: the acceleration guard held back %lld frames (farthest %.1f cm); before it, %.3f pops/min\n",
                    r.controller.c_str(), static_cast<long long>(r.guarded_frames), r.guard_offset_cm_max,
                    r.unguarded_pops_per_min);
      text += line;
    }
  for (const MotionQualityResult& r : results)
    if (r.shown_collisions != r.played_collisions) {
      std::snprintf(line, sizeof line, "  %s: %lld shown frames collide, %lld played\n", r.controller.c_str(),
                    static_cast<long long>(r.shown_collisions), static_cast<long long>(r.played_collisions));
      text += line;
    }
  return text;
}

nlohmann::json motion_quality_json(const MotionQualityResult& r) {
  using bench::rounded;
  return {{"foot_skate_cm_per_s_p50", rounded(r.foot_skate_cm_per_s_p50, 4)},
          {"foot_skate_cm_per_s_p95", rounded(r.foot_skate_cm_per_s_p95, 4)},
          {"foot_skate_cm_per_s_max", rounded(r.foot_skate_cm_per_s_max, 4)},
          {"ground_error_cm_p95", rounded(r.ground_error_cm_p95, 4)},
          {"ground_error_cm_max", rounded(r.ground_error_cm_max, 4)},
          {"pops_per_min", rounded(r.pops_per_min, 3)},
          {"added_pops_per_min", rounded(r.added_pops_per_min, 3)},
          {"unguarded_pops_per_min", rounded(r.unguarded_pops_per_min, 3)},
          {"guarded_frames", r.guarded_frames},
          {"guard_offset_cm_max", rounded(r.guard_offset_cm_max, 3)},
          {"limit_violations", r.limit_violations},
          {"response_ms_p50", rounded(r.response_ms_p50, 1)},
          {"response_ms_p95", rounded(r.response_ms_p95, 1)},
          {"shown_response_ms_p50", rounded(r.shown_response_ms_p50, 1)},
          {"shown_response_ms_p95", rounded(r.shown_response_ms_p95, 1)},
          {"responses", r.responses},
          {"responses_over_250ms", r.responses_over_aim},
          {"collisions", r.collisions},
          {"goals_reached_share", rounded(r.goals_reached_share, 4)}};
}

}  // namespace foresight::lab
