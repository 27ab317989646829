#include "terrain_poses.hpp"

#include <algorithm>

namespace foresight::client {

TerrainPoses::TerrainPoses(const Morphology& default_morphology, uint8_t morphology)
    : skeleton_(default_morphology.skeleton), morphology_(morphology) {
  valid_ = terrain::terrain_skeleton_joints(skeleton_, joints_) &&
           skeleton_.num_joints() <= static_cast<int>(protocol::kMaxFighterJoints);
  pose_.resize(skeleton_.num_joints());
  mapped_.reserve(static_cast<size_t>(poses_.config().max_fighters));
}

void TerrainPoses::push(double server_time_s, std::span<const protocol::TerrainBodyState> bodies) {
  if (!valid_) return;
  mapped_.clear();
  for (const protocol::TerrainBodyState& b : bodies) {
    if (mapped_.size() == mapped_.capacity()) break;  // more than the buffer tracks
    terrain::TerrainBodyPose body;
    body.pelvis_m = b.pelvis_m;
    body.heading_rad = b.heading_rad;
    terrain::terrain_body_set_angles(body, b.angles_rad);
    terrain::terrain_body_to_pose(body, skeleton_, joints_, pose_);
    FighterPoseSample& s = mapped_.emplace_back();
    s.avatar = b.avatar;
    s.morphology = morphology_;
    s.num_joints = static_cast<uint16_t>(skeleton_.num_joints());
    s.pelvis_m = b.pelvis_m;
    std::copy(pose_.local_rot.begin(), pose_.local_rot.end(), s.local_rot.begin());
  }
  poses_.push(server_time_s, mapped_);
}

}  // namespace foresight::client
