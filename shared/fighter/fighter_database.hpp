#pragma once
// The fighter database (paper 3.2.1): strike entries, each a window of a take (a clip on its own
// skeleton) holding exactly one hit, with its semantics, its hit frame, the hit point's
// trajectory and bounding box, and the per-frame pose key points the clustering and the
// retrieval read. Built offline (fighter_build/fighter_database_build.hpp) from the default
// library's strike clips and from BVH folders with a strike sidecar or automatic splitting; the
// runtime plays its takes. See docs/FIGHTER_DATABASE.md.
#include "anim/clip.hpp"
#include "fighter/fighter_rig.hpp"
#include "fighter/pose_cloud.hpp"
#include "fighter/strike_kind.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace foresight {

/// One captured or authored take: a clip on its own skeleton.
struct FighterTake {
  std::string name;    ///< File stem, or the default library's clip name.
  std::string source;  ///< The BVH path, or "default library".
  Skeleton skeleton;
  FighterRig rig;
  Clip clip;
};

/// One strike: frames [start_frame, end_frame] of a take, one hit at hit_frame.
struct FighterEntry {
  std::string name;  ///< The take's name, plus "#i" when the take holds several strikes.
  int take = -1;     ///< Index into FighterDatabase::takes.
  int hit_joint = -1;
  StrikeKind kind = StrikeKind::kPunch;
  StrikeSide side = StrikeSide::kLeft;
  StrikeHeight height = StrikeHeight::kMid;
  int start_frame = 0, hit_frame = 0, end_frame = 0;  ///< Take frames, start <= hit <= end.
  float body_size_m = 0.0f;                           ///< The actor's (FighterRig::body_size_m).
  // Per frame of the window (num_frames() items, frame start_frame + i at index i):
  std::vector<vec3> key_points;        ///< [i * kPoseKeyPoints + k]: root frame of frame i / body size.
  std::vector<Placement> root_from_start_m;  ///< Frame i's root placement in the start's root frame.
  std::vector<vec3> hit_path_m;        ///< Hit joint, in the root frame at start_frame, metres.
  vec3 hit_box_min_m{0.0f}, hit_box_max_m{0.0f};  ///< Axis-aligned box of hit_path_m.

  int num_frames() const { return end_frame - start_frame + 1; }
  vec3 hit_point_m() const { return hit_path_m[static_cast<std::size_t>(hit_frame - start_frame)]; }
};

struct FighterDatabase {
  std::vector<FighterTake> takes;
  std::vector<FighterEntry> entries;
};

}  // namespace foresight
