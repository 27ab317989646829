#include "scripted/scripted_player.hpp"

#include "lookahead/scene_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace foresight {
namespace {

// The 8 arrow-key directions in camera space (x right, y up/forward), clockwise from "up".
constexpr float kDiag = 0.70710677f;
const vec2 kKeys[8] = {{0, 1}, {kDiag, kDiag}, {1, 0}, {kDiag, -kDiag},
                       {0, -1}, {-kDiag, -kDiag}, {-1, 0}, {-kDiag, kDiag}};
// A pressed key is kept while the wanted direction stays this close to it (hysteresis: at a
// sector boundary a person does not flick between two keys every frame).
constexpr float kKeepKey_rad = (22.5f + 10.0f) * kPi / 180.0f;
// The longest stuck_after_s: the player keeps that many seconds of positions (300k at 2 ms).
constexpr double kMaxStuckAfter_s = 600.0;
// The radius of the thin body scene_route joins the exact start / goal to its grid with: a point
// not free for it cannot be routed from or to, whatever the clearance.
constexpr float kThinRadius_m = 0.05f;

int key_of(vec2 camera_dir) {
  const float a = std::atan2(camera_dir.x, camera_dir.y);  // 0 = up, +pi/2 = right
  const int k = static_cast<int>(std::lround(a / (kPi / 4.0f)));
  return ((k % 8) + 8) % 8;
}

vec2 world_to_camera(vec2 world_dir, float yaw_rad) {
  const float s = std::sin(yaw_rad), c = std::cos(yaw_rad);
  const vec2 forward(s, c), right(-c, s);  // as control_world_direction
  return {glm::dot(world_dir, right), glm::dot(world_dir, forward)};
}

// The camera for a point: the current one while it covers it, else the first that does, else
// the current one (-1 only before any camera was chosen).
int camera_for(const Scene& scene, vec2 p, int current) {
  if (current >= 0 && scene.cameras[static_cast<size_t>(current)].region.contains(p)) return current;
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    if (scene.cameras[i].region.contains(p)) return static_cast<int>(i);
  return current;
}

bool finite(vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

std::string point_text(vec2 p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f)", static_cast<double>(p.x), static_cast<double>(p.y));
  return buf;
}

std::string metres(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f m", v);
  return buf;
}

// Empty when the model is usable, else the first field that is not.
std::string human_model_problem(const HumanModel& h) {
  const std::pair<const char*, double> fields[] = {
      {"reaction_min_s", h.reaction_min_s},   {"reaction_max_s", h.reaction_max_s},
      {"overshoot_probability", h.overshoot_probability},
      {"overshoot_min_s", h.overshoot_min_s}, {"overshoot_max_s", h.overshoot_max_s},
      {"hesitations_per_min", h.hesitations_per_min},
      {"hesitation_min_s", h.hesitation_min_s}, {"hesitation_max_s", h.hesitation_max_s},
      {"wrong_taps_per_min", h.wrong_taps_per_min},
      {"wrong_tap_min_s", h.wrong_tap_min_s}, {"wrong_tap_max_s", h.wrong_tap_max_s},
      {"stuck_after_s", h.stuck_after_s},     {"wiggle_s", h.wiggle_s}};
  for (const auto& [name, value] : fields)
    if (!(std::isfinite(value) && value >= 0.0)) return std::string(name) + " must be finite and >= 0";
  if (h.overshoot_probability > 1.0) return "overshoot_probability must be at most 1";
  if (h.stuck_after_s > kMaxStuckAfter_s) return "stuck_after_s must be at most 600 s";
  return {};
}

}  // namespace

