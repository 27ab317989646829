#include "client_app.hpp"

#include "avatar_decode.hpp"
#include "camera_rig.hpp"
#include "client_input.hpp"
#include "debug_overlay.hpp"
#include "fighter_poses.hpp"
#include "terrain_poses.hpp"
#include "renderer.hpp"
#include "screenshot.hpp"
#include "script_input.hpp"
#include "snapshot_buffer.hpp"
#include "strike_feedback.hpp"
#include "tree_overlay.hpp"

#include "fighter/morphology.hpp"
#include "library/playback.hpp"
#include "library/pose_stage.hpp"
#include "transport/client_connection.hpp"
#include "protocol/protocol.hpp"
#include "world/data_paths.hpp"
#include "transport/scene_transfer.hpp"
#include "world/collision_world.hpp"
#include "world/scene_load.hpp"

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <thread>
#include <unordered_map>

namespace foresight::client {

namespace {

using Clock = std::chrono::steady_clock;

constexpr vec3 kOwnColour{1.0f, 0.55f, 0.10f};    // orange: the player
constexpr vec3 kOtherColour{0.25f, 0.45f, 0.85f}; // blue: everyone else
constexpr vec3 kNpcColour{0.60f, 0.30f, 0.70f};      // NPCs without a streamed pose
constexpr vec3 kFighterColour{0.72f, 0.06f, 0.10f};  // crimson: NPC fighters
constexpr vec3 kStrikingColour{1.00f, 0.16f, 0.12f}; // bright red: a fighter mid-strike
constexpr vec3 kFlashColour{1.0f, 1.0f, 1.0f};       // a hit target flashes white
// Effector markers (unlit): magenta where a strike hit, yellow where it missed; 0.2 m cubes
// shrinking to half over their second.
constexpr vec3 kHitMarkerColour{1.0f, 0.15f, 0.85f};
constexpr vec3 kMissMarkerColour{1.0f, 0.92f, 0.20f};
constexpr float kMarkerSizeM = 0.20f;
constexpr vec3 kStoppedColour{0.70f, 0.30f, 0.30f};  // idle fallback: nothing feasible ahead
/// Least time between two Inputs: the server ticks at 30 Hz, the window may draw far faster.
constexpr std::chrono::milliseconds kInputInterval{30};
constexpr double kMinFrameS = 1.0 / 240.0;  ///< Frame cap when vsync does not throttle.
/// Tree overlay (paper Fig. 5, tree_overlay.hpp): how often the tree is asked for.
constexpr double kTreeRequestIntervalS = 0.2;

void on_glfw_error(int code, const char* message) {
  std::fprintf(stderr, "foresight-client: GLFW error %d: %s\n", code, message);
}

// Edge-triggered keys (F, Escape) come through the callback; held keys are polled per frame.
void on_key(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, GLFW_TRUE);
  if (key == GLFW_KEY_F) static_cast<CameraRig*>(glfwGetWindowUserPointer(window))->toggle_follow();
}

HeldKeys held_keys(GLFWwindow* w) {
  // Focus lost: nothing is held (a key released in another window never reaches us).
  if (!glfwGetWindowAttrib(w, GLFW_FOCUSED)) return {};
  auto down = [w](int a, int b) { return glfwGetKey(w, a) == GLFW_PRESS || glfwGetKey(w, b) == GLFW_PRESS; };
  HeldKeys k;
  k.up = down(GLFW_KEY_UP, GLFW_KEY_W);
  k.down = down(GLFW_KEY_DOWN, GLFW_KEY_S);
  k.left = down(GLFW_KEY_LEFT, GLFW_KEY_A);
  k.right = down(GLFW_KEY_RIGHT, GLFW_KEY_D);
  k.crouch = glfwGetKey(w, GLFW_KEY_C) == GLFW_PRESS;
  return k;
}

// Mouse-drag steering: the drag starts where the left button went down (unless the press went to
// the debug overlay) and lasts while the button is held and the window has focus (a release in
// another window never reaches us).
void update_drag(GLFWwindow* w, bool overlay_wants_mouse, MouseDrag& drag) {
  if (!glfwGetWindowAttrib(w, GLFW_FOCUSED) || glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) != GLFW_PRESS) {
    drag.active = false;
    return;
  }
  double x = 0, y = 0;
  glfwGetCursorPos(w, &x, &y);
  const vec2 at(static_cast<float>(x), static_cast<float>(y));
  if (!drag.active) {
    if (overlay_wants_mouse) return;
    drag.active = true;
    drag.from_px = at;
  }
  drag.to_px = at;
}

