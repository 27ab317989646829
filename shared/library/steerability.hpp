#pragma once
// Which command directions a library can follow: from a segment, the directions (relative to
// its facing, in 8 sectors of 45 degrees) some segment within a few steps of the graph travels
// in. A library whose graph cannot go left from standing leaves a player pressing left with an
// avatar that does nothing; `foresight-motion graph` prints this per library.
#include "library/motion_library.hpp"

#include <array>
#include <string_view>

namespace foresight {

inline constexpr int kCommandSectors = 8;
/// "forward", "forward-left", "left", "back-left", "back", "back-right", "right", "forward-right".
std::string_view command_sector_name(int sector);

/// Sector s is true when a segment reached from `start` within `max_steps` transitions moves at
/// least `min_speed_m_per_s` towards s (within 22.5 degrees), relative to `start`'s first frame.
std::array<bool, kCommandSectors> followable_directions(const MotionLibrary& library, int start,
                                                        int max_steps = 4,
                                                        float min_speed_m_per_s = 0.3f);

/// The library's standing segment (idle-tagged, not crouching, moving least) and walking segment (locomotion,
/// ground speed nearest 1.3 m/s), or -1.
int standing_segment(const MotionLibrary& library);
int walking_segment(const MotionLibrary& library);

}  // namespace foresight
