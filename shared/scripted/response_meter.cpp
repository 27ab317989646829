#include "scripted/response_meter.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {
namespace {

constexpr float kMovingSpeed_mps = 0.2f;   // slower counts as standing (sway, idle shuffle)
constexpr float kFollowAngle_deg = 30.0f;  // "within 30 deg" of the paper-free responsiveness metric
constexpr double kVelocityWindow_s = 0.2;

float angle_between_deg(vec2 a, vec2 b) {
  const float la = glm::length(a), lb = glm::length(b);
  if (la <= 0.0f || lb <= 0.0f) return 0.0f;
  return degrees(std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f)));
}

}  // namespace

ResponseMeter::ResponseMeter(double frame_interval_s) : frame_interval_s_(frame_interval_s) {
  window_ = std::max(1, static_cast<int>(std::lround(kVelocityWindow_s / frame_interval_s)));
  recent_.resize(static_cast<size_t>(window_) + 1);
}

bool ResponseMeter::frame(double t_s, vec2 command, vec2 position, int segment) {
  const size_t ring = recent_.size();
  recent_[static_cast<size_t>(frames_) % ring] = position;
  ++frames_;
  vec2 velocity(0.0f);
  if (frames_ > window_) {
    const double window_s = window_ * frame_interval_s_;
    velocity = (position - recent_[static_cast<size_t>(frames_ - 1 - window_) % ring]) / static_cast<float>(window_s);
  }
  const bool moving = glm::length(velocity) > kMovingSpeed_mps;

  if (glm::length(command) <= 1e-4f) {
    pending_response_ = false;
    reference_dir_ = vec2(0.0f);
    return false;
  }
  if (moving) {
    angle_sum_deg_ += angle_between_deg(command, velocity);
    ++angle_frames_;
  }
  if (reference_dir_ == vec2(0.0f) || angle_between_deg(command, reference_dir_) > kFollowAngle_deg) {
    pending_ = Response{};
    pending_.at_s = t_s;
    pending_.change_deg = reference_dir_ == vec2(0.0f) ? 180.0f : angle_between_deg(command, reference_dir_);
    pending_.segment_at_change = segment;
    reference_dir_ = command;
    pending_response_ = true;
  }
  if (pending_response_ && moving && angle_between_deg(command, velocity) <= kFollowAngle_deg) {
    pending_.ms = (t_s - pending_.at_s) * 1000.0;
    pending_.segment_at_response = segment;
    pending_response_ = false;
    return true;
  }
  return false;
}

double ResponseMeter::mean_command_angle_deg() const {
  return angle_frames_ > 0 ? angle_sum_deg_ / static_cast<double>(angle_frames_) : 0.0;
}

}  // namespace foresight