uint32_t id_of(const FighterPoseSample& f) { return f.avatar; }
uint32_t id_of(uint32_t id) { return id; }

vec3 colour_of(const ShownAvatar& a, uint32_t own_id) {
  if (a.id == own_id || (a.flags & protocol::kAvatarYours)) return kOwnColour;
  if (a.flags & protocol::kAvatarNpc) return kNpcColour;
  if (a.flags & protocol::kAvatarFallback) return kStoppedColour;
  return kOtherColour;
}

// Everything one window needs; lives while its GL context is current.
class Session {
 public:
  Session(GLFWwindow* window, const MotionLibrary& library, const ClientOptions& options)
      : window_(window), library_(library), options_(options), connection_(connection_config(options)),
        buffer_(buffer_config(options)), morphologies_(with_default(default_morphologies())),
        terrain_(morphologies_.back(), static_cast<uint8_t>(morphologies_.size() - 1)),
        strikes_(strike_config(options)), rig_(nullptr, follow_config(options)) {
    tree_overlay_ = options.tree_overlay;
    if (options.follow_camera) rig_.toggle_follow();
    overlay_.set_visible(!options.hide_overlay);
    shown_.reserve(256);
    shown_fighters_.reserve(static_cast<size_t>(fighters_.config().max_fighters));
    strike_events_.reserve(64);
    entries_.reserve(256);
    ghosts_.reserve(protocol::kMaxTreeSamples * kGhostFramesPerNode);
    glfwSetWindowUserPointer(window_, &rig_);
    glfwSetKeyCallback(window_, on_key);
  }

  // The overlay after the constructor set our GLFW callbacks: ImGui chains to them.
  bool init(std::string& error) { return renderer_.init(error) && overlay_.init(window_, error); }

  /// One frame. Returns false when the program should end (exit status in `status`).
  bool frame(int& status);

 private:
  static protocol::ClientConfig connection_config(const ClientOptions& o) {
    protocol::ClientConfig c;
    c.min_input_interval = kInputInterval;
    c.impairment = o.impairment;
    return c;
  }
  static StrikeFeedbackConfig strike_config(const ClientOptions& o) {
    StrikeFeedbackConfig c;
    c.show_delay_s = o.delay_s;
    return c;
  }
  static FollowCameraConfig follow_config(const ClientOptions& o) {
    FollowCameraConfig c;
    if (o.follow_distance_m > 0) {  // nearer or farther, looking down at the same angle
      c.height_m *= o.follow_distance_m / c.distance_m;
      c.distance_m = o.follow_distance_m;
    }
    return c;
  }
  static std::vector<Morphology> with_default(std::vector<Morphology> fighters) {
    fighters.push_back(default_morphology());  // last: the terrain avatars' skeleton
    return fighters;
  }
  static SnapshotBufferConfig buffer_config(const ClientOptions& o) {
    SnapshotBufferConfig c;
    c.delay_s = o.delay_s;
    return c;
  }
  void connection_step(Clock::time_point now, double t);
  void on_connected();
  void show_scene(const std::string& name, uint64_t hash, std::string_view text);
  void fetch_scene();  ///< One part a frame until the server's scene file has arrived.
  void draw_avatars(double t, vec2& own_pos, float& own_heading, bool& own_seen);
  void draw_fighters(double t);
  void draw_terrain_avatars(double t, vec2& own_pos, float& own_heading, bool& own_seen);
  const ShownAvatar* shown_avatar(uint32_t id) const;
  void tree_overlay_step(double t);

