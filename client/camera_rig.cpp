#include "camera_rig.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace foresight::client {

int designer_camera_for(const Scene& scene, vec2 pos_m, int current) {
  const int n = static_cast<int>(scene.cameras.size());
  if (current >= 0 && current < n && scene.cameras[static_cast<size_t>(current)].region.contains(pos_m))
    return current;
  for (int i = 0; i < n; ++i)
    if (scene.cameras[static_cast<size_t>(i)].region.contains(pos_m)) return i;
  return current < n ? current : -1;
}

float first_box_hit(const Scene& scene, vec3 from, vec3 to) {
  const vec3 d = to - from;
  float first = 1.0f;
  for (const SceneBox& box : scene.boxes) {
    // Slabs: the parameter range inside the box on each axis, intersected.
    float enter = 0.0f, leave = first;
    bool inside_at_start = true;
    for (int axis = 0; axis < 3 && enter <= leave; ++axis) {
      const float lo = box.min_m[axis], hi = box.max_m[axis];
      if (from[axis] < lo || from[axis] > hi) inside_at_start = false;
      if (std::abs(d[axis]) < 1e-9f) {
        if (from[axis] < lo || from[axis] > hi) enter = leave + 1.0f;  // parallel and outside
        continue;
      }
      float t0 = (lo - from[axis]) / d[axis], t1 = (hi - from[axis]) / d[axis];
      if (t0 > t1) std::swap(t0, t1);
      enter = std::max(enter, t0);
      leave = std::min(leave, t1);
    }
    if (enter <= leave && !inside_at_start) first = std::min(first, enter);
  }
  return first;
}

CameraRig::CameraRig(const Scene* scene, const FollowCameraConfig& follow)
    : scene_(scene), follow_config_(follow) {}

void CameraRig::set_scene(const Scene* scene) {
  scene_ = scene;
  designer_ = -1;
}

void CameraRig::toggle_follow() {
  follow_ = !follow_;
  follow_placed_ = false;  // Snap behind the avatar rather than swinging round from afar.
}

void CameraRig::update(vec2 pos_m, float heading_rad, float dt_s) {
  if (scene_) designer_ = designer_camera_for(*scene_, pos_m, designer_);
  if (!following()) {
    const SceneCamera& cam = scene_->cameras[static_cast<size_t>(designer_)];
    eye_ = cam.position_m;
    target_ = cam.target_m;
    fov_y_ = cam.fov_y_rad;
    follow_placed_ = false;
    return;
  }
  // Follow: swing towards the avatar's heading at turn_rate, along the shorter way round.
  const bool snap = !follow_placed_;
  if (snap) {
    follow_heading_ = heading_rad;
    follow_placed_ = true;
  } else {
    const float k = 1.0f - std::exp(-follow_config_.turn_rate * std::max(dt_s, 0.0f));
    follow_heading_ = wrap_angle(follow_heading_ + k * wrap_angle(heading_rad - follow_heading_));
  }
  const vec2 forward(std::sin(follow_heading_), std::cos(follow_heading_));
  const vec3 wanted_eye = from_ground(pos_m - forward * follow_config_.distance_m, follow_config_.height_m);
  target_ = from_ground(pos_m, follow_config_.target_height_m);
  fov_y_ = follow_config_.fov_y_rad;
  // A spring arm, as third-person cameras do: never look at the player through a wall.
  const float full_arm = glm::length(wanted_eye - target_);
  const float hit = scene_ ? first_box_hit(*scene_, target_, wanted_eye) : 1.0f;
  const float clear_arm = hit < 1.0f ? std::max(hit * full_arm - follow_config_.wall_margin_m, 0.3f) : full_arm;
  if (snap || clear_arm < arm_m_) {
    arm_m_ = clear_arm;
  } else {
    arm_m_ += (clear_arm - arm_m_) * (1.0f - std::exp(-follow_config_.ease_out_rate * std::max(dt_s, 0.0f)));
  }
  eye_ = target_ + (wanted_eye - target_) * (std::min(arm_m_, full_arm) / full_arm);
}

glm::mat4 CameraRig::view() const { return glm::lookAt(eye_, target_, vec3(0.0f, 1.0f, 0.0f)); }

glm::mat4 CameraRig::projection(float aspect) const {
  return glm::perspective(fov_y_, std::max(aspect, 0.01f), 0.1f, 200.0f);
}

}  // namespace foresight::client
