#pragma once
// The responsiveness measure (docs/LAB.md), for any point that moves on the ground: per command-
// direction change (a command more than 30 deg from the last one followed, or a command after a
// stop), the time until the point's velocity over the last ~0.2 s is within 30 deg of it and
// above 0.2 m/s. ReplayRun measures the root with it; the motion-quality bench also measures the
// shown pose's pelvis, which is what a player sees answer.
#include "math/types.hpp"

#include <cstdint>
#include <vector>

namespace foresight {

/// One command-direction change the avatar followed (ReplayResult::responses).
struct Response {
  double at_s = 0;          ///< Display time of the change.
  double ms = 0;            ///< Until the velocity was within 30 deg of the command.
  float change_deg = 0;     ///< Angle from the command before; 180 for a command after a stop.
  int segment_at_change = -1;    ///< Segment playing when the command changed.
  int segment_at_response = -1;  ///< Segment playing when the avatar followed.
  bool operator==(const Response&) const = default;
};

class ResponseMeter {
 public:
  explicit ResponseMeter(double frame_interval_s);

  /// One display frame at `t_s`: the commanded world direction (zero: none), where the measured
  /// point is, the segment playing (kept in the responses). True when a change was followed on
  /// this frame: last() is its response. Changes superseded or cancelled (no command) before
  /// they are followed are not counted.
  bool frame(double t_s, vec2 command, vec2 position, int segment);
  const Response& last() const { return pending_; }
  /// Mean angle between the command and the velocity over frames with both (speed > 0.2 m/s).
  double mean_command_angle_deg() const;

 private:
  double frame_interval_s_;
  int window_ = 6;                  ///< Display frames in ~0.2 s.
  std::vector<vec2> recent_;        ///< The last window_ + 1 positions, a ring.
  int64_t frames_ = 0;
  double angle_sum_deg_ = 0;
  int64_t angle_frames_ = 0;
  vec2 reference_dir_{0.0f};
  bool pending_response_ = false;
  Response pending_;
};

}  // namespace foresight
