#include "fighters/fighter_assets.hpp"
#include "fighter_build/retrieval_index.hpp"
#include "fighter_build/fighter_database_build.hpp"

#include "anim/root_motion.hpp"

namespace foresight::server {

std::unique_ptr<FighterAssets> fighter_assets_build(const MotionLibrary& library,
                                                    const std::filesystem::path& strikes,
                                                    const std::filesystem::path& sidecar,
                                                    const std::filesystem::path& cache_dir, std::string& error) {
  auto a = std::make_unique<FighterAssets>();
  if (!fighter_database_add_default_library(a->database, error)) return nullptr;
  if (!strikes.empty()) {
    FolderLoadReport report;
    if (!fighter_database_add_folder(a->database, strikes, sidecar, StrikeSplitParams{}, &report, error)) return nullptr;
  }
  // A strike starts at least kMinLeadFrames before its hit: the wind-up a player sees coming (and
  // can step away from), never a fist that appears at the head a tenth of a second after the order.
  RetrievalIndexParams index_params;
  index_params.min_lead_frames = kStrikeMinLeadFrames;
  fighter_retrieval_prepare(a->database, PoseClusterParams{}, index_params, cache_dir, a->index, nullptr, nullptr);

  a->morphologies = default_morphologies();
  a->morphology_models.resize(a->morphologies.size());
  for (size_t m = 0; m < a->morphologies.size(); ++m)
    if (!limb_model_for_morphology(a->morphologies[m], a->morphology_models[m], error)) return nullptr;

  // Default-library takes are on the default skeleton, standing in its rest pose; mocap takes are
  // calibrated on their first frame (a guard stance in the shipped folders).
  LimbModel default_model;
  if (!limb_model_for_morphology(default_morphology(), default_model, error)) return nullptr;
  a->take_models.resize(a->database.takes.size());
  a->take_root_tracks.resize(a->database.takes.size());
  for (size_t t = 0; t < a->database.takes.size(); ++t) {
    const FighterTake& take = a->database.takes[t];
    extract_root_track(take.clip, find_forward_axis(take.skeleton, take.clip), a->take_root_tracks[t]);
    if (take.source == "default library") {
      a->take_models[t] = default_model;
    } else if (!limb_model_from_clip(take.skeleton, take.clip, 0, a->take_models[t], error)) {
      error = take.name + ": " + error;
      return nullptr;
    }
  }
  if (library.name == "default") {
    a->library_model = default_model;
  } else if (library.clips.empty() || !limb_model_from_clip(library.skeleton, library.clips.front(), 0, a->library_model, error)) {
    error = "fighters need the motion library's skeleton to have arms, legs, a spine and a head: " + error;
    return nullptr;
  }
  return a;
}

}  // namespace foresight::server
