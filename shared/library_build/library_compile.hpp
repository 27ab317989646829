#pragma once
// Build time: a MotionLibrary's source (skeleton, clips, graph) in, its compiled tables out (root
// tracks, foot contacts, segment motions and body volumes, transition offsets, content hash).
// The tick only reads what this writes (library/motion_library.hpp).
#include "library/motion_library.hpp"

#include <string>

namespace foresight {

/// Checks the source, moves it into `out` and computes the compiled tables and the content hash.
/// Returns false with a reason (and `out` untouched) when clips and skeleton disagree, a segment's
/// frame range is outside its clip, or a transition names a missing segment.
bool motion_library_compile(MotionLibrarySource source, MotionLibrary& out, std::string& error);

}  // namespace foresight