  GLFWwindow* window_;
  const MotionLibrary& library_;
  const ClientOptions& options_;
  protocol::ClientConnection connection_;
  SnapshotBuffer buffer_;
  std::vector<Morphology> morphologies_;  ///< default_morphologies(): the fighters' skeletons; last the default.
  FighterPoses fighters_;                 ///< Their streamed poses, played with the avatars.
  TerrainPoses terrain_;                  ///< Terrain avatars' bodies, likewise.
  StrikeFeedback strikes_;                ///< Strike markers, hit flashes, counters.
  CameraRig rig_;
  Renderer renderer_;
  DebugOverlay overlay_;  ///< F1; drawn over the scene (also in screenshots).
  Scene scene_;
  CollisionWorld obstacles_;  ///< scene_'s boxes: the pose stages' eased turns keep joints out of them.
  bool has_obstacles_ = false;
  std::string scene_name_;
  Clock::time_point start_ = Clock::now();
  double last_frame_s_ = 0;

  bool started_ = false, was_connected_ = false, reported_down_ = false;
  double next_attempt_s_ = 0;
  uint32_t last_tick_ = 0;
  int last_parts_ = -1;
  uint64_t rejected_ = 0;
  int shot_frames_ = 0;
  FrameStrip strip_;  ///< Screenshot mode: the frames taken so far.
  bool tree_overlay_ = false, tree_key_down_ = false;
  double next_tree_request_s_ = 0;
  double connected_at_s_ = 0;  ///< When the connection was last made (the script's time 0).
  bool script_end_reported_ = false;
  bool resized_ = false;  ///< --resize-at-s done.
  MouseDrag drag_;

  std::vector<AvatarEntry> entries_;
  std::vector<ShownAvatar> shown_;
  /// Per avatar shown from the library: its pose stage (foot locking, eased turns, no pops),
  /// kept while it is shown (docs/MOTION_QUALITY.md).
  std::unordered_map<uint32_t, PoseStage> poses_;
  double last_draw_s_ = -1.0;
  std::vector<PlaybackState> ghosts_;  ///< Tree overlay scratch: the chosen branch's ghost poses.
  std::vector<FighterPoseSample> shown_fighters_;
  std::vector<FighterPoseSample> shown_terrain_;
  std::vector<protocol::StrikeEventInfo> strike_events_;
  std::vector<vec3> fighter_local_pos_, fighter_global_pos_;  ///< FK scratch.
  std::vector<quat> fighter_global_rot_;
  uint64_t scene_hash_ = 0;      ///< Of the scene shown (0: none, or an empty floor).
  bool fetching_scene_ = false;  ///< The server's scene file is on its way.
};

void Session::on_connected() {
  const auto& a = connection_.accept();
  std::fprintf(stderr, "foresight-client: connected to %s: scene '%s', avatar %u, %u Hz ticks\n",
               options_.server_text.c_str(), a.scene.c_str(), a.avatar, a.tick_hz);
  if (a.scene == scene_name_ && a.scene_hash == scene_hash_) return;
  // Our own copy when it is the server's file; else fetched (connection_step) and drawn when it
  // has arrived. Meanwhile: avatars on an empty floor.
  fetching_scene_ = false;
  std::string text;
  if (protocol::own_scene_file_matches(options_.scene_path, a.scene, a.scene_hash, text)) {
    show_scene(a.scene, a.scene_hash, text);
    return;
  }
  std::fprintf(stderr, "foresight-client: scene '%s': %s, fetching the server's (%u bytes)\n", a.scene.c_str(),
               text.empty() ? "no copy here" : "our copy differs from the server's", a.scene_bytes);
  fetching_scene_ = true;
  show_scene(a.scene, 0, {});
}

