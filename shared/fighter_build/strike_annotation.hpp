#pragma once
// The strike sidecar: what a captured fighting take holds (paper 3.2.1: hit segment, semantics,
// hit time), in a JSON file beside the BVH files so annotations can be edited by hand and saved
// back. Format (docs/FIGHTER_DATABASE.md):
//
//   <folder>/strikes.json               one file for the folder, or
//   <folder>/<clip stem>.strikes.json   one file per clip (wins over the folder's entry)
//
//   { "format": "foresight-strikes", "version": 1,
//     "clips": { "take.bvh": { "strikes": [ { "hit_joint": "Hand_L", "kind": "punch",
//                                             "side": "left", "height": "high",
//                                             "hit_frame": 31, "start_frame": 18,
//                                             "end_frame": 45 } ] },
//                "cuts.bvh": { "skip": true } } }
//
// A per-clip file is the clip object itself plus "format" and "version". Frames are frames of the
// IMPORTED clip (bvh_import.hpp resamples to 30 or 60 fps; the Bandai takes are 30 fps already).
// hit_joint, kind, side and hit_frame are required; height, start_frame and end_frame are
// optional (found from the hit point and the effector's speed, strike_split.hpp). A clip that the
// sidecar does not list has its strikes detected automatically. Keys starting with '_' are
// comments.
#include "anim/skeleton.hpp"
#include "fighter/strike_kind.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace foresight {


/// One strike of a take.
struct StrikeMark {
  std::string hit_joint;  ///< Joint name on the take's skeleton (wrist or ankle: "Hand_L").
  StrikeKind kind = StrikeKind::kPunch;
  StrikeSide side = StrikeSide::kLeft;
  std::optional<StrikeHeight> height;  ///< Absent: from the hit point's height (fighter_database).
  int hit_frame = 0;                   ///< Full extension at the target.
  int start_frame = -1;                ///< -1: found from the effector's speed (strike_split).
  int end_frame = -1;                  ///< -1: likewise. Otherwise start <= hit <= end.
  bool operator==(const StrikeMark&) const = default;
};

/// What the sidecar says about one clip.
struct ClipStrikes {
  std::string clip;  ///< The BVH file name within the folder ("take.bvh").
  bool skip = false; ///< The take holds nothing to use (sword cuts...): not loaded at all.
  std::vector<StrikeMark> strikes;
  bool operator==(const ClipStrikes&) const = default;
};

struct StrikeSidecar {
  std::vector<ClipStrikes> clips;  ///< Sorted by clip name (the JSON object's order).
  const ClipStrikes* find(std::string_view clip) const;
  bool operator==(const StrikeSidecar&) const = default;
};

inline constexpr int kStrikeSidecarVersion = 1;
inline constexpr std::string_view kStrikeSidecarFormat = "foresight-strikes";

/// Parses a folder sidecar. Syntax, types, unknown keys, bad kind/side/height, negative frames
/// and start > hit > end orders fail with "<source>: <json path>: <reason>". Joint names and the
/// clip's frame count are checked later by strike_marks_check (they need the clip).
bool strike_sidecar_parse(std::string_view text, std::string_view source, StrikeSidecar& out,
                          std::string& error);
/// Parses a per-clip sidecar ("<stem>.strikes.json") for clip `clip`.
bool strike_clip_sidecar_parse(std::string_view text, std::string_view source,
                               std::string_view clip, ClipStrikes& out, std::string& error);
/// Reads and parses a file (size-capped, never throws).
bool strike_sidecar_load(const std::filesystem::path& path, StrikeSidecar& out, std::string& error);
bool strike_clip_sidecar_load(const std::filesystem::path& path, std::string_view clip,
                              ClipStrikes& out, std::string& error);

/// Checks marks against the loaded clip: every hit_joint names a joint of `skeleton` (not an End
/// Site) and every frame is < num_frames. `source` names the sidecar file in the message.
bool strike_marks_check(const ClipStrikes& marks, const Skeleton& skeleton, int num_frames,
                        std::string_view source, std::string& error);

/// The sidecar as JSON text (2-space indent, clips sorted, trailing newline); parses back equal.
std::string strike_sidecar_write(const StrikeSidecar& sidecar);
/// Writes atomically (temporary file, then rename) so an editor never sees half a file.
bool strike_sidecar_save(const std::filesystem::path& path, const StrikeSidecar& sidecar,
                         std::string& error);

}  // namespace foresight
