#include "client_input.hpp"

#include <algorithm>

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

ControlInput control_from_drag(const MouseDrag& drag, float camera_yaw_rad, const DragScale& scale) {
  ControlInput in;
  in.camera_yaw_rad = camera_yaw_rad;
  if (!drag.active) return in;
  // Screen y grows downwards: a drag up (negative y) is forward.
  const vec2 d(drag.to_px.x - drag.from_px.x, drag.from_px.y - drag.to_px.y);
  const float len = glm::length(d);
  if (!(len > scale.dead_zone_px)) return in;  // also catches NaN
  const float span = std::max(scale.full_px - scale.dead_zone_px, 1.0f);
  const float magnitude = std::min((len - scale.dead_zone_px) / span, 1.0f);
  in.camera_dir = d * (magnitude / len);
  return in;
}

ControlInput control_from_input(const HeldKeys& keys, const MouseDrag& drag, float camera_yaw_rad,
                                const DragScale& scale) {
  if (!drag.active) return control_from_keys(keys, camera_yaw_rad);
  ControlInput in = control_from_drag(drag, camera_yaw_rad, scale);
  in.crouch = keys.crouch;
  return in;
}

}  // namespace foresight::client
