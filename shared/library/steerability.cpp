#include "library/steerability.hpp"

#include <cmath>
#include <limits>

namespace foresight {
namespace {

float segment_speed(const MotionLibrary& lib, int s) {
  const Segment& seg = lib.graph.segments[static_cast<size_t>(s)];
  const float seconds = std::max(seg.num_frames(), 1) / lib.clips[static_cast<size_t>(seg.clip)].fps;
  return glm::length(lib.segment_motion[static_cast<size_t>(s)].end.pos_m) / seconds;
}

void walk(const MotionLibrary& lib, int segment, const Placement& at, int steps_left, float min_speed,
          std::array<bool, kCommandSectors>& out) {
  const SegmentMotion& m = lib.segment_motion[static_cast<size_t>(segment)];
  if (segment_speed(lib, segment) >= min_speed) {
    const vec2 travel = rotate_ground(m.end.pos_m, at.heading_rad);
    const float relative = wrap_angle(heading_of(travel));
    const int sector = static_cast<int>(std::lround(relative / radians(45.0f)) + kCommandSectors) % kCommandSectors;
    out[static_cast<size_t>(sector)] = true;
  }
  if (steps_left == 0) return;
  const Placement next = at.compose(m.end);
  for (const Transition& t : lib.graph.successors(segment)) walk(lib, t.to, next, steps_left - 1, min_speed, out);
}

}  // namespace

std::string_view command_sector_name(int sector) {
  static const char* const names[kCommandSectors] = {"forward", "forward-left", "left", "back-left",
                                                     "back", "back-right", "right", "forward-right"};
  return names[(sector % kCommandSectors + kCommandSectors) % kCommandSectors];
}

std::array<bool, kCommandSectors> followable_directions(const MotionLibrary& library, int start, int max_steps,
                                                        float min_speed_m_per_s) {
  std::array<bool, kCommandSectors> out{};
  if (start < 0 || start >= library.graph.num_segments()) return out;
  walk(library, start, Placement{}, max_steps, min_speed_m_per_s, out);
  return out;
}

int standing_segment(const MotionLibrary& lib) {
  int best = -1;
  float least = std::numeric_limits<float>::max();
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const uint32_t tags = lib.graph.segments[static_cast<size_t>(s)].tags;
    if (!(tags & kTagIdle) || (tags & kTagCrouch)) continue;
    const float moved = glm::length(lib.segment_motion[static_cast<size_t>(s)].end.pos_m) +
                        std::fabs(lib.segment_motion[static_cast<size_t>(s)].end.heading_rad);
    if (moved < least) least = moved, best = s;
  }
  return best;
}

int walking_segment(const MotionLibrary& lib) {
  int best = -1;
  float nearest = std::numeric_limits<float>::max();
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    if (!(lib.graph.segments[static_cast<size_t>(s)].tags & kTagLocomotion)) continue;
    const float d = std::fabs(segment_speed(lib, s) - 1.3f);
    if (d < nearest) nearest = d, best = s;
  }
  return best;
}

}  // namespace foresight
