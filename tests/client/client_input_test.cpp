#include "client_input.hpp"

#include <gtest/gtest.h>

namespace foresight::client {
namespace {

TEST(ClientInput, KeysGiveAUnitCameraSpaceDirection) {
  HeldKeys k;
  EXPECT_EQ(control_from_keys(k, 0.3f).camera_dir, vec2(0.0f));
  k.up = true;
  ControlInput in = control_from_keys(k, 0.3f);
  EXPECT_EQ(in.camera_dir, vec2(0.0f, 1.0f));
  EXPECT_FLOAT_EQ(in.camera_yaw_rad, 0.3f);
  k.right = true;
  in = control_from_keys(k, 0.0f);
  EXPECT_NEAR(glm::length(in.camera_dir), 1.0f, 1e-6f);
  EXPECT_GT(in.camera_dir.x, 0.0f);
  EXPECT_TRUE(control_input_valid(in));
  k.crouch = true;
  EXPECT_TRUE(control_from_keys(k, 0.0f).crouch);
  // Up with the camera looking along +x means walking along +x in the world.
  HeldKeys up;
  up.up = true;
  const vec2 world = control_world_direction(control_from_keys(up, heading_of(vec2(1, 0))));
  EXPECT_NEAR(world.x, 1.0f, 1e-5f);
  EXPECT_NEAR(world.y, 0.0f, 1e-5f);
}


MouseDrag drag_by(float dx_px, float dy_px) {
  MouseDrag d;
  d.active = true;
  d.from_px = vec2(400.0f, 300.0f);
  d.to_px = d.from_px + vec2(dx_px, dy_px);
  return d;
}

TEST(ClientInput, DragUpOnScreenIsForwardInCameraSpace) {
  const ControlInput up = control_from_drag(drag_by(0.0f, -200.0f), 0.3f);
  EXPECT_NEAR(up.camera_dir.x, 0.0f, 1e-6f);
  EXPECT_NEAR(up.camera_dir.y, 1.0f, 1e-6f);
  EXPECT_FLOAT_EQ(up.camera_yaw_rad, 0.3f);
  const ControlInput right = control_from_drag(drag_by(200.0f, 0.0f), 0.0f);
  EXPECT_NEAR(right.camera_dir.x, 1.0f, 1e-6f);
  EXPECT_NEAR(right.camera_dir.y, 0.0f, 1e-6f);
  const ControlInput back_left = control_from_drag(drag_by(-100.0f, 100.0f), 0.0f);
  EXPECT_LT(back_left.camera_dir.x, 0.0f);
  EXPECT_LT(back_left.camera_dir.y, 0.0f);
  EXPECT_NEAR(back_left.camera_dir.x, back_left.camera_dir.y, 1e-6f);
  // A drag up with the camera looking along +x walks along +x in the world, as the key does.
  const vec2 world = control_world_direction(control_from_drag(drag_by(0.0f, -500.0f), heading_of(vec2(1, 0))));
  EXPECT_NEAR(world.x, 1.0f, 1e-5f);
  EXPECT_NEAR(world.y, 0.0f, 1e-5f);
}

TEST(ClientInput, DragMagnitudeHasADeadZoneAndSaturates) {
  const DragScale scale{10.0f, 110.0f};
  EXPECT_EQ(control_from_drag(drag_by(0.0f, -9.0f), 0.0f, scale).camera_dir, vec2(0.0f)) << "dead zone";
  EXPECT_EQ(control_from_drag(drag_by(6.0f, -6.0f), 0.0f, scale).camera_dir, vec2(0.0f)) << "dead zone";
  EXPECT_NEAR(glm::length(control_from_drag(drag_by(0.0f, -60.0f), 0.0f, scale).camera_dir), 0.5f, 1e-5f);
  EXPECT_NEAR(glm::length(control_from_drag(drag_by(300.0f, -400.0f), 0.0f, scale).camera_dir), 1.0f, 1e-5f);
  for (float len : {0.0f, 11.0f, 50.0f, 109.0f, 110.0f, 5000.0f}) {
    const ControlInput in = control_from_drag(drag_by(0.6f * len, 0.8f * len), 0.0f, scale);
    EXPECT_TRUE(control_input_valid(in)) << len;
  }
  MouseDrag idle = drag_by(0.0f, -500.0f);
  idle.active = false;
  EXPECT_EQ(control_from_drag(idle, 0.0f, scale).camera_dir, vec2(0.0f)) << "not held: no drag";
}

TEST(ClientInput, DragOverridesKeysWhileHeldAndReleaseGoesBackToKeys) {
  HeldKeys keys;
  keys.left = true;
  keys.crouch = true;
  const MouseDrag drag = drag_by(0.0f, -500.0f);
  ControlInput in = control_from_input(keys, drag, 0.2f);
  EXPECT_NEAR(in.camera_dir.y, 1.0f, 1e-6f) << "the drag steers";
  EXPECT_NEAR(in.camera_dir.x, 0.0f, 1e-6f);
  EXPECT_TRUE(in.crouch) << "C still crouches";
  EXPECT_FLOAT_EQ(in.camera_yaw_rad, 0.2f);
  MouseDrag released = drag;
  released.active = false;
  in = control_from_input(keys, released, 0.2f);
  EXPECT_EQ(in.camera_dir, vec2(-1.0f, 0.0f)) << "released: the keys again";
  EXPECT_EQ(control_from_input(HeldKeys{}, released, 0.2f).camera_dir, vec2(0.0f)) << "no key: stop";
}

}  // namespace
}  // namespace foresight::client
