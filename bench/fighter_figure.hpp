#pragma once
// The picture of adapted strikes (like the paper's Fig. 10): one default strike retargeted onto the
// five morphologies and adapted so every one reaches the same target, each in its own panel, as
// orthographic stick figures. Grey: the retargeted strike at its hit frame, before adaptation; blue:
// the adapted pose; red circle: the target. One row per strike.
#include "math/types.hpp"

#include <string>
#include <vector>

namespace foresight::bench {

struct FighterFigureStrike {
  std::string clip;  ///< A default library strike, e.g. "punch_left_jab_mid".
  vec3 target_m{0.0f};  ///< In the fighter's root frame (it stands at the origin facing +Z).
};

struct FighterFigureOptions {
  std::vector<FighterFigureStrike> strikes{{"punch_left_jab_mid", vec3(0.05f, 1.0f, 0.55f)},
                                           {"kick_right_front_mid", vec3(-0.05f, 0.8f, 0.6f)}};
  bool side_view = true;  ///< Side (looking along -X: forward is to the right) or front (along -Z).
  float pixels_per_m = 110.0f;
};

/// The SVG document (deterministic). Unknown clip names get a row saying so. Empty when the
/// fighters' limb models cannot be built.
std::string fighter_adaptation_svg(const FighterFigureOptions& options);

}  // namespace foresight::bench
