#pragma once
// The interactive client: a GLFW window, the connection to the server, the snapshot buffer, the
// cameras and the renderer, driven one frame at a time (docs/CLIENT.md).
#include "scripted/recording.hpp"
#include "transport/impairment.hpp"
#include "transport/udp_socket.hpp"

#include <atomic>
#include <optional>
#include <string>

namespace foresight {
struct MotionLibrary;
}

namespace foresight::client {

struct ClientOptions {
  protocol::Endpoint server;
  std::string server_text;  ///< As given (for messages).
  std::string name = "player";
  /// --scene PATH: our copy of the server's scene file (used when its hash is the server's; else
  /// the server's is fetched).
  std::string scene_path;
  int width = 1280, height = 720;
  double delay_s = 0.100;          ///< Interpolation delay.
  std::string screenshot_path;     ///< Non-empty: render `frames` frames, write a PNG, exit.
  int frames = 60;
  double screenshot_timeout_s = 30;  ///< Screenshot mode: give up when nothing arrives by then.
  double reconnect_interval_s = 2.0;
  bool tree_overlay = false;  ///< Start with the feasible-motion-tree overlay on (key T toggles).
  bool follow_camera = false;  ///< Start with the follow camera on (key F toggles).
  /// --script: the player's input comes from this recording (sample-and-hold from the moment the
  /// client is connected; stop once it ends), the keyboard's steering keys are ignored.
  std::optional<Recording> script;
  /// Screenshot mode: > 0 takes the shot this many seconds after connecting (instead of `frames`).
  double screenshot_at_s = 0;
  /// Screenshot mode: this many frames side by side in one PNG (1: a single shot),
  /// `strip_interval_s` apart from screenshot_at_s, else consecutive frames.
  int strip_frames = 1;
  bool hide_overlay = false;  ///< Start with the debug overlay (F1) hidden.
  float follow_distance_m = 0;  ///< The follow camera's distance behind the avatar (0: its default).
  double strip_interval_s = 0.25;
  /// --resize-at-s S --resize-to WxH: > 0 resizes the window to resize_width x resize_height this
  /// many seconds after connecting (tests resizing under Xvfb, where nobody drags a border).
  double resize_at_s = 0;
  int resize_width = 0, resize_height = 0;
  /// The link through the impairment layer (--loss, --latency-ms, ...: docs/RELIABILITY.md).
  protocol::ImpairmentConfig impairment;
};

/// Runs until the window closes, Escape, `stop` or (screenshot mode) the PNG is written.
/// Returns the process exit status: 0 fine, 1 on failure (reason on stderr).
int client_run(const MotionLibrary& library, const ClientOptions& options, const std::atomic<bool>* stop);

}  // namespace foresight::client
