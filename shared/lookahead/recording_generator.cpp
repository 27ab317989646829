#include "lookahead/recording_generator.hpp"

#include "lookahead/scene_path.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace foresight {
namespace {

// Uniform numbers from the top 53 bits of std::mt19937_64 (fully specified by the standard):
// std::uniform_real_distribution is not, and the recordings are committed data that must come
// out the same with any standard library.
class Dice {
 public:
  explicit Dice(uint64_t seed) : rng_(seed) {}
  double unit() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }
  int below(int n) { return std::min(n - 1, static_cast<int>(unit() * n)); }

 private:
  std::mt19937_64 rng_;
};

// The 8 arrow-key directions in camera space (x right, y up/forward), clockwise from "up".
constexpr float kDiag = 0.70710677f;
const vec2 kKeys[8] = {{0, 1}, {kDiag, kDiag}, {1, 0}, {kDiag, -kDiag},
                       {0, -1}, {-kDiag, -kDiag}, {-1, 0}, {-kDiag, kDiag}};
// A pressed key is kept while the wanted direction stays this close to it (hysteresis: at a
// sector boundary a person does not flick between two keys every frame).
constexpr float kKeepKey_rad = (22.5f + 10.0f) * kPi / 180.0f;

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

// The scripted player: what it sees (avatar position, camera) in, the keys it holds out.
class Player {
 public:
  Player(const HumanModel& model, uint64_t seed, double dt_s) : m_(model), dice_(seed), dt_(dt_s) {}

  // The key held at time t (-1: none). `wanted_camera_dir` is the direction to the target in
  // camera space (zero when there), `turned` whether a waypoint was passed this frame,
  // `progress_m` how far the avatar moved over the last stuck_after_s (negative: not known yet).
  int keys(double t, vec2 wanted_camera_dir, bool turned, double progress_m) {
    if (turned && dice_.chance(m_.overshoot_probability))
      late_by_s_ = dice_.uniform(m_.overshoot_min_s, m_.overshoot_max_s);
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
      if (dice_.chance(m_.hesitations_per_min / 60.0 * dt_)) {
        mode_ = Mode::kHesitate;
        mode_until_ = t + dice_.uniform(m_.hesitation_min_s, m_.hesitation_max_s);
        pressed_ = -1;
        return pressed_;
      }
      if (dice_.chance(m_.wrong_taps_per_min / 60.0 * dt_)) {
        mode_ = Mode::kWrongTap;
        mode_until_ = t + dice_.uniform(m_.wrong_tap_min_s, m_.wrong_tap_max_s);
        saved_key_ = pressed_;
        pressed_ = neighbour(pressed_);
        return pressed_;
      }
      if (progress_m >= 0.0 && progress_m < 0.3 && t - pressed_since_ >= m_.stuck_after_s &&
          t - last_wiggle_s_ >= m_.stuck_after_s && desired >= 0) {
        mode_ = Mode::kWiggle;
        mode_until_ = t + m_.wiggle_s;
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
      change_at_ = t + dice_.uniform(m_.reaction_min_s, m_.reaction_max_s) + late_by_s_;
      late_by_s_ = 0;
    }
    if (t >= change_at_) {
      if (pressed_ < 0) pressed_since_ = t;
      pressed_ = desired;
      change_at_ = -1;
    }
    return pressed_;
  }

 private:
  enum class Mode { kFollow, kHesitate, kWrongTap, kWiggle };

  int want(vec2 camera_dir) const {
    const float len = glm::length(camera_dir);
    if (len < 1e-3f) return -1;
    if (pressed_ >= 0) {
      const float c = glm::dot(camera_dir / len, kKeys[pressed_]) / glm::length(kKeys[pressed_]);
      if (c >= std::cos(kKeepKey_rad)) return pressed_;
    }
    return key_of(camera_dir);
  }
  // 45 or 90 degrees off, either side.
  int neighbour(int key) {
    static constexpr int kOffsets[4] = {1, -1, 2, -2};
    return (key + kOffsets[dice_.below(4)] + 8) % 8;
  }

  HumanModel m_;
  Dice dice_;
  double dt_;
  Mode mode_ = Mode::kFollow;
  double mode_until_ = 0;
  int pressed_ = -1;
  int saved_key_ = -1;
  double change_at_ = -1;
  double late_by_s_ = 0;
  double pressed_since_ = 0;
  double last_wiggle_s_ = -1e9;
};

