#pragma once
// What the client shows of NPC fighters' strikes (docs/CLIENT.md "Fighters"): each strike event
// (ClientConnection::take_strike_events, each once) becomes
//   - a marker at the effector's position for marker_s (every hit and miss, whoever the target),
//   - a white flash of the target avatar for flash_s when it was hit,
//   - a red tint of the screen's edges for flash_s when the target is the local player and it was
//     hit,
// and counts in the debug overlay: hits taken and strikes dodged (missed) by the local player.
// Effects start `show_delay_s` after the event arrives: the avatars are drawn that far behind the
// newest snapshot (the interpolation delay), so the flash lands with the strike as drawn.
//
// Pure logic, fixed capacity (a ring of markers and of flashing targets), no allocation.
#include "transport/client_connection.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace foresight::client {

struct StrikeFeedbackConfig {
  double show_delay_s = 0.100;  ///< Usually the interpolation delay.
  double flash_s = 0.3;         ///< Hit flash (target white, screen edges red when it is us).
  double marker_s = 1.0;        ///< Effector marker.
};

/// One effector marker: where the fist or foot was at the hit frame.
struct StrikeMarker {
  vec3 pos_m{0.0f};
  double start_s = 0;  ///< Local time it appears.
  bool hit = false;
  bool kick = false;
};

class StrikeFeedback {
 public:
  static constexpr int kMaxMarkers = 32;  ///< The newest kept when more are alive.
  static constexpr int kMaxFlashes = 16;

  explicit StrikeFeedback(const StrikeFeedbackConfig& config = {}) : config_(config) {}

  /// Events that arrived at local time `t_s`; `own_avatar` is the local player's avatar id.
  void add(std::span<const protocol::StrikeEventInfo> events, uint32_t own_avatar, double t_s);
  /// Forgets markers and flashes; the counters stay (they count the whole run).
  void clear_effects();

  /// Red screen-edge tint for the local player being hit, 0..1 (1 as the flash starts, 0 once
  /// over).
  float own_hit_flash(double t_s) const;
  /// White flash of avatar `id` when it was hit, 0..1.
  float target_flash(uint32_t id, double t_s) const;
  /// Calls f(marker, age 0..1) for every marker showing at `t_s`.
  template <class F>
  void for_each_marker(double t_s, F&& f) const {
    for (int i = 0; i < marker_count_; ++i) {
      const StrikeMarker& m = markers_[static_cast<size_t>(i)];
      const double age = t_s - m.start_s;
      if (age >= 0.0 && age < config_.marker_s) f(m, static_cast<float>(age / config_.marker_s));
    }
  }
  int markers_showing(double t_s) const;

  uint64_t strikes_seen() const { return strikes_; }
  uint64_t hits_taken() const { return hits_taken_; }  ///< Strikes at the local player that hit.
  uint64_t dodged() const { return dodged_; }          ///< Strikes at the local player that missed.
  const StrikeFeedbackConfig& config() const { return config_; }

 private:
  struct Flash {
    uint32_t target = 0;
    double start_s = 0;
  };
  float flash_strength(double start_s, double t_s) const;

  StrikeFeedbackConfig config_;
  std::array<StrikeMarker, kMaxMarkers> markers_{};
  int marker_count_ = 0, marker_next_ = 0;
  std::array<Flash, kMaxFlashes> flashes_{};
  int flash_count_ = 0, flash_next_ = 0;
  double own_flash_start_s_ = -1e9;
  uint64_t strikes_ = 0, hits_taken_ = 0, dodged_ = 0;
};

}  // namespace foresight::client