void Session::show_scene(const std::string& name, uint64_t hash, std::string_view text) {
  std::string error;
  Scene scene;
  if (text.empty() || !scene_parse(text, name, scene, error)) {
    if (!text.empty()) std::fprintf(stderr, "foresight-client: cannot load scene '%s' (%s): drawing avatars only\n",
                                    name.c_str(), error.c_str());
    scene = Scene{};
    scene.bounds = {vec2(-20.0f), vec2(20.0f)};
  }
  scene_ = std::move(scene);
  scene_name_ = name;
  scene_hash_ = hash;
  has_obstacles_ = collision_world_build(scene_, obstacles_, error);
  if (!has_obstacles_)
    std::fprintf(stderr, "foresight-client: scene '%s' has no collision world (%s): turns are eased without it\n",
                 name.c_str(), error.c_str());
  rig_.set_scene(&scene_);
  renderer_.set_scene(scene_);
}

void Session::fetch_scene() {
  const protocol::SceneDownload& d = connection_.scene_download();
  if (!d.complete()) {
    connection_.request_scene_part();
    return;
  }
  fetching_scene_ = false;
  if (!d.verified()) {
    std::fprintf(stderr, "foresight-client: the server's scene arrived with another hash than it named\n");
    return;
  }
  std::fprintf(stderr, "foresight-client: scene '%s' fetched from the server\n", connection_.accept().scene.c_str());
  show_scene(connection_.accept().scene, d.hash(), d.bytes());
}

void Session::connection_step(Clock::time_point now, double t) {
  using protocol::ClientState;
  const ClientState state = connection_.state();
  if (state == ClientState::kConnecting || state == ClientState::kConnected) {
    connection_.update(now);
  } else if (!started_ || t >= next_attempt_s_) {
    if (started_) std::fprintf(stderr, "foresight-client: reconnecting to %s\n", options_.server_text.c_str());
    started_ = true;
    reported_down_ = false;
    buffer_.clear();
    fighters_.clear();
    terrain_.clear();
    strikes_.clear_effects();
    last_parts_ = -1;
    if (!connection_.start(options_.server, library_.content_hash, options_.name, now)) {
      std::fprintf(stderr, "foresight-client: %s\n", connection_.status_message().c_str());
    }
  }
  const bool connected = connection_.connected();
  if (connected && !was_connected_) {
    on_connected();
    connected_at_s_ = t;
    script_end_reported_ = false;
  }
  was_connected_ = connected;
  if (connected && fetching_scene_) fetch_scene();
  const ClientState after = connection_.state();
  if (after != ClientState::kConnecting && after != ClientState::kConnected && !reported_down_) {
    // The server is gone, refused us or never answered: say so once, then retry on a timer.
    std::fprintf(stderr, "foresight-client: %s (%s); retrying every %.0f s\n",
                 protocol::client_state_name(after), connection_.status_message().c_str(),
                 options_.reconnect_interval_s);
    reported_down_ = true;
    next_attempt_s_ = t + options_.reconnect_interval_s;
  }
  if (!connected || !connection_.has_snapshot() || connection_.accept().tick_hz == 0) return;
  // A new tick, or more parts of the newest one: (re)place it in the buffer.
  if (connection_.snapshot_tick() != last_tick_ || connection_.snapshot_parts_received() != last_parts_) {
    last_tick_ = connection_.snapshot_tick();
    last_parts_ = connection_.snapshot_parts_received();
    rejected_ += static_cast<uint64_t>(avatar_entries_from_wire(library_, connection_.avatars(), entries_));
    const double server_time_s = static_cast<double>(last_tick_) / connection_.accept().tick_hz;
    buffer_.push(server_time_s, t, entries_);
    fighters_.push(server_time_s, connection_.fighters());
    terrain_.push(server_time_s, connection_.terrain_bodies());
  }
  strike_events_.clear();
  connection_.take_strike_events(strike_events_);
  if (!strike_events_.empty()) strikes_.add(strike_events_, connection_.accept().avatar, t);
  for (const protocol::StrikeEventInfo& e : strike_events_) {
    if (e.target != connection_.accept().avatar) continue;
    std::fprintf(stderr, "foresight-client: %.2f s: %s by fighter %u's %s (%.2f m from the head)\n",
                 t - connected_at_s_, e.hit ? "hit" : "dodged", e.fighter, e.kick ? "kick" : "punch",
                 static_cast<double>(e.miss_m));
  }
}