bool ScriptedPlayer::plan(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
                          const Placement& start, vec2 goal, const ScriptedPlayerConfig& config,
                          std::string& error) {
  *this = ScriptedPlayer();  // unplanned until everything checks out
  if (!finite(start.pos_m) || !std::isfinite(start.heading_rad) || !finite(goal)) {
    error = "scripted player: the start " + point_text(start.pos_m) + " (heading " +
            std::to_string(start.heading_rad) + ") and the goal " + point_text(goal) + " must be finite";
    return false;
  }
  const ScriptedPlayerConfig& c = config;
  if (!(c.frame_interval_s >= 0.002 && c.frame_interval_s <= 1.0)) {
    error = "scripted player: frame_interval_s must be in [0.002, 1] s";
    return false;
  }
  const auto usable = [](float v) { return std::isfinite(v) && v >= 0.0f; };
  if (!(usable(c.route_clearance_m) && usable(c.waypoint_reached_m) && usable(c.look_ahead_m) &&
        usable(c.sight_clearance_m))) {
    error = "scripted player: route_clearance_m, waypoint_reached_m, look_ahead_m and sight_clearance_m "
            "must be finite and >= 0";
    return false;
  }
  if (const std::string problem = human_model_problem(c.human); !problem.empty()) {
    error = "scripted player: human model: " + problem;
    return false;
  }

  const float height = lowest_moving_body_m(library);
  const float body_clearance = moving_body_clearance_m(library);
  std::vector<vec2> route;
  float clearance = c.route_clearance_m;
  bool routed = scene_route(world, start.pos_m, goal, clearance, height, route);
  if (!routed && body_clearance < clearance) {
    clearance = body_clearance;
    routed = scene_route(world, start.pos_m, goal, clearance, height, route);
  }
  if (!routed) {
    const std::string body = "a body of height " + metres(height);
    if (!scene_segment_clear(world, start.pos_m, start.pos_m, kThinRadius_m, height))
      error = "no route: the start " + point_text(start.pos_m) + " is not free for " + body +
              " (inside an obstacle or outside the scene)";
    else if (!scene_segment_clear(world, goal, goal, kThinRadius_m, height))
      error = "no route: the goal " + point_text(goal) + " is not free for " + body +
              " (inside an obstacle or outside the scene)";
    else
      error = "no route from " + point_text(start.pos_m) + " to " + point_text(goal) +
              " for a body of radius " + metres(clearance) + " and height " + metres(height) +
              " (the library's walkers are " + metres(2.0f * (body_clearance - kMovingBodySteerRoom_m)) +
              " across): every way is narrower or lower, or walled off";
    return false;
  }

  scene_ = &scene;
  world_ = &world;
  config_ = c;
  start_heading_rad_ = start.heading_rad;
  route_ = std::move(route);
  route_length_m_ = foresight::route_length_m(route_);
  route_body_height_m_ = height;
  route_clearance_used_m_ = clearance;
  config_.sight_clearance_m = std::min(c.sight_clearance_m, clearance);
  const int stuck_frames =
      std::max(1, static_cast<int>(std::lround(c.human.stuck_after_s / c.frame_interval_s)));
  history_.assign(static_cast<size_t>(stuck_frames) + 1, vec2(0.0f));
  rng_.seed(c.seed);
  return true;
}

