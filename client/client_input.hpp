#pragma once
// Keyboard to ControlInput: arrows / WASD give a direction in camera space (x right, y forward),
// C crouches. Pure so it can be tested without a window.
#include "lookahead/control_input.hpp"

namespace foresight::client {

struct HeldKeys {
  bool up = false, down = false, left = false, right = false, crouch = false;
};

/// The input for the held keys seen through a camera with heading `camera_yaw_rad`.
ControlInput control_from_keys(const HeldKeys& keys, float camera_yaw_rad);

}  // namespace foresight::client
