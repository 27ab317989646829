#pragma once
// Which parts of the feet are planted, per clip frame, found once when the library is compiled
// (the clips' own motion, root motion included, is the truth: at run time steering, blends and
// corrections move the feet, which is what the pose stage undoes and the motion-quality bench
// measures). A part is planted when it is within kContactHeight_m of its lowest height in the clip
// and moves slower than kContactSpeed_mps (horizontally) and kContactRise_mps (vertically).
#include "anim/clip.hpp"
#include "anim/skeleton.hpp"

#include <cstdint>
#include <vector>

namespace foresight {

inline constexpr float kContactHeight_m = 0.03f;
inline constexpr float kContactSpeed_mps = 0.3f;
inline constexpr float kContactRise_mps = 0.15f;

/// Bits of a frame's contact byte.
enum FootContactBit : uint8_t {
  kLeftHeel = 1,   ///< Left ankle (kCanonLeftFoot) planted.
  kLeftBall = 2,   ///< Left ball of the foot (kCanonLeftToeBase) planted.
  kRightHeel = 4,
  kRightBall = 8,
};

/// The heel (ankle) and ball joints of foot 0 (left) and 1 (right) on the canonical skeleton.
int foot_heel_joint(int foot);
int foot_ball_joint(int foot);
inline uint8_t foot_heel_bit(int foot) { return foot == 0 ? kLeftHeel : kRightHeel; }
inline uint8_t foot_ball_bit(int foot) { return foot == 0 ? kLeftBall : kRightBall; }

/// One contact byte per frame of `clip` (canonical skeleton), appended to `out`; raises
/// `max_step_m` to the farthest any joint moves between two of its frames (one FK pass for both).
void clip_foot_contact(const Skeleton& skeleton, const Clip& clip, std::vector<uint8_t>& out, float& max_step_m);

}  // namespace foresight
