// foresight-client: the interactive client (docs/CLIENT.md).
//   foresight-client --server 127.0.0.1:7777 [--motions DIR] [--delay-ms 100]
//                    [--screenshot out.png --frames N | --screenshot-at-s S] [--tree-overlay]
//                    [--follow-camera] [--script recording.json] [--resize-at-s S --resize-to WxH]
// Arrows / WASD (or a left-button drag) steer in camera space, C crouches, F toggles the follow
// camera, T the feasible-motion-tree overlay, Escape quits.
#include "client_app.hpp"

#include "library_build/library_source.hpp"
#include "library_build/motion_source_cli.hpp"
#include "transport/impairment_cli.hpp"

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <utility>

namespace {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }

}  // namespace

int main(int argc, char** argv) {
  using namespace foresight;
  CLI::App app{"foresight-client: see and steer your avatar on a Foresight server"};
  client::ClientOptions options;
  options.server_text = "127.0.0.1:7777";
  double delay_ms = 100;
  app.add_option("--server", options.server_text, "Server address host:port")->capture_default_str();
  app.add_option("--scene", options.scene_path,
                 "Our copy of the server's scene file (default: data/scenes/<its name>.json); fetched from "
                 "the server when missing or different");
  app.add_option("--name", options.name, "Player name sent to the server")->capture_default_str();
  app.add_option("--delay-ms", delay_ms, "Interpolation delay behind the newest snapshot")
      ->check(CLI::Range(0.0, 2000.0))
      ->capture_default_str();
  protocol::add_impairment_options(app, options.impairment);
  app.add_option("--width", options.width, "Window width")->check(CLI::Range(64, 8192))->capture_default_str();
  app.add_option("--height", options.height, "Window height")->check(CLI::Range(64, 8192))->capture_default_str();
  app.add_flag("--tree-overlay", options.tree_overlay,
               "Start with the feasible-motion-tree overlay on (key T toggles it)");
  app.add_flag("--follow-camera", options.follow_camera, "Start with the follow camera on (key F toggles it)");
  app.add_option("--follow-distance-m", options.follow_distance_m,
                 "The follow camera's distance behind the avatar (default 4.5; its height follows)")
      ->check(CLI::Range(0.5f, 50.0f));
  app.add_flag("--no-overlay", options.hide_overlay, "Start with the debug overlay hidden (key F1 toggles it)");
  std::string script_path;
  app.add_option("--script", script_path,
                 "Steer from this recording (docs/RECORDINGS.md format) instead of the keyboard, "
                 "from the moment the client is connected; stop once it ends");
  app.add_option("--screenshot", options.screenshot_path,
                 "Render --frames frames once our avatar shows, write this PNG and exit");
  app.add_option("--frames", options.frames, "Frames before the screenshot")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--screenshot-at-s", options.screenshot_at_s,
                 "Screenshot mode: take the shot this many seconds after connecting (instead of --frames)")
      ->check(CLI::Range(0.0, 100000.0));
  app.add_option("--strip", options.strip_frames,
                 "Screenshot mode: this many frames side by side in the PNG, --strip-interval-s apart "
                 "from --screenshot-at-s (else consecutive frames)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--strip-interval-s", options.strip_interval_s, "Time between the frames of a --strip")
      ->check(CLI::Range(0.0, 60.0))
      ->capture_default_str();
  app.add_option("--timeout", options.screenshot_timeout_s,
                 "Screenshot mode: give up (exit 1) after this many seconds")
      ->capture_default_str();
  std::string resize_to;
  app.add_option("--resize-at-s", options.resize_at_s,
                 "Resize the window (to --resize-to) this many seconds after connecting")
      ->check(CLI::Range(0.0, 100000.0));
  app.add_option("--resize-to", resize_to, "New window size for --resize-at-s, WxH (e.g. 960x540)");
  // The same library options as the server: the library's content hash must match its own.
  MotionSource source;
  add_motion_source_options(app, source);
  CLI11_PARSE(app, argc, argv);
  options.delay_s = delay_ms / 1000.0;

  std::string error;
  if (!protocol::parse_endpoint(options.server_text, options.server, error)) {
    std::fprintf(stderr, "foresight-client: --server: %s\n", error.c_str());
    return 1;
  }
  if (options.resize_at_s > 0 || !resize_to.empty()) {
    char x = 0, rest = 0;
    if (options.resize_at_s <= 0 ||
        std::sscanf(resize_to.c_str(), "%d%c%d%c", &options.resize_width, &x, &options.resize_height, &rest) != 3 ||
        (x != 'x' && x != 'X') || options.resize_width < 64 || options.resize_height < 64 ||
        options.resize_width > 8192 || options.resize_height > 8192) {
      std::fprintf(stderr, "foresight-client: --resize-at-s S and --resize-to WxH go together "
                           "(W and H 64..8192), got '%s'\n", resize_to.c_str());
      return 1;
    }
  }
  if (!script_path.empty()) {
    Recording script;
    if (!recording_load(script_path, script, error)) {
      std::fprintf(stderr, "foresight-client: --script: %s\n", error.c_str());
      return 1;
    }
    options.script = std::move(script);
  }
  MotionLibrary library;
  if (!motion_library_load(source, library, error)) {
    std::fprintf(stderr, "foresight-client: %s\n", error.c_str());
    return 1;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  return client::client_run(library, options, &g_stop);
}
