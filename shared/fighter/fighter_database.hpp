#pragma once
// The fighter database (paper 3.2.1): strike entries, each a window of a take (a clip on its own
// skeleton) holding exactly one hit, with its semantics, its hit frame, the hit point's
// trajectory and bounding box, and the per-frame pose key points the clustering and the
// retrieval read. Built offline from the default library's strike clips and from BVH folders
// with a strike sidecar (strike_annotation.hpp) or automatic splitting (strike_split.hpp).
// See docs/FIGHTER_DATABASE.md.
#include "anim/clip.hpp"
#include "fighter/fighter_rig.hpp"
#include "fighter/pose_cloud.hpp"
#include "fighter/strike_annotation.hpp"
#include "fighter/strike_split.hpp"

#include <cstdint>
#include <filesystem>
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

/// Adds the default library's strike clips (one entry each, the whole clip as its window).
bool fighter_database_add_default_library(FighterDatabase& db, std::string& error);

struct FolderLoadReport {
  int takes_loaded = 0;
  int takes_skipped = 0;       ///< "skip": true in the sidecar.
  int strikes_annotated = 0;   ///< Entries from sidecar marks.
  int strikes_detected = 0;    ///< Entries from strike_detect.
  std::string sidecar;         ///< The sidecar used, or empty.
};

/// Adds every *.bvh of `folder` (sorted by name). `sidecar`: the folder sidecar to use; empty:
/// `folder`/strikes.json when it exists. A per-clip `<stem>.strikes.json` beside the BVH wins
/// over the folder sidecar's entry. A take the sidecars do not annotate (absent, or listed with
/// no strikes and no skip) is split automatically. Fails with the file and the reason (a BVH that
/// does not load, a skeleton without the fighter roles, a bad sidecar or mark).
bool fighter_database_add_folder(FighterDatabase& db, const std::filesystem::path& folder,
                                 const std::filesystem::path& sidecar, const StrikeSplitParams& split,
                                 FolderLoadReport* report, std::string& error);

/// Adds one take and its strikes. Marks with start/end -1 get their window from strike_window;
/// no marks: strike_detect. Marks must have passed strike_marks_check.
bool fighter_database_add_take(FighterDatabase& db, FighterTake take, const std::vector<StrikeMark>& marks,
                               const StrikeSplitParams& split, std::string& error);

/// The entries of take `take` as sidecar marks (every field given), to save and edit.
ClipStrikes fighter_database_marks(const FighterDatabase& db, int take);

/// A deterministic database of `num_entries` entries for benchmarks: variants of `seed_db`'s
/// entries (cycled) with a later start frame, another actor size (+-12%), the hit path turned and
/// shifted, and key-point noise, all drawn from `seed`. Entries reference seed_db's takes (copied
/// once), so they can be played, but their key points and paths no longer match the clip exactly:
/// for timing retrieval, not for animation.
FighterDatabase fighter_database_synthetic(const FighterDatabase& seed_db, int num_entries, std::uint64_t seed);

/// Height class from the hit point's height above the take's floor relative to the actor's body
/// size (thresholds in docs/FIGHTER_DATABASE.md).
StrikeHeight strike_height_from_hit(float hit_height_m, float body_size_m);

}  // namespace foresight