void Session::draw_avatars(double t, vec2& own_pos, float& own_heading, bool& own_seen) {
  renderer_.begin_frame();
  const double render_t = buffer_.render_time(t);
  buffer_.sample(library_, render_t, shown_);
  fighters_.sample(render_t, shown_fighters_);
  const uint32_t own_id = connection_.accept().avatar;
  const float dt = last_draw_s_ < 0.0 ? 0.0f : static_cast<float>(std::clamp(t - last_draw_s_, 0.0, 0.25));
  last_draw_s_ = t;
  std::erase_if(poses_, [this](const auto& p) { return shown_avatar(p.first) == nullptr; });
  for (const ShownAvatar& a : shown_) {
    const vec3 colour = colour_of(a, own_id);
    // A fighter with a streamed pose is drawn from it (draw_fighters), not from the library.
    const bool fighter = (a.flags & protocol::kAvatarNpc) &&
                         std::binary_search(shown_fighters_.begin(), shown_fighters_.end(), a.id,
                                            [](const auto& x, const auto& y) { return id_of(x) < id_of(y); });
    if (!fighter) {
      const float flash = strikes_.target_flash(a.id, t);
      PoseStage& stage = poses_.try_emplace(a.id, library_).first->second;
      stage.set_ground(&scene_.terrain);
      stage.set_obstacles(has_obstacles_ ? &obstacles_ : nullptr);
      renderer_.add_skeleton(library_.skeleton.parents, stage.update(a.state, dt, a.frame_alpha),
                             glm::mix(colour, kFlashColour, flash));
    }
    if (colour == kOwnColour) {
      const Placement root = playback_root(library_, a.state);
      own_pos = root.pos_m;
      own_heading = root.heading_rad;
      own_seen = true;
    }
  }
}

const ShownAvatar* Session::shown_avatar(uint32_t id) const {
  const auto it = std::lower_bound(shown_.begin(), shown_.end(), id,
                                   [](const ShownAvatar& a, uint32_t v) { return a.id < v; });
  return it != shown_.end() && it->id == id ? &*it : nullptr;
}

// The fighters from their streamed poses on their own morphologies' skeletons (crimson, brighter
// while striking, white while flashing from a hit they took), then the strike markers.
void Session::draw_fighters(double t) {
  for (const FighterPoseSample& f : shown_fighters_) {
    if (!fighter_joint_positions(morphologies_, f, fighter_local_pos_, fighter_global_pos_, fighter_global_rot_))
      continue;
    const ShownAvatar* a = shown_avatar(f.avatar);
    const bool striking = a != nullptr && (a->flags & protocol::kAvatarStriking);
    const vec3 colour = glm::mix(striking ? kStrikingColour : kFighterColour, kFlashColour,
                                 strikes_.target_flash(f.avatar, t));
    const Morphology& m = morphologies_[f.morphology];
    renderer_.add_skeleton(m.skeleton.parents, fighter_global_pos_, colour, std::sqrt(m.height_m / 1.75f));
  }
  strikes_.for_each_marker(t, [this](const StrikeMarker& m, float age) {
    renderer_.add_marker(m.pos_m, kMarkerSizeM * (1.0f - 0.5f * age), m.hit ? kHitMarkerColour : kMissMarkerColour);
  });
}