// The point the player steers for (pure pursuit along the route): from the closest point of
// the route to the avatar (legs are never revisited: `leg` only grows; a waypoint within
// waypoint_reached_m counts as passed), the furthest point up to look_ahead_m further along that
// a straight clear line from the avatar reaches (sight_clearance_m wide). When even the closest
// point is hidden (the avatar brushes a wall), a point 0.5 m ahead of it.
vec2 look_ahead(const CollisionWorld& world, const std::vector<vec2>& route, vec2 pos,
                const RecordingGeneratorConfig& c, float body_height_m, size_t& leg) {
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
  if (any) return seen;
  const vec2 along = route[leg + 1] - route[leg];
  const float len = glm::length(along);
  return len > 0.0f ? route[leg] + u * along + along * (std::min(0.5f, len) / len) : route[leg + 1];
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

float lowest_moving_body_m(const MotionLibrary& library) {
  float lowest = kStandingHeight_m;
  bool any = false;
  for (int s = 0; s < library.graph.num_segments(); ++s) {
    if (!(library.graph.segments[s].tags & kTagLocomotion)) continue;
    const float top = library.segment_shapes[static_cast<size_t>(s)].y_max_m;
    lowest = any ? std::min(lowest, top) : top;
    any = true;
  }
  return lowest;
}

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

  GeneratedRecording g;
  g.route_body_height_m = lowest_moving_body_m(library);
  if (!scene_route(world, spawn->pos_m, goal->pos_m, config.route_clearance_m, g.route_body_height_m, g.route)) {
    error = scene.name + ": no route from spawn \"" + spawn->name + "\" to goal \"" + goal->name +
            "\" for a body of radius " + std::to_string(config.route_clearance_m) + " m and height " +
            std::to_string(g.route_body_height_m) + " m";
    return false;
  }
  g.route_length_m = route_length_m(g.route);

  Recording& rec = g.recording;
  rec.scene = config.scene.empty() ? scene.name : config.scene;
  rec.name = config.name;
  rec.library_hash = library.content_hash;
  rec.start_pos_m = spawn->pos_m;
  rec.start_heading_rad = spawn->heading_rad;
  rec.goal_pos_m = goal->pos_m;
  rec.goal_radius_m = goal->radius_m;

  ReplayRun run(library, world, Placement{spawn->pos_m, spawn->heading_rad}, goal->pos_m, goal->radius_m, rc);
  if (!run.ok()) {
    error = run.error();
    return false;
  }

  Player player(config.human, config.seed, dt);
  const int stuck_frames = std::max(1, static_cast<int>(std::lround(config.human.stuck_after_s / dt)));
  int camera = -1;
  size_t leg = 0;  // the route leg the avatar is along
  while (!run.done()) {
    const double t = run.time_s();
    const vec2 pos = run.avatar().root().pos_m;

    camera = camera_for(scene, pos, camera);
    float yaw_rad = spawn->heading_rad;  // no camera anywhere: one behind the spawn
    vec3 camera_pos(0.0f);
    if (camera >= 0) {
      const SceneCamera& cam = scene.cameras[static_cast<size_t>(camera)];
      yaw_rad = heading_of(cam.target_m - cam.position_m);
      camera_pos = cam.position_m;
    }

    // Where the player looks: the furthest point of the route ahead that it can see.
    const size_t before = leg;
    const vec2 target = look_ahead(world, g.route, pos, config, g.route_body_height_m, leg);
    const bool turned = leg != before;
    const vec2 to_target = target - pos;
    const float distance = glm::length(to_target);
    const vec2 wanted = distance > 1e-3f ? world_to_camera(to_target / distance, yaw_rad) : vec2(0.0f);

    const auto& path = run.result().path;
    const double progress = path.size() > static_cast<size_t>(stuck_frames)
                                ? glm::length(pos - path[path.size() - 1 - static_cast<size_t>(stuck_frames)])
                                : -1.0;
    const int key = player.keys(t, wanted, turned, progress);

    ControlInput input;
    input.camera_dir = key >= 0 ? kKeys[key] : vec2(0.0f);
    input.camera_yaw_rad = yaw_rad;
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
