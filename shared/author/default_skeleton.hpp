#pragma once
// The default library's humanoid skeleton: the canonical skeleton with its built-in proportions
// (anim/canonical_skeleton.hpp says what the joints are).
#include "anim/canonical_skeleton.hpp"

namespace foresight::author {

inline Skeleton default_skeleton() { return canonical_skeleton(); }

using foresight::kRestAnkleHeightM;
using foresight::kRestBallHeightM;
using foresight::kRestPelvisHeightM;

}  // namespace foresight::author
