#pragma once
// The player's steering to ControlInput: arrows / WASD, or a mouse drag (the terrain paper's
// alternative), give a direction in camera space (x right, y forward); C crouches. Both go
// through control_from_input, so keys and drag reach the server the same way. Pure so it can be
// tested without a window.
#include "world/control_input.hpp"

namespace foresight::client {

struct HeldKeys {
  bool up = false, down = false, left = false, right = false, crouch = false;
};

/// A left-button drag in window pixels (y down, as GLFW reports the cursor).
struct MouseDrag {
  bool active = false;   ///< The left button is held (and the press did not go to the overlay).
  vec2 from_px{0.0f};    ///< Where the press began.
  vec2 to_px{0.0f};      ///< Where the cursor is now.
};

/// How a drag's length becomes speed: no motion inside the dead zone (a click is not a command),
/// full magnitude at `full_px` and beyond, linear in between.
struct DragScale {
  float dead_zone_px = 12.0f;
  float full_px = 120.0f;
};

/// The input for the held keys seen through a camera with heading `camera_yaw_rad`.
ControlInput control_from_keys(const HeldKeys& keys, float camera_yaw_rad);

/// The input for a drag: dragging up on screen is forward (away from the camera), right is
/// right; magnitude from the drag's length (DragScale), at most 1. Inactive or in the dead
/// zone: stop.
ControlInput control_from_drag(const MouseDrag& drag, float camera_yaw_rad, const DragScale& scale = {});

/// What the client sends: an active drag steers (crouch still from C); otherwise the keys
/// (stop when none is held), so releasing the button hands control back to the keys.
ControlInput control_from_input(const HeldKeys& keys, const MouseDrag& drag, float camera_yaw_rad,
                                const DragScale& scale = {});

}  // namespace foresight::client
