#pragma once
// The cameras a player sees through (paper 3.1, Fig. 2): the scene's designer-placed cameras,
// switched automatically as the avatar walks from one region to the next, or a follow camera
// behind the avatar (toggled by a key). The camera's yaw on the ground goes out with every input
// so "up" on the keyboard means "away from the camera" on screen.
#include "math/types.hpp"
#include "world/scene.hpp"

#include <glm/mat4x4.hpp>

namespace foresight::client {

struct FollowCameraConfig {
  float distance_m = 4.5f;       ///< Behind the avatar, on the ground.
  float height_m = 2.6f;         ///< Above the ground.
  float target_height_m = 1.0f;  ///< Looks at this point above the avatar's root.
  float fov_y_rad = 1.0f;
  float turn_rate = 3.0f;        ///< Heading follow speed (1/s); high: snappier.
  /// A wall between the avatar and the camera pulls the camera in front of it at once (this far
  /// before the wall); once the way is clear the camera eases back out at this rate (1/s).
  float wall_margin_m = 0.25f;
  float ease_out_rate = 4.0f;
};

/// Where the segment from `from` to `to` first enters one of the scene's boxes, as a fraction
/// of its length (1: it enters none). Boxes holding `from` do not count.
float first_box_hit(const Scene& scene, vec3 from, vec3 to);

class CameraRig {
 public:
  explicit CameraRig(const Scene* scene = nullptr, const FollowCameraConfig& follow = {});
  void set_scene(const Scene* scene);

  /// Moves the cameras for the avatar at `pos_m` (ground) facing `heading_rad`, `dt_s` after the
  /// previous update.
  void update(vec2 pos_m, float heading_rad, float dt_s);
  void toggle_follow();
  /// True while the follow camera is in use (chosen, or no designer camera covers the avatar).
  bool following() const { return follow_ || designer_ < 0; }
  /// Index into Scene::cameras of the designer camera in use (-1: none yet).
  int designer_camera() const { return designer_; }

  vec3 eye_m() const { return eye_; }
  vec3 target_m() const { return target_; }
  /// Heading of the view direction on the ground: ControlInput::camera_yaw_rad.
  float yaw_rad() const { return heading_of(target_ - eye_); }
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;

 private:
  const Scene* scene_ = nullptr;
  FollowCameraConfig follow_config_;
  bool follow_ = false;
  bool follow_placed_ = false;  ///< The follow heading has been set (snap on first use).
  float follow_heading_ = 0.0f;
  float arm_m_ = 0.0f;  ///< Target-to-eye distance now (shortened in front of walls).
  int designer_ = -1;
  vec3 eye_{0.0f, 5.0f, -5.0f};
  vec3 target_{0.0f};
  float fov_y_ = 1.0f;
};

/// The designer camera for a point: `current` while its region still covers the point
/// (hysteresis where regions overlap), else the first that covers it, else `current`.
int designer_camera_for(const Scene& scene, vec2 pos_m, int current);

}  // namespace foresight::client