ControlInput ScriptedPlayer::frame(double t, vec2 pos) {
  const bool seen = planned() && finite(pos) && std::isfinite(t);
  if (seen) camera_ = camera_for(*scene_, pos, camera_);
  ControlInput input;
  input.camera_yaw_rad = start_heading_rad_;  // no camera anywhere: one behind the start
  camera_pos_m_ = vec3(0.0f);
  if (camera_ >= 0) {
    const SceneCamera& cam = scene_->cameras[static_cast<size_t>(camera_)];
    input.camera_yaw_rad = heading_of(cam.target_m - cam.position_m);
    camera_pos_m_ = cam.position_m;
  }
  if (!seen) return input;  // keys up; the frame is not counted

  // Where the player looks: the furthest point of the route ahead that it can see.
  const size_t before = leg_;
  bool in_sight = false;
  const vec2 target = look_ahead(pos, in_sight);
  replan_if_lost(in_sight, pos);
  const bool turned = leg_ != before;
  const vec2 to_target = target - pos;
  const float distance = glm::length(to_target);
  const vec2 wanted =
      distance > 1e-3f ? world_to_camera(to_target / distance, input.camera_yaw_rad) : vec2(0.0f);

  // Progress: the distance from the position stuck_frames frames ago. The reference is never the
  // first position seen (the generator measured along its replay's path, which starts after the
  // first frame; kept so that recordings do not change), so -1 until stuck_frames + 2 are known.
  const size_t n = history_.size();  // stuck_frames + 1
  history_[static_cast<size_t>(frames_seen_ % static_cast<int64_t>(n))] = pos;
  ++frames_seen_;
  const double progress =
      frames_seen_ > static_cast<int64_t>(n)
          ? glm::length(pos - history_[static_cast<size_t>(frames_seen_ % static_cast<int64_t>(n))])
          : -1.0;

  const int key = keys(t, wanted, turned, progress);
  input.camera_dir = key >= 0 ? kKeys[key] : vec2(0.0f);
  return input;
}

// The point the player steers for (pure pursuit along the route): from the closest point of
// the route to the avatar (legs are never revisited: `leg_` only grows, by at most two legs per
// frame; a waypoint within waypoint_reached_m counts as passed), the furthest point up to
// look_ahead_m further along that a straight clear line from the avatar reaches
// (sight_clearance_m wide). When even the closest point is hidden (the avatar brushes a wall), a
// point 0.5 m ahead of it.
vec2 ScriptedPlayer::look_ahead(vec2 pos, bool& in_sight) {
  const ScriptedPlayerConfig& c = config_;
  const std::vector<vec2>& route = route_;
  const CollisionWorld& world = *world_;
  const float body_height_m = route_body_height_m_;
  size_t& leg = leg_;
  const size_t last_leg = route.size() - 2;
  const auto closest_on = [&](size_t i, float& u) {
    const vec2 a = route[i], ab = route[i + 1] - a;
    const float len2 = glm::dot(ab, ab);
    u = len2 > 0.0f ? std::clamp(glm::dot(pos - a, ab) / len2, 0.0f, 1.0f) : 1.0f;
    return glm::length(a + u * ab - pos);
  };
  float u = 0.0f;
  float best = closest_on(leg, u);
  const size_t first = leg;
  for (size_t i = first + 1; i <= std::min(first + 2, last_leg); ++i) {
    float ui = 0.0f;
    const float d = closest_on(i, ui);
    if (d < best) best = d, leg = i, u = ui;
  }
  while (leg < last_leg && glm::length(route[leg + 1] - pos) < c.waypoint_reached_m) ++leg, u = 0.0f;
  // Walk along the route from the closest point.
  size_t i = leg;
  vec2 p = route[i] + u * (route[i + 1] - route[i]);
  vec2 seen = p;
  bool any = scene_segment_clear(world, pos, p, c.sight_clearance_m, body_height_m);
  float walked = 0.0f;
  const float step = 0.25f;
  while (walked < c.look_ahead_m) {
    const float left = glm::length(route[i + 1] - p);
    if (left <= step) {
      if (i == last_leg) {
        p = route[i + 1];
        walked = c.look_ahead_m;
      } else {
        p = route[++i];
        walked += left;
        continue;
      }
    } else {
      p += (route[i + 1] - p) * (step / left);
      walked += step;
    }
    if (!scene_segment_clear(world, pos, p, c.sight_clearance_m, body_height_m)) break;
    seen = p;
    any = true;
  }
  in_sight = any;
  if (any) return seen;
  const vec2 along = route[leg + 1] - route[leg];
  const float len = glm::length(along);
  return len > 0.0f ? route[leg] + u * along + along * (std::min(0.5f, len) / len) : route[leg + 1];
}

