#pragma once
// The default library's humanoid skeleton (owned by the procedural authoring code).
#include "anim/skeleton.hpp"

namespace foresight::author {

/// The one skeleton every default clip uses: 21+ joints, metres, Y up, facing +Z, T-pose-free
/// rest (bones along their offsets, arms hanging).
Skeleton default_skeleton();

}  // namespace foresight::author
