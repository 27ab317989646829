#pragma once
// Third-person control (paper 3.1): the player gives a direction in camera space (arrow keys:
// x = right, y = forward/up on screen), which becomes a direction on the ground in the world and
// then in the avatar's own frame, where command matching compares it with each motion.
#include "math/types.hpp"

#include <cmath>

namespace foresight {

struct ControlInput {
  vec2 camera_dir{0.0f};       ///< Camera space: x right, y forward. Zero means "stop". |dir| <= 1.
  float camera_yaw_rad = 0.0f; ///< Heading of the camera's view direction on the ground.
  bool crouch = false;         ///< Button: prefer crouching motions.
};

/// True when every value is finite and the direction is at most unit length (with slack).
inline bool control_input_valid(const ControlInput& in) {
  return std::isfinite(in.camera_dir.x) && std::isfinite(in.camera_dir.y) &&
         std::isfinite(in.camera_yaw_rad) && glm::dot(in.camera_dir, in.camera_dir) <= 1.0001f;
}

/// The world ground direction (x, z) the player asks for: forward along the camera's view, right
/// to the camera's right (heading convention of math/types.hpp: the right of heading h is
/// (-cos h, sin h)). Zero stays zero.
inline vec2 control_world_direction(const ControlInput& in) {
  const float s = std::sin(in.camera_yaw_rad), c = std::cos(in.camera_yaw_rad);
  const vec2 forward(s, c), right(-c, s);
  return in.camera_dir.y * forward + in.camera_dir.x * right;
}

/// The same direction in the avatar's frame (+Z forward, +X left), as command matching uses it.
inline vec2 control_avatar_direction(const ControlInput& in, float avatar_heading_rad) {
  return rotate_ground(control_world_direction(in), -avatar_heading_rad);
}

}  // namespace foresight
