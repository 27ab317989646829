#pragma once
// Foresight's own default motion library, authored procedurally (no external data): the skeleton,
// every clip with its tags (and, for strikes, where and when it hits), and the manifest of declared
// transitions. See docs/DEFAULT_LIBRARY.md.
//
// Clip conventions (the motion graph relies on them): 30 fps; local_pos_m[frame * J + 0] is the
// Hips position in clip space, every other joint's local_pos is its rest offset; each clip starts
// near the origin facing +Z. The LAST frame is the boundary pose: for every declared transition
// A -> B, A's last frame equals B's first frame once B is placed at A's last root placement
// (find_forward_axis + extract_root_track), so playback runs frames [0, N-1) of A and continues
// with B from its frame 0.
#include "anim/clip.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "author/manifest.hpp"

namespace foresight::author {

struct StrikeAnnotation {
  int hit_joint = -1;   ///< Hand (wrist) or Foot (ankle) joint.
  int hit_frame = -1;   ///< The frame where the effector is fully extended at the target.
  std::string kind;     ///< "punch" / "kick"
  std::string side;     ///< "left" / "right"
  std::string height;   ///< "low" (0.5-0.8 m) / "mid" (1.0-1.3 m) / "high" (1.5-1.75 m)
};

struct AuthoredClip {
  Clip clip;
  uint32_t tags = 0;  ///< SegmentTag bits (graph/motion_graph.hpp).
  std::optional<StrikeAnnotation> strike;
};

struct DefaultLibrarySpec {
  Skeleton skeleton;
  std::vector<AuthoredClip> clips;
  std::vector<DeclaredTransition> transitions;  ///< The manifest.
};

/// Builds the library. Deterministic: the same bytes on every call (no randomness, no clocks, no
/// global state; outputs are rounded to a fixed grid so last-bit differences between math
/// libraries do not change them).
DefaultLibrarySpec build_default_library();

}  // namespace foresight::author
