#pragma once
// Build time: the fighter database (fighter/fighter_database.hpp) from the default library's
// strike clips and from BVH folders, annotated by a strike sidecar (strike_annotation.hpp) or
// split automatically (strike_split.hpp). docs/FIGHTER_DATABASE.md.
#include "fighter/fighter_database.hpp"
#include "fighter_build/strike_annotation.hpp"
#include "fighter_build/strike_split.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace foresight {

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