// Terrain avatars from their streamed bodies on the default skeleton, coloured as the others.
void Session::draw_terrain_avatars(double t, vec2& own_pos, float& own_heading, bool& own_seen) {
  terrain_.sample(buffer_.render_time(t), shown_terrain_);
  const uint32_t own_id = connection_.accept().avatar;
  const Morphology& m = morphologies_.back();
  for (const FighterPoseSample& a : shown_terrain_) {
    if (!fighter_joint_positions(morphologies_, a, fighter_local_pos_, fighter_global_pos_, fighter_global_rot_))
      continue;
    const bool own = a.avatar == own_id;
    renderer_.add_skeleton(m.skeleton.parents, fighter_global_pos_, own ? kOwnColour : kOtherColour, 1.0f);
    if (own) {
      own_pos = ground(a.pelvis_m);
      own_heading = heading_of(a.local_rot[0] * vec3(0.0f, 0.0f, 1.0f));
      own_seen = true;
    }
  }
}

// Key T (edge-triggered, polled) toggles the overlay; while on, the tree is asked for every
// kTreeRequestIntervalS and the newest summary drawn (tree_overlay.hpp).
void Session::tree_overlay_step(double t) {
  const bool down = glfwGetWindowAttrib(window_, GLFW_FOCUSED) && glfwGetKey(window_, GLFW_KEY_T) == GLFW_PRESS;
  if (down && !tree_key_down_) tree_overlay_ = !tree_overlay_;
  tree_key_down_ = down;
  if (!tree_overlay_ || !connection_.connected()) return;
  if (t >= next_tree_request_s_) {
    connection_.request_tree();
    next_tree_request_s_ = t + kTreeRequestIntervalS;
  }
  const protocol::TreeView& tree = connection_.tree();
  if (connection_.tree_count() == 0 || tree.avatar != connection_.accept().avatar) return;
  add_tree_overlay(renderer_, library_, tree, scene_.terrain.floor_y_m, ghosts_);
}

