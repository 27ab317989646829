#include "author/manifest.hpp"

namespace foresight::author {

std::vector<DeclaredTransition> build_manifest(const std::vector<ClipBoundaries>& clips) {
  std::vector<DeclaredTransition> out;
  for (const ClipBoundaries& a : clips) {
    for (const ClipBoundaries& b : clips) {
      if (a.end != b.start) continue;
      // Strikes are single moves out of and back into the stance: no strike chains, and no leaving
      // the fight from mid-strike (the fighter's state machine returns to the stance first).
      if (a.strike && b.name != kFightStanceClip) continue;
      if (b.strike && a.name != kFightStanceClip) continue;
      out.push_back({a.name, b.name,
                     a.strike || b.strike ? kStrikeBlendFrames : kLocomotionBlendFrames});
    }
  }
  return out;
}

}  // namespace foresight::author
