#include "client_app.hpp"

#include "avatar_decode.hpp"
#include "camera_rig.hpp"
#include "client_input.hpp"
#include "debug_overlay.hpp"
#include "renderer.hpp"
#include "screenshot.hpp"
#include "script_input.hpp"
#include "snapshot_buffer.hpp"

#include "library/playback.hpp"
#include "protocol/client_connection.hpp"
#include "protocol/protocol.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>

namespace foresight::client {

namespace {

using Clock = std::chrono::steady_clock;

constexpr vec3 kOwnColour{1.0f, 0.55f, 0.10f};    // orange: the player
constexpr vec3 kOtherColour{0.25f, 0.45f, 0.85f}; // blue: everyone else
constexpr vec3 kNpcColour{0.60f, 0.30f, 0.70f};
constexpr vec3 kStoppedColour{0.70f, 0.30f, 0.30f};  // idle fallback: nothing feasible ahead
/// Least time between two Inputs: the server ticks at 30 Hz, the window may draw far faster.
constexpr std::chrono::milliseconds kInputInterval{30};
constexpr double kMinFrameS = 1.0 / 240.0;  ///< Frame cap when vsync does not throttle.
/// Tree overlay (paper Fig. 5): how often the tree is asked for, and how it is drawn.
constexpr double kTreeRequestIntervalS = 0.2;
constexpr vec3 kTreeColour{0.10f, 0.85f, 0.85f};    // cyan: the sampled tree
constexpr vec3 kChosenColour{1.00f, 0.95f, 0.10f};  // yellow: the branch the tree would take now
constexpr float kTreeLineM = 0.06f, kChosenLineM = 0.12f;
/// A square outline (side) around each chosen node's end: idle clips end where they start, and
/// the choice still shows around a standing avatar's feet.
constexpr float kChosenMarkM = 0.60f;
constexpr float kTreeLiftM = 0.06f;  ///< Above the floor, so the floor never hides the lines.

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
      : window_(window), library_(library), options_(options), connection_(connection_config()),
        buffer_(buffer_config(options)) {
    tree_overlay_ = options.tree_overlay;
    if (options.follow_camera) rig_.toggle_follow();
    shown_.reserve(256);
    entries_.reserve(256);
    glfwSetWindowUserPointer(window_, &rig_);
    glfwSetKeyCallback(window_, on_key);
  }

  // The overlay after the constructor set our GLFW callbacks: ImGui chains to them.
  bool init(std::string& error) { return renderer_.init(error) && overlay_.init(window_, error); }

  /// One frame. Returns false when the program should end (exit status in `status`).
  bool frame(int& status);

 private:
  static protocol::ClientConfig connection_config() {
    protocol::ClientConfig c;
    c.min_input_interval = kInputInterval;
    return c;
  }
  static SnapshotBufferConfig buffer_config(const ClientOptions& o) {
    SnapshotBufferConfig c;
    c.delay_s = o.delay_s;
    return c;
  }
  void connection_step(Clock::time_point now, double t);
  void on_connected();
  void draw_avatars(double t, vec2& own_pos, float& own_heading, bool& own_seen);
  void tree_overlay_step(double t);

  GLFWwindow* window_;
  const MotionLibrary& library_;
  const ClientOptions& options_;
  protocol::ClientConnection connection_;
  SnapshotBuffer buffer_;
  CameraRig rig_;
  Renderer renderer_;
  DebugOverlay overlay_;  ///< F1; drawn over the scene (also in screenshots).
  Scene scene_;
  std::string scene_name_;
  Clock::time_point start_ = Clock::now();
  double last_frame_s_ = 0;

  bool started_ = false, was_connected_ = false, reported_down_ = false;
  double next_attempt_s_ = 0;
  uint32_t last_tick_ = 0;
  int last_parts_ = -1;
  uint64_t rejected_ = 0;
  int shot_frames_ = 0;
  bool tree_overlay_ = false, tree_key_down_ = false;
  double next_tree_request_s_ = 0;
  double connected_at_s_ = 0;  ///< When the connection was last made (the script's time 0).
  bool script_end_reported_ = false;

