#include "strike_feedback.hpp"

#include <algorithm>

namespace foresight::client {

void StrikeFeedback::add(std::span<const protocol::StrikeEventInfo> events, uint32_t own_avatar, double t_s) {
  const double start = t_s + config_.show_delay_s;
  for (const protocol::StrikeEventInfo& e : events) {
    ++strikes_;
    markers_[static_cast<size_t>(marker_next_)] = {e.effector_m, start, e.hit, e.kick};
    marker_next_ = (marker_next_ + 1) % kMaxMarkers;
    marker_count_ = std::min(marker_count_ + 1, kMaxMarkers);
    if (e.hit) {
      flashes_[static_cast<size_t>(flash_next_)] = {e.target, start};
      flash_next_ = (flash_next_ + 1) % kMaxFlashes;
      flash_count_ = std::min(flash_count_ + 1, kMaxFlashes);
    }
    if (e.target != own_avatar || own_avatar == 0) continue;
    if (e.hit) {
      ++hits_taken_;
      own_flash_start_s_ = start;
    } else {
      ++dodged_;
    }
  }
}

void StrikeFeedback::clear_effects() {
  marker_count_ = marker_next_ = 0;
  flash_count_ = flash_next_ = 0;
  own_flash_start_s_ = -1e9;
}

float StrikeFeedback::flash_strength(double start_s, double t_s) const {
  const double age = t_s - start_s;
  if (age < 0.0 || age >= config_.flash_s) return 0.0f;
  return static_cast<float>(1.0 - age / config_.flash_s);
}

float StrikeFeedback::own_hit_flash(double t_s) const { return flash_strength(own_flash_start_s_, t_s); }

float StrikeFeedback::target_flash(uint32_t id, double t_s) const {
  float strength = 0.0f;
  for (int i = 0; i < flash_count_; ++i) {
    const Flash& f = flashes_[static_cast<size_t>(i)];
    if (f.target == id) strength = std::max(strength, flash_strength(f.start_s, t_s));
  }
  return strength;
}

int StrikeFeedback::markers_showing(double t_s) const {
  int n = 0;
  for_each_marker(t_s, [&n](const StrikeMarker&, float) { ++n; });
  return n;
}

}  // namespace foresight::client
