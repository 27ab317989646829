#pragma once
// Terrain avatars' bodies (schema TerrainBody: pelvis, heading, 18 angles) as poses of the default
// skeleton (shared/terrain/terrain_body.hpp), in the form the streamed-pose buffer plays back
// (FighterPoses: history per avatar, slerped between snapshots), so they are drawn like fighters.
#include "fighter_poses.hpp"
#include "terrain/terrain_body.hpp"

namespace foresight::client {

class TerrainPoses {
 public:
  /// `morphology`: the index of the default skeleton's Morphology in the caller's list.
  TerrainPoses(const Morphology& default_morphology, uint8_t morphology);
  /// Maps `bodies` onto the skeleton and adds them at server time `server_time_s`.
  void push(double server_time_s, std::span<const protocol::TerrainBodyState> bodies);
  void clear() { poses_.clear(); }
  /// Every terrain avatar to draw at server time `t`, sorted by avatar id.
  void sample(double t, std::vector<FighterPoseSample>& out) const { poses_.sample(t, out); }
  bool valid() const { return valid_; }

 private:
  const Skeleton& skeleton_;
  uint8_t morphology_;
  terrain::TerrainSkeletonJoints joints_;
  bool valid_ = false;
  Pose pose_;
  std::vector<FighterPoseSample> mapped_;
  FighterPoses poses_;
};

}  // namespace foresight::client