  std::vector<AvatarEntry> entries_;
  std::vector<ShownAvatar> shown_;
};

void Session::on_connected() {
  const auto& a = connection_.accept();
  std::fprintf(stderr, "foresight-client: connected to %s: scene '%s', avatar %u, %u Hz ticks\n",
               options_.server_text.c_str(), a.scene.c_str(), a.avatar, a.tick_hz);
  if (a.scene == scene_name_) return;
  std::string error;
  Scene scene;
  if (!scene_load(scene_path(a.scene), scene, error)) {
    // Still playable: avatars on an empty floor.
    std::fprintf(stderr, "foresight-client: cannot load scene '%s' (%s): drawing avatars only\n",
                 a.scene.c_str(), error.c_str());
    scene = Scene{};
    scene.bounds = {vec2(-20.0f), vec2(20.0f)};
  }
  scene_ = std::move(scene);
  scene_name_ = a.scene;
  rig_.set_scene(&scene_);
  renderer_.set_scene(scene_);
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
    buffer_.push(static_cast<double>(last_tick_) / connection_.accept().tick_hz, t, entries_);
  }
}

void Session::draw_avatars(double t, vec2& own_pos, float& own_heading, bool& own_seen) {
  renderer_.begin_frame();
  buffer_.sample(library_, buffer_.render_time(t), shown_);
  const uint32_t own_id = connection_.accept().avatar;
  for (const ShownAvatar& a : shown_) {
    const vec3 colour = colour_of(a, own_id);
    renderer_.add_avatar(library_, a.state, a.frame_alpha, colour);
    if (colour == kOwnColour) {
      const Placement root = playback_root(library_, a.state);
      own_pos = root.pos_m;
      own_heading = root.heading_rad;
      own_seen = true;
    }
  }
}

// Key T (edge-triggered, polled) toggles the overlay; while on, the tree is asked for every
// kTreeRequestIntervalS and the newest summary drawn: a line from each sampled node's parent end
// to its own end (the root's from where it started), the chosen branch thicker and in yellow with
// a square outline around each of its nodes' ends.
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
  const float y = scene_.terrain.floor_y_m + kTreeLiftM;
  const auto at = [y](vec2 ground) { return vec3(ground.x, y, ground.y); };
  // Ordinary nodes first, the chosen branch after: where they overlap the highlight wins.
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < tree.size(); ++i) {
      if ((tree.chosen[i] != 0) != (pass == 1)) continue;
      const vec2 from = tree.parent[i] == protocol::kTreeNoParent ? tree.origin_m : tree.end_m[tree.parent[i]];
      renderer_.add_line(at(from), at(tree.end_m[i]), pass == 1 ? kChosenLineM : kTreeLineM,
                         pass == 1 ? kChosenColour : kTreeColour);
      if (pass == 1) {  // a square outline around the end
        const vec3 c = at(tree.end_m[i]);
        const float h = 0.5f * kChosenMarkM;
        const vec3 corners[4] = {c + vec3(-h, 0, -h), c + vec3(h, 0, -h), c + vec3(h, 0, h), c + vec3(-h, 0, h)};
        for (int k = 0; k < 4; ++k) renderer_.add_line(corners[k], corners[(k + 1) % 4], kTreeLineM, kChosenColour);
      }
    }
  }
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
      // Keys go to ImGui instead only while one of its widgets is active.
      connection_.set_input(control_from_keys(overlay_.wants_keyboard() ? HeldKeys{} : held_keys(window_), rig_.yaw_rad()));
    }
  }

  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);  // follows resizes
  if (width > 0 && height > 0) {                     // 0: minimised, nothing to draw
    renderer_.draw(width, height, rig_.view(),
                   rig_.projection(static_cast<float>(width) / static_cast<float>(height)));
    overlay_.frame(connection_, t, tree_overlay_);
  }

  if (!options_.screenshot_path.empty()) {
    // Count only frames that show the player among received snapshots.
    // With the tree overlay on, also wait for the first tree summary.
    // With --screenshot-at-s, the shot waits for that much time since connecting instead.
    const bool ready = own_seen && buffer_.size() >= 2 && (!tree_overlay_ || connection_.tree_count() > 0);
    if (ready) ++shot_frames_;
    const bool shoot = options_.screenshot_at_s > 0
                           ? ready && connection_.connected() && t - connected_at_s_ >= options_.screenshot_at_s
                           : shot_frames_ >= options_.frames;
    if (shoot) {
      std::string error;
      glReadBuffer(GL_BACK);
      if (!write_framebuffer_png(options_.screenshot_path, width, height, error)) {
        std::fprintf(stderr, "foresight-client: %s\n", error.c_str());
        status = 1;
      } else {
        std::fprintf(stderr, "foresight-client: wrote %s (%dx%d, %zu avatars)\n",
                     options_.screenshot_path.c_str(), width, height, shown_.size());
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
