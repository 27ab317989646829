#include "anim/root_motion.hpp"

#include "anim/fk.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace foresight {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Side tokens, as (left, right) spellings; tried in order on the lower-cased name.
constexpr std::pair<std::string_view, std::string_view> kSideTokens[] = {
    {"left", "right"}, {"_l", "_r"}, {"l_", "r_"}, {".l", ".r"}, {"lft", "rgt"}};

struct SideToken {
  size_t at = std::string::npos;
  std::string_view found, other;
  bool left = false;
};

// The first side token in a lower-case name. Two-letter tokens ("_l", "l_") only count at the
// end/start of the name or next to a separator, so "hand_lower" is not a left joint.
SideToken find_side_token(const std::string& name) {
  for (auto [l, r] : kSideTokens) {
    for (int side = 0; side < 2; ++side) {
      const std::string_view from = side == 0 ? l : r, to = side == 0 ? r : l;
      const size_t at = name.find(from);
      if (at == std::string::npos) continue;
      const bool short_token = from.size() == 2;
      if (short_token && from[0] == '_' && at + 2 != name.size() && name[at + 2] != '_') continue;
      if (short_token && from[1] == '_' && at != 0 && name[at - 1] != '_') continue;
      return {at, from, to, side == 0};
    }
  }
  return {};
}

int depth_of(const Skeleton& s, int j) {
  int d = 0;
  while (s.parents[j] != kNoParent) j = s.parents[j], ++d;
  return d;
}

}  // namespace

int mirror_joint(const Skeleton& skeleton, int joint) {
  std::string name = lower(skeleton.joint_names[joint]);
  const SideToken token = find_side_token(name);
  if (token.at == std::string::npos) return joint;
  name.replace(token.at, token.found.size(), token.other);
  for (int j = 0; j < skeleton.num_joints(); ++j)
    if (lower(skeleton.joint_names[j]) == name) return j;
  return joint;
}

LeftRightPair find_left_right_pair(const Skeleton& skeleton) {
  // The shallowest leg pair: hip joints sit next to the pelvis and so are the most reliable
  // facing reference; shoulder and arm pairs are used only when there is no leg pair.
  LeftRightPair best;
  int best_depth = 1 << 30;
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    if (skeleton.is_end_site[j]) continue;
    const std::string name = lower(skeleton.joint_names[j]);
    if (!find_side_token(name).left) continue;
    const int m = mirror_joint(skeleton, j);
    if (m == j) continue;
    const bool upper_body = name.find("shoulder") != std::string::npos ||
                            name.find("clav") != std::string::npos ||
                            name.find("arm") != std::string::npos;
    const int depth = depth_of(skeleton, j) + (upper_body ? 100 : 0);
    if (depth < best_depth) best_depth = depth, best = {j, m};
  }
  return best;
}

vec3 find_forward_axis(const Skeleton& skeleton, const Clip& clip) {
  const int n = skeleton.num_joints();
  std::vector<vec3> pos(static_cast<size_t>(n));
  std::vector<quat> rot(static_cast<size_t>(n));
  fk_pose(skeleton, clip.frame_pos(0), clip.frame_rot(0), pos, rot);

  vec3 forward(0.0f);
  const LeftRightPair lr = find_left_right_pair(skeleton);
  if (lr.left >= 0) forward = glm::cross(pos[lr.left] - pos[lr.right], vec3(0, 1, 0));
  forward.y = 0.0f;
  if (glm::length(forward) < 1e-4f && clip.num_frames > 1) {
    forward = clip.frame_pos(clip.num_frames - 1)[0] - clip.frame_pos(0)[0];
    forward.y = 0.0f;
  }
  if (glm::length(forward) < 1e-4f) forward = vec3(0, 0, 1);
  // Express the world forward in the pelvis frame of frame 0: the axis then follows the pelvis.
  return glm::normalize(glm::inverse(rot[0]) * glm::normalize(forward));
}

void extract_root_track(const Clip& clip, vec3 forward_axis_local, std::vector<Placement>& track) {
  track.resize(static_cast<size_t>(clip.num_frames));
  float previous = 0.0f;
  for (int f = 0; f < clip.num_frames; ++f) {
    const vec3 forward = clip.frame_rot(f)[0] * forward_axis_local;
    // A pelvis pitched straight up or down has no heading: keep the previous one.
    float heading = glm::length(ground(forward)) > 1e-3f ? heading_of(forward) : previous;
    // Unwrap so headings are continuous within the clip (a 360 spin reads as 2 pi, not 0).
    if (f > 0) heading = previous + wrap_angle(heading - previous);
    track[static_cast<size_t>(f)] = {ground(clip.frame_pos(f)[0]), heading};
    previous = heading;
  }
}

}  // namespace foresight
