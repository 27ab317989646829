#pragma once
// A scripted "human" at the arrow keys: it plans a coarse route to a goal, then, once per display
// frame, looks at where the avatar is and holds the keys a person would. It only sees the avatar's
// root position, so the same player makes the recordings (recording_generator.hpp drives a local
// LookaheadAvatar with it) and drives network bots (which see their avatar through snapshots).
//
// Each frame the player
//  * takes the camera the scene assigns to the avatar's root (the first camera whose region covers
//    it; the current one while it still covers; the last one when none does; behind the start
//    heading when the scene has none yet),
//  * follows the route (scene_path.hpp), planned with the lowest body the library can move in (so
//    crouch-only passages are on the route; the player never presses crouch: the avatar must
//    choose to crouch by itself) and, where the comfortable clearance finds no way, for the
//    library's own width (moving_body_clearance_m: doorways and gaps a person fits through): it
//    heads for the furthest point of the route, up to
//    look_ahead_m ahead of the avatar's closest point on it, that a clear straight line
//    (sight_clearance_m wide) from the avatar reaches (waypoints within waypoint_reached_m count
//    as passed),
//  * turns that world direction into camera space and quantises it to the 8 arrow-key
//    directions (keeping the pressed key within 32.5 deg, so it does not flicker at a sector
//    boundary), and
//  * behaves like a person, from a seeded std::mt19937_64 (top 53 bits to [0, 1): no
//    implementation-defined distributions, so the keys are the same with any standard library):
//    a reaction delay before following a needed key change, a longer one now and then after a
//    turn (late correction / overshoot), occasional hesitation (all keys released for a moment),
//    brief taps of a wrong key, and a wiggle of the keys when the avatar has made no progress for
//    a while.
// Deterministic: the same route, config and sequence of (t, position) give the same keys. The
// player tracks the avatar continuously (it moves along the route at most two legs per frame), so
// an avatar that is teleported (respawned) needs a new plan().
#include "library/motion_library.hpp"
#include "world/control_input.hpp"
#include "world/collision_world.hpp"
#include "world/scene.hpp"

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace foresight {

struct HumanModel {
  double reaction_min_s = 0.15;  ///< Delay before following a needed key change: uniform in
  double reaction_max_s = 0.30;  ///< [min, max].
  double overshoot_probability = 0.35;  ///< After a turn (waypoint passed), the next change is
  double overshoot_min_s = 0.15;        ///< late by a further uniform [min, max].
  double overshoot_max_s = 0.45;
  double hesitations_per_min = 4;  ///< Rate of releasing every key ...
  double hesitation_min_s = 0.3;   ///< ... for uniform [min, max].
  double hesitation_max_s = 0.8;
  double wrong_taps_per_min = 3;  ///< Rate of pressing a neighbouring wrong key ...
  double wrong_tap_min_s = 0.1;   ///< ... for uniform [min, max].
  double wrong_tap_max_s = 0.25;
  /// No 0.3 m of progress for this long while pressing: wiggle (at most 600 s: the player keeps
  /// this many seconds of positions).
  double stuck_after_s = 4.0;
  double wiggle_s = 1.5;  ///< a key 45 or 90 deg off for this long.
};

struct ScriptedPlayerConfig {
  /// Radius of the walker the route is planned for first (corridor centres). Where that finds no
  /// route, the library's own walker (moving_body_clearance_m) is planned for.
  float route_clearance_m = 0.9f;
  float waypoint_reached_m = 0.8f;  ///< A waypoint this close counts as passed.
  float look_ahead_m = 4.0f;        ///< How far along the route the player looks.
  /// Width (radius) of the clear line it steers along; at most the clearance the route got.
  float sight_clearance_m = 0.5f;
  HumanModel human;
  uint64_t seed = 1;  ///< Of the human behaviour.
  /// The interval between frame() calls, in [0.002, 1] s: the per-frame chances of hesitating
  /// and of wrong taps, and how many frames "stuck_after_s" is, follow from it.
  double frame_interval_s = 1.0 / 30.0;
};

class ScriptedPlayer {
 public:
  static constexpr double kReplanAfter_s = 2.0;

  /// Plans the route from `start` to `goal` for the lowest body the library moves in and starts a
  /// fresh player (keys up, human behaviour from config.seed, no positions seen). False with a
  /// reason (the player is then unplanned) when an argument or config value is not finite or out
  /// of range, the start or the goal is not free (inside an obstacle, outside the scene), or there
  /// is no route. start.heading_rad is where the camera looks when no scene camera covers the
  /// avatar yet. `scene` and `world` are kept by reference: they must outlive the player's use.
  bool plan(const MotionLibrary& library, const Scene& scene, const CollisionWorld& world,
            const Placement& start, vec2 goal, const ScriptedPlayerConfig& config, std::string& error);

  bool planned() const { return scene_ != nullptr; }

  /// The input the player holds at time t_s, seeing the avatar's root at `avatar_pos_m`. Call
  /// once per frame, t increasing by frame_interval_s (the player counts frames for its "stuck"
  /// measure). Stop (keys up) when unplanned or when t or the position is not finite (that frame
  /// is then not seen at all). When no point of the route has been in sight for kReplanAfter_s
  /// (the avatar went round another way and the route is behind a wall), it plans the route
  /// again from where the avatar is (the only allocation, counted in replans()).
  ControlInput frame(double t_s, vec2 avatar_pos_m);
  int replans() const { return replans_; }

  /// Position of the camera the last frame() used (for drawing); zero when no scene camera.
  vec3 camera_pos_m() const { return camera_pos_m_; }

  /// The planned waypoints, start first, goal last (empty when unplanned).
  const std::vector<vec2>& route() const { return route_; }
  float route_length_m() const { return route_length_m_; }
  /// The body height the route was planned for (lowest_moving_body_m).
  float route_body_height_m() const { return route_body_height_m_; }
  /// The clearance (radius) the route was planned for: route_clearance_m or the library's own.
  float route_clearance_used_m() const { return route_clearance_used_m_; }

 private:
  enum class Mode { kFollow, kHesitate, kWrongTap, kWiggle };

  vec2 look_ahead(vec2 pos, bool& in_sight);
  void replan_if_lost(bool route_in_sight, vec2 pos);
  int keys(double t, vec2 wanted_camera_dir, bool turned, double progress_m);
  int want(vec2 camera_dir) const;
  int neighbour(int key);
  // Uniform numbers from the top 53 bits of std::mt19937_64 (fully specified by the standard):
  // std::uniform_real_distribution is not, and the recordings are committed data that must come
  // out the same with any standard library.
  double unit() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
  bool chance(double p) { return unit() < p; }

  // The plan.
  const Scene* scene_ = nullptr;
  const CollisionWorld* world_ = nullptr;
  ScriptedPlayerConfig config_;
  float start_heading_rad_ = 0.0f;
  std::vector<vec2> route_;
  float route_length_m_ = 0.0f;
  float route_body_height_m_ = 0.0f;
  float route_clearance_used_m_ = 0.0f;

  // What the player sees.
  int camera_ = -1;  ///< Scene camera index, -1 before any covered the avatar.
  vec3 camera_pos_m_{0.0f};
  size_t leg_ = 0;  ///< The route leg the avatar is along (only grows).
  /// The last stuck_frames + 1 positions seen (a ring, sized by plan(): no allocation per frame),
  /// for the progress over stuck_after_s.
  std::vector<vec2> history_;
  int64_t frames_seen_ = 0;
  int lost_frames_ = 0;  ///< Frames in a row with no point of the route in sight.
  int replans_ = 0;

  // The human.
  std::mt19937_64 rng_;
  Mode mode_ = Mode::kFollow;
  double mode_until_ = 0;
  int pressed_ = -1;  ///< Arrow key held (0 = up, clockwise), -1: none.
  int saved_key_ = -1;
  double change_at_ = -1;
  double late_by_s_ = 0;
  double pressed_since_ = 0;
  double last_wiggle_s_ = -1e9;
};

}  // namespace foresight