bool Session::frame(int& status) {
  const Clock::time_point now = Clock::now();
  const double t = std::chrono::duration<double>(now - start_).count();
  const auto dt = static_cast<float>(t - last_frame_s_);
  last_frame_s_ = t;
  glfwPollEvents();
  if (glfwWindowShouldClose(window_)) {
    connection_.disconnect();
    status = 0;
    return false;
  }
  connection_step(now, t);

  vec2 own_pos = scene_.spawns.empty() ? vec2(0.0f) : scene_.spawns[0].pos_m;
  float own_heading = scene_.spawns.empty() ? 0.0f : scene_.spawns[0].heading_rad;
  bool own_seen = false;
  draw_avatars(t, own_pos, own_heading, own_seen);
  draw_fighters(t);
  draw_terrain_avatars(t, own_pos, own_heading, own_seen);
  tree_overlay_step(t);
  rig_.update(own_pos, own_heading, dt);
  if (connection_.connected()) {
    if (options_.script) {  // --script: the recording steers, the keyboard is ignored
      const double script_t = t - connected_at_s_;
      connection_.set_input(script_input_at(*options_.script, script_t));
      if (script_ended(*options_.script, script_t) && !script_end_reported_) {
        std::fprintf(stderr, "foresight-client: script ended after %.1f s; input is stop\n", script_t);
        script_end_reported_ = true;
      }
    } else {
      // Keys go to ImGui instead only while one of its widgets is active; a left-button drag
      // steers while held, through the same mapping (client_input.hpp).
      update_drag(window_, overlay_.wants_mouse(), drag_);
      const HeldKeys keys = overlay_.wants_keyboard() ? HeldKeys{} : held_keys(window_);
      connection_.set_input(control_from_input(keys, drag_, rig_.yaw_rad()));
    }
  }

  // --resize-at-s: resize the window as a person dragging its border would (tests: the next
  // frames and the screenshot follow the new size).
  if (options_.resize_at_s > 0 && !resized_ && connection_.connected() && t - connected_at_s_ >= options_.resize_at_s) {
    glfwSetWindowSize(window_, options_.resize_width, options_.resize_height);
    std::fprintf(stderr, "foresight-client: resized the window to %dx%d\n", options_.resize_width,
                 options_.resize_height);
    resized_ = true;
  }
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);  // follows resizes
  if (width > 0 && height > 0) {                     // 0: minimised, nothing to draw
    renderer_.draw(width, height, rig_.view(),
                   rig_.projection(static_cast<float>(width) / static_cast<float>(height)));
    FightFigures fight;
    fight.fighters = static_cast<int>(shown_fighters_.size());
    fight.hits_taken = strikes_.hits_taken();
    fight.dodged = strikes_.dodged();
    fight.hit_flash = strikes_.own_hit_flash(t);
    overlay_.frame(connection_, t, tree_overlay_, fight);
  }

  if (!options_.screenshot_path.empty()) {
    // Count only frames that show the player among received snapshots.
    // With the tree overlay on, also wait for the first tree summary.
    // With --screenshot-at-s, the shot waits for that much time since connecting instead.
    const bool ready = own_seen && buffer_.size() >= 2 && (!tree_overlay_ || connection_.tree_count() > 0);
    if (ready) ++shot_frames_;
    // A strip's later frames follow the first by strip_interval_s each (by a frame each when
    // counting frames).
    const bool shoot =
        options_.screenshot_at_s > 0
            ? ready && connection_.connected() &&
                  t - connected_at_s_ >= options_.screenshot_at_s + strip_.frames() * options_.strip_interval_s
            : shot_frames_ >= options_.frames + strip_.frames();
    if (shoot) {
      glReadBuffer(GL_BACK);
      std::vector<uint8_t> rgb;
      read_framebuffer(width, height, rgb);
      strip_.add(width, height, std::move(rgb));
    }
    if (shoot && strip_.frames() >= options_.strip_frames) {
      std::string error;
      if (!strip_.write_png(options_.screenshot_path, error)) {
        std::fprintf(stderr, "foresight-client: %s\n", error.c_str());
        status = 1;
      } else {
        std::fprintf(stderr, "foresight-client: wrote %s (%d frame(s) of %dx%d, %zu avatars, %zu fighters)\n",
                     options_.screenshot_path.c_str(), strip_.frames(), width, height, shown_.size(),
                     shown_fighters_.size());
        status = 0;
      }
      connection_.disconnect();
      return false;
    }
    if (t > options_.screenshot_timeout_s) {
      std::fprintf(stderr, "foresight-client: no snapshots of our avatar after %.0f s (%s); no screenshot\n",
                   t, connection_.status_message().c_str());
      status = 1;
      return false;
    }
  }
  glfwSwapBuffers(window_);
  const double spent = std::chrono::duration<double>(Clock::now() - now).count();
  if (spent < kMinFrameS) std::this_thread::sleep_for(std::chrono::duration<double>(kMinFrameS - spent));
  return true;
}

}  // namespace

int client_run(const MotionLibrary& library, const ClientOptions& options, const std::atomic<bool>* stop) {
  glfwSetErrorCallback(on_glfw_error);
  if (!glfwInit()) {
    std::fprintf(stderr, "foresight-client: cannot initialise GLFW (no display? try xvfb-run -a)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "Foresight", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "foresight-client: cannot open an OpenGL 3.3 core window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.screenshot_path.empty() ? 1 : 0);
  int status = 0;
  {
    auto session = std::make_unique<Session>(window, library, options);
    std::string error;
    if (!session->init(error)) {
      std::fprintf(stderr, "foresight-client: %s\n", error.c_str());
      status = 1;
    } else {
      std::fprintf(stderr, "foresight-client: OpenGL %s (%s)\n",
                   reinterpret_cast<const char*>(glGetString(GL_VERSION)),
                   reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
      while (!(stop && stop->load()) && session->frame(status)) {
      }
    }
  }  // GL objects go while the context is still current
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}

}  // namespace foresight::client
