#include "client_input.hpp"

namespace foresight::client {

ControlInput control_from_keys(const HeldKeys& keys, float camera_yaw_rad) {
  ControlInput in;
  in.camera_dir = vec2(static_cast<float>(keys.right) - static_cast<float>(keys.left),
                       static_cast<float>(keys.up) - static_cast<float>(keys.down));
  const float len = glm::length(in.camera_dir);
  if (len > 1.0f) in.camera_dir /= len;  // diagonals: unit length, as the wire requires
  in.camera_yaw_rad = camera_yaw_rad;
  in.crouch = keys.crouch;
  return in;
}

}  // namespace foresight::client
