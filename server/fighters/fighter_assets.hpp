#pragma once
// Everything the server's fighters share, built once at start-up (the offline half of issue 6):
// the strike database (the default library's punches and kicks, plus an optional BVH folder), its
// clusters and retrieval index, the five morphologies with their limb models, and the models of
// the takes and of the motion library's skeleton (for retargeting locomotion onto a fighter).
#include "fighter/fighter_database.hpp"
#include "fighter/limb_representation.hpp"
#include "fighter/morphology.hpp"
#include "fighter/retarget.hpp"
#include "fighter/retrieval.hpp"
#include "library/motion_library.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace foresight::server {

inline constexpr int kStrikeMinLeadFrames = 15;  ///< 0.5 s of wind-up at 30 fps.

struct FighterAssets {
  FighterDatabase database;
  FighterRetrievalIndex index;
  std::vector<Morphology> morphologies;
  std::vector<LimbModel> morphology_models;  ///< Per morphology.
  std::vector<LimbModel> take_models;        ///< Per database take.
  std::vector<std::vector<Placement>> take_root_tracks;  ///< Per take: root placement per frame, clip space.
  LimbModel library_model;                   ///< The motion library's skeleton.

  LimbCharacter fighter(int morphology) const {
    return {&morphologies[static_cast<size_t>(morphology)].skeleton, &morphology_models[static_cast<size_t>(morphology)]};
  }
  LimbCharacter take(int t) const {
    return {&database.takes[static_cast<size_t>(t)].skeleton, &take_models[static_cast<size_t>(t)]};
  }
};

/// Builds the assets for `library` (whose skeleton the avatars' locomotion plays on). `strikes`:
/// an extra BVH folder of strikes, annotated by `sidecar` (empty: the folder's strikes.json, or
/// automatic splitting); empty: the default library's strikes only. `cache_dir`: where the pose clusters are cached (empty: computed every start).
/// Null with a reason when something does not load.
std::unique_ptr<FighterAssets> fighter_assets_build(const MotionLibrary& library,
                                                    const std::filesystem::path& strikes,
                                                    const std::filesystem::path& sidecar,
                                                    const std::filesystem::path& cache_dir, std::string& error);

}  // namespace foresight::server
