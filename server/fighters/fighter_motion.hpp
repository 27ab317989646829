#pragma once
// A fighter's body each tick: its locomotion (the avatar's clip, retargeted onto its morphology)
// or the strike it is playing (retrieved and adapted, paper 3.3-3.4), with a short blend back to
// locomotion afterwards. The result is the pose snapshots stream to clients.
// Allocation only in init(); every tick after is allocation-free.
#include "fighter/strike_adaptation.hpp"
#include "fighters/fighter_assets.hpp"
#include "fighters/fighter_brain.hpp"
#include "library/playback.hpp"

#include <string>

namespace foresight::server {

/// What one strike frame did.
struct StrikeFrame {
  bool hit_frame = false;  ///< This is the annotated hit frame: judge it.
  bool finished = false;   ///< The strike's last frame was played.
  vec3 effector_m{0.0f};
  float reach_error_m = 0.0f;  ///< Effector to the adaptation's goal (the stored target at the hit).
};

/// A retrieved strike, for logs and tests.
struct StrikeChoice {
  int entry = -1;
  RetrievalScope scope = RetrievalScope::kCluster;
  float target_distance_m = 0.0f;  ///< The unadapted hit path's distance to the target.
};

class FighterMotion {
 public:
  void init(const FighterAssets& assets, int morphology);

  /// The locomotion pose of the avatar's playback (on the library's skeleton) onto the fighter.
  void pose_locomotion(const MotionLibrary& library, const PlaybackState& playback);
  /// Retrieves a strike for `target_m` (world) of `order`'s kind, facing the target from where the
  /// fighter stands (`root`), and starts adapting it from the current pose. False with a reason
  /// (no entry of that kind, or the adaptation refused the request).
  bool start_strike(FighterRetriever& retriever, StrikeOrder order, vec3 target_m, const Placement& root,
                    StrikeChoice& choice, std::string& error);
  /// Plays the strike's next clip frame into pose().
  StrikeFrame step_strike();

  bool striking() const { return striking_; }
  int morphology() const { return morphology_; }
  const PoseBuffers& pose() const { return striking_ ? adapter_.pose() : pose_; }
  const Skeleton& skeleton() const { return *fighter_.skeleton; }

 private:
  const FighterAssets* assets_ = nullptr;
  int morphology_ = 0;
  LimbCharacter fighter_;
  Pose sampled_;            ///< The library's pose, before retargeting.
  PoseBuffers pose_;        ///< Locomotion (and the blend after a strike).
  PoseBuffers last_strike_; ///< The strike's last frame, blended out of.
  int blend_left_ = 0;
  bool striking_ = false;
  int frame_ = 0;           ///< Strike frame index (0 = start).
  StrikeAdapter adapter_;
};

}  // namespace foresight::server
