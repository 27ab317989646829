#include "camera_rig.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace foresight::client {
namespace {

Scene two_rooms() {
  Scene scene;
  SceneCamera west;
  west.name = "west";
  west.position_m = vec3(-2, 8, 5);
  west.target_m = vec3(4, 0, 5);
  west.region = {vec2(0, 0), vec2(6, 10)};
  SceneCamera east = west;
  east.name = "east";
  east.position_m = vec3(12, 8, 5);
  east.target_m = vec3(6, 0, 5);
  east.region = {vec2(4, 0), vec2(10, 10)};  // overlaps west on x in [4, 6]
  scene.cameras = {west, east};
  return scene;
}

TEST(CameraRig, SwitchesDesignerCamerasWithRegions) {
  const Scene scene = two_rooms();
  CameraRig rig(&scene);
  rig.update(vec2(1, 5), 0.0f, 0.016f);
  EXPECT_EQ(rig.designer_camera(), 0);
  EXPECT_FALSE(rig.following());
  EXPECT_EQ(rig.eye_m(), scene.cameras[0].position_m);
  EXPECT_NEAR(rig.yaw_rad(), heading_of(vec2(1, 0)), 1e-5);  // west camera looks along +x
  rig.update(vec2(8, 5), 0.0f, 0.016f);
  EXPECT_EQ(rig.designer_camera(), 1);
  EXPECT_NEAR(rig.yaw_rad(), heading_of(vec2(-1, 0)), 1e-5);
}

TEST(CameraRig, HysteresisKeepsTheCameraWhileItStillCovers) {
  const Scene scene = two_rooms();
  CameraRig rig(&scene);
  rig.update(vec2(8, 5), 0.0f, 0.016f);
  EXPECT_EQ(rig.designer_camera(), 1);
  rig.update(vec2(5, 5), 0.0f, 0.016f);  // overlap: east still covers
  EXPECT_EQ(rig.designer_camera(), 1);
  rig.update(vec2(3, 5), 0.0f, 0.016f);  // only west now
  EXPECT_EQ(rig.designer_camera(), 0);
  rig.update(vec2(5, 5), 0.0f, 0.016f);  // overlap again: west stays
  EXPECT_EQ(rig.designer_camera(), 0);
  rig.update(vec2(50, 50), 0.0f, 0.016f);  // outside every region: keep the last
  EXPECT_EQ(rig.designer_camera(), 0);
}

TEST(CameraRig, FollowCameraSitsBehindTheAvatar) {
  const Scene scene = two_rooms();
  CameraRig rig(&scene);
  rig.update(vec2(1, 5), 0.0f, 0.016f);
  rig.toggle_follow();
  const float heading = 0.7f;
  rig.update(vec2(2, 3), heading, 0.016f);
  EXPECT_TRUE(rig.following());
  const vec2 forward(std::sin(heading), std::cos(heading));
  const vec2 to_avatar = vec2(2, 3) - ground(rig.eye_m());
  EXPECT_GT(glm::dot(to_avatar, forward), 1.0f);               // behind
  EXPECT_NEAR(std::abs(to_avatar.x * forward.y - to_avatar.y * forward.x), 0.0f, 1e-4);  // on line
  EXPECT_GT(rig.eye_m().y, 1.0f);
  EXPECT_NEAR(rig.yaw_rad(), heading, 1e-4);
  // Turning: the camera swings round towards the new heading, not instantly.
  rig.update(vec2(2, 3), heading + 1.0f, 0.1f);
  EXPECT_GT(rig.yaw_rad(), heading + 0.05f);
  EXPECT_LT(rig.yaw_rad(), heading + 0.95f);
  rig.toggle_follow();
  rig.update(vec2(1, 5), 0.0f, 0.016f);
  EXPECT_FALSE(rig.following());
}

// A wall behind the avatar: the follow camera comes in front of it at once (the player is never
// seen through a wall), and eases back out once the avatar has walked away from it.
TEST(CameraRig, FollowCameraStaysOnTheAvatarsSideOfAWall) {
  Scene scene;
  SceneBox wall;
  wall.min_m = vec3(-5, 0, -2.2f);
  wall.max_m = vec3(5, 3, -2.0f);  // 2 m behind an avatar at the origin facing +z
  scene.boxes = {wall};
  CameraRig rig(&scene);
  rig.update(vec2(0, 0), 0.0f, 0.016f);
  ASSERT_TRUE(rig.following());
  EXPECT_GT(rig.eye_m().z, -2.0f) << "the camera is behind the wall";
  EXPECT_LT(rig.eye_m().z, -1.0f) << "the camera came further in than the wall asks";
  EXPECT_EQ(first_box_hit(scene, rig.target_m(), rig.eye_m()), 1.0f);
  // Walk 5 m away from the wall: the camera eases back to its full distance, not at once.
  rig.update(vec2(0, 5), 0.0f, 0.016f);
  const float just_after = glm::length(ground(rig.eye_m()) - vec2(0, 5));
  for (int i = 0; i < 120; ++i) rig.update(vec2(0, 5), 0.0f, 0.016f);
  const float later = glm::length(ground(rig.eye_m()) - vec2(0, 5));
  EXPECT_LT(just_after, 3.5f);
  EXPECT_NEAR(later, FollowCameraConfig{}.distance_m, 0.05f);
}

TEST(CameraRig, FirstBoxHitFindsTheNearestBoxAndIgnoresOnesHoldingTheStart) {
  Scene scene;
  SceneBox near, far, around;
  near.min_m = vec3(2, -1, -1);
  near.max_m = vec3(3, 1, 1);
  far.min_m = vec3(6, -1, -1);
  far.max_m = vec3(7, 1, 1);
  around.min_m = vec3(-1, -1, -1);
  around.max_m = vec3(1, 1, 1);  // holds the start
  scene.boxes = {far, around, near};
  EXPECT_NEAR(first_box_hit(scene, vec3(0), vec3(10, 0, 0)), 0.2f, 1e-6);
  EXPECT_EQ(first_box_hit(scene, vec3(0), vec3(1.5f, 0, 0)), 1.0f);    // stops short
  EXPECT_EQ(first_box_hit(scene, vec3(0, 2, 0), vec3(10, 2, 0)), 1.0f);  // passes above
}

TEST(CameraRig, NoDesignerCamerasMeansFollow) {
  const Scene scene;
  CameraRig rig(&scene);
  rig.update(vec2(0, 0), 0.0f, 0.016f);
  EXPECT_TRUE(rig.following());
  EXPECT_NEAR(rig.yaw_rad(), 0.0f, 1e-5);
}

}  // namespace
}  // namespace foresight::client
