#pragma once
// Shared helpers for the default-library tests: the library built once, forward kinematics, root
// placements, and the measurements the tests assert on (foot skate, transition continuity).
#include "author/default_library.hpp"
#include "anim/fk.hpp"
#include "anim/root_motion.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace foresight::author::testing {

/// Built once per test binary (building takes a fraction of a second, the checks read it often).
const DefaultLibrarySpec& library();
const AuthoredClip* find_clip(std::string_view name);
int joint(std::string_view name);

/// FK positions of every frame, [frame * J + joint].
std::vector<vec3> clip_positions(const Clip& clip);
/// Per-frame root placement, the way the motion graph extracts it.
std::vector<Placement> clip_root_track(const Clip& clip);

inline vec3 at(const std::vector<vec3>& pos, const Clip& clip, int frame, int joint_index) {
  return pos[static_cast<size_t>(frame) * clip.num_joints + joint_index];
}

/// Worst horizontal speed of a foot joint (ankle or ball) while it is in contact: within
/// kContactHeightM of its lowest height in the clip and moving vertically slower than
/// kContactVerticalMps, measured between consecutive frames. Why 4 cm/s: a heel rolling up about
/// the pinned ball moves the ankle 0.42 m forward per metre up (the ball sits 13 cm ahead of and
/// 5.5 cm below the ankle), so a rolling - not sliding - ankle just under the cut-off shows at most
/// 1.7 cm/s; anything over the 2 cm/s skate bound is then a real slide.
inline constexpr float kContactHeightM = 0.03f;
inline constexpr float kContactVerticalMps = 0.04f;
struct SkateReport {
  float worst_mps = 0.0f;
  std::string joint;
  int frame = -1;
  int contact_frames = 0;
};
SkateReport foot_skate(const Clip& clip);

/// Largest joint distance between A's last frame and B's first frame placed at A's last root
/// placement.
float transition_gap_m(const Clip& a, const Clip& b);

/// Clips played one after the other the way the motion graph plays them: each placed at the
/// previous one's last root placement, its last frame (the boundary pose) left to the next clip
/// (the final clip's is kept). World joint positions per frame [frame * J + joint] and root
/// placements per frame.
struct Chain {
  std::vector<vec3> pos;
  std::vector<Placement> root;
  int num_joints = 0;
  int num_frames = 0;
  vec3 at(int frame, int joint_index) const {
    return pos[static_cast<size_t>(frame) * num_joints + joint_index];
  }
};
Chain chain_clips(const std::vector<std::string>& names);

/// Highest point of the head top over the clip (metres) and its lowest.
float max_joint_height(const Clip& clip, int joint_index);
float min_joint_height(const Clip& clip, int joint_index);

}  // namespace foresight::author::testing