// A person who finds the way they meant to take behind a wall (the avatar went round by another
// way, or was pushed aside) looks for the way again from where they are.
void ScriptedPlayer::replan_if_lost(bool route_in_sight, vec2 pos) {
  lost_frames_ = route_in_sight ? 0 : lost_frames_ + 1;
  if (static_cast<double>(lost_frames_) * config_.frame_interval_s < kReplanAfter_s) return;
  lost_frames_ = 0;
  std::vector<vec2> route;
  if (!scene_route(*world_, pos, route_.back(), route_clearance_used_m_, route_body_height_m_, route)) return;
  route_ = std::move(route);
  leg_ = 0;
  ++replans_;
}

// The key held at time t (-1: none). `wanted_camera_dir` is the direction to the target in
// camera space (zero when there), `turned` whether a waypoint was passed this frame,
// `progress_m` how far the avatar moved over the last stuck_after_s (negative: not known yet).
int ScriptedPlayer::keys(double t, vec2 wanted_camera_dir, bool turned, double progress_m) {
  const HumanModel& m = config_.human;
  const double dt = config_.frame_interval_s;
  if (turned && chance(m.overshoot_probability)) late_by_s_ = uniform(m.overshoot_min_s, m.overshoot_max_s);
  switch (mode_) {
    case Mode::kHesitate:
    case Mode::kWiggle:
      if (t < mode_until_) return pressed_;
      mode_ = Mode::kFollow;
      pressed_since_ = t;
      break;
    case Mode::kWrongTap:
      if (t < mode_until_) return pressed_;
      mode_ = Mode::kFollow;
      pressed_ = saved_key_;  // the tap is released: back to the key held before
      break;
    case Mode::kFollow: break;
  }
  const int desired = want(wanted_camera_dir);
  if (pressed_ >= 0 && change_at_ < 0) {
    if (chance(m.hesitations_per_min / 60.0 * dt)) {
      mode_ = Mode::kHesitate;
      mode_until_ = t + uniform(m.hesitation_min_s, m.hesitation_max_s);
      pressed_ = -1;
      return pressed_;
    }
    if (chance(m.wrong_taps_per_min / 60.0 * dt)) {
      mode_ = Mode::kWrongTap;
      mode_until_ = t + uniform(m.wrong_tap_min_s, m.wrong_tap_max_s);
      saved_key_ = pressed_;
      pressed_ = neighbour(pressed_);
      return pressed_;
    }
    if (progress_m >= 0.0 && progress_m < 0.3 && t - pressed_since_ >= m.stuck_after_s &&
        t - last_wiggle_s_ >= m.stuck_after_s && desired >= 0) {
      mode_ = Mode::kWiggle;
      mode_until_ = t + m.wiggle_s;
      last_wiggle_s_ = mode_until_;
      pressed_ = neighbour(desired);
      return pressed_;
    }
  }
  if (desired == pressed_) {
    change_at_ = -1;
    return pressed_;
  }
  if (change_at_ < 0) {
    change_at_ = t + uniform(m.reaction_min_s, m.reaction_max_s) + late_by_s_;
    late_by_s_ = 0;
  }
  if (t >= change_at_) {
    if (pressed_ < 0) pressed_since_ = t;
    pressed_ = desired;
    change_at_ = -1;
  }
  return pressed_;
}

int ScriptedPlayer::want(vec2 camera_dir) const {
  const float len = glm::length(camera_dir);
  if (len < 1e-3f) return -1;
  if (pressed_ >= 0) {
    const float c = glm::dot(camera_dir / len, kKeys[pressed_]) / glm::length(kKeys[pressed_]);
    if (c >= std::cos(kKeepKey_rad)) return pressed_;
  }
  return key_of(camera_dir);
}

// 45 or 90 degrees off, either side.
int ScriptedPlayer::neighbour(int key) {
  static constexpr int kOffsets[4] = {1, -1, 2, -2};
  const int pick = std::min(3, static_cast<int>(unit() * 4));
  return (key + kOffsets[pick] + 8) % 8;
}

}  // namespace foresight
