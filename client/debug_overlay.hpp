#pragma once
// The debug overlay (docs/CLIENT.md, key F1): a Dear ImGui window with the connection's figures
// (state, ping, snapshot loss, bandwidth, snapshot interval), the server's (tick time, overruns,
// players, tree size, from ServerStats asked for once a second while the window shows) and the
// client's frame time, plus a connection-quality dot that stays in the corner when the window is
// hidden. The pure parts (quality classification, the loss and bandwidth meter) are separate so
// tests reach them without a window.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

struct GLFWwindow;

namespace foresight::protocol {
class ClientConnection;
}

namespace foresight::client {

/// Connection quality, the corner dot's colour: green, yellow, red.
enum class LinkQuality : uint8_t { kGood, kFair, kPoor };
const char* link_quality_name(LinkQuality quality);

/// Where green ends and red begins. RTT is the client's measure (snapshot arrival minus the input
/// time it echoes), so it includes up to one snapshot interval of waiting at the server: 100 ms is
/// a fast link at 30 snapshots a second. Loss is the share of snapshot ticks that never arrived.
struct QualityThresholds {
  double good_rtt_ms = 100;   ///< Green: RTT below this and loss below good_loss.
  double good_loss = 0.02;
  double fair_rtt_ms = 250;   ///< Yellow: RTT below this and loss below fair_loss; else red.
  double fair_loss = 0.10;
};

/// Green / yellow / red from RTT (ms) and loss (0..1). Not connected, or no RTT sample yet
/// (rtt_ms <= 0): red.
LinkQuality classify_link(bool connected, double rtt_ms, double loss, const QualityThresholds& limits = {});

/// The connection's counters at one moment (ClientConnection: snapshot_tick(), snapshot_ticks(),
/// bytes_received(), bytes_sent()).
struct LinkSample {
  double t_s = 0;
  uint32_t newest_snapshot = 0;     ///< Newest snapshot number seen (Snapshot::tick: one per snapshot).
  uint64_t snapshots_received = 0;  ///< New snapshots seen so far.
  uint64_t bytes_down = 0, bytes_up = 0;
};

/// Loss and bandwidth from samples taken about once a second: loss over the last kWindow samples
/// (snapshots received against those the numbers say were sent: the server numbers every
/// snapshot; late or reordered ones count as lost, as the client drops them), bandwidth over the
/// last interval. A counter that goes back (reconnect) restarts the meter. Fixed size, never
/// allocates.
class LinkMeter {
 public:
  static constexpr int kWindow = 6;  ///< Samples: 5 intervals.

  void reset() { count_ = 0; }
  void add(const LinkSample& sample);
  /// Share of snapshots missing, 0..1 (0 until two samples span at least one snapshot).
  double loss() const { return loss_; }
  double down_kbit_s() const { return down_kbit_s_; }
  double up_kbit_s() const { return up_kbit_s_; }
  int samples() const { return count_; }

 private:
  const LinkSample& at(int i) const { return ring_[static_cast<size_t>((first_ + i) % kWindow)]; }

  std::array<LinkSample, kWindow> ring_{};
  int first_ = 0, count_ = 0;
  double loss_ = 0, down_kbit_s_ = 0, up_kbit_s_ = 0;
};

/// Exponentially smoothed frame time.
class FrameTimer {
 public:
  /// The time between this call and the previous one, folded in (the first call only starts).
  void tick(double t_s);
  double ms() const { return ms_; }
  double fps() const { return ms_ > 0 ? 1000.0 / ms_ : 0.0; }

 private:
  static constexpr double kSmoothing = 0.05;  ///< Weight of the newest frame.
  double last_s_ = -1, ms_ = 0;
};

/// NPC fighters' figures for the overlay (strike_feedback.hpp), and the hit flash to draw.
struct FightFigures {
  int fighters = 0;          ///< Fighters shown.
  uint64_t hits_taken = 0;   ///< Strikes at the local player that hit.
  uint64_t dodged = 0;       ///< Strikes at the local player that missed.
  float hit_flash = 0.0f;    ///< 0..1: red tint of the screen's edges (the local player was hit).
};

/// The overlay's fighters line: "fighters N, hits taken H, dodged M" (into `out`, size `n`).
void format_fight_line(const FightFigures& fight, char* out, size_t n);

/// The ImGui window. Lives while the window's GL context is current.
class DebugOverlay {
 public:
  DebugOverlay() = default;
  ~DebugOverlay();
  DebugOverlay(const DebugOverlay&) = delete;
  DebugOverlay& operator=(const DebugOverlay&) = delete;

  /// Creates the ImGui context and its GLFW / OpenGL 3 backends. Call after the application has
  /// set its own GLFW callbacks: ImGui's chain to them. False with a reason.
  bool init(GLFWwindow* window, std::string& error);
  void shutdown();
  bool initialised() const { return window_ != nullptr; }

  /// Once a frame, after the scene is drawn and before the buffer is read or swapped: polls F1,
  /// updates the figures, asks for ServerStats once a second while visible, draws the window (or
  /// only the quality dot). The checkbox edits `tree_overlay` (the key T flag). `fight` adds the
  /// fighters line and, while fight.hit_flash > 0, a red tint along the screen's edges (drawn
  /// with the window hidden too).
  void frame(protocol::ClientConnection& connection, double t_s, bool& tree_overlay,
             const FightFigures& fight = {});

  /// True while ImGui uses the keyboard (a widget of its window active): the game should then
  /// ignore held keys. False whenever its window is not focused.
  bool wants_keyboard() const;
  /// True while the mouse is over ImGui's window or one of its widgets holds it: a left-button
  /// press then goes to the overlay, not to drag steering.
  bool wants_mouse() const;
  bool visible() const { return visible_; }
  void set_visible(bool visible) { visible_ = visible; }
  LinkQuality quality() const { return quality_; }

 private:
  GLFWwindow* window_ = nullptr;
  bool visible_ = true, f1_down_ = false;
  double next_stats_request_s_ = 0, next_sample_s_ = 0;
  LinkMeter meter_;
  FrameTimer frame_timer_;
  LinkQuality quality_ = LinkQuality::kPoor;
};

}  // namespace foresight::client
