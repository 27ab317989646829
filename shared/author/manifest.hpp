#pragma once
// The transition manifest: which clip may follow which. Derived from the boundary families: a clip
// ending in family F may be followed by any clip starting in F (their boundary poses are equal by
// construction), except that strikes only connect to and from the fighting stance.
#include "author/gait_style.hpp"

#include <string>
#include <vector>

namespace foresight::author {

struct DeclaredTransition {
  std::string from, to;
  int blend_frames = 6;
};

/// What the manifest needs to know about a clip.
struct ClipBoundaries {
  std::string name;
  FamilyId start = FamilyId::kIdle;
  FamilyId end = FamilyId::kIdle;
  bool strike = false;
};

inline constexpr int kLocomotionBlendFrames = 6;
inline constexpr int kStrikeBlendFrames = 4;  ///< Strikes react fast.

/// The name of the clip every strike starts from and returns to.
inline constexpr const char* kFightStanceClip = "fight_stance";

std::vector<DeclaredTransition> build_manifest(const std::vector<ClipBoundaries>& clips);

}  // namespace foresight::author
