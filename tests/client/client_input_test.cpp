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

}  // namespace
}  // namespace foresight::client
