#pragma once
// Streamed poses: NPC fighters' (and terrain avatars', client_app.cpp) (docs/CLIENT.md "Fighters"): each snapshot carries every fighter's
// pose on its morphology's skeleton (pelvis position plus quantised local joint rotations,
// ClientConnection::fighters()). FighterPoses keeps a short history per fighter, stamped with the
// snapshot's server time, and plays it back at the same render time as the avatars' snapshot
// buffer: rotations slerped and the pelvis lerped between the two samples around the time shown,
// the oldest held before it, the newest held when snapshots are late.
//
// Pure (no GL) and fixed capacity: every slot is allocated in the constructor, push() and
// sample() (into a vector whose capacity holds max_fighters) allocate nothing.
#include "fighter/morphology.hpp"
#include "transport/client_connection.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace foresight::client {

/// One fighter's pose at one moment: dequantised, ready for forward kinematics.
struct FighterPoseSample {
  uint32_t avatar = 0;     ///< The AvatarState (flag kAvatarNpc) this fighter is.
  uint8_t morphology = 0;  ///< Index into default_morphologies().
  uint16_t num_joints = 0;
  vec3 pelvis_m{0.0f};     ///< Joint 0, world.
  std::array<quat, protocol::kMaxFighterJoints> local_rot{};  ///< Joint 0: world rotation.
};

struct FighterPosesConfig {
  int samples_per_fighter = 12;  ///< History per fighter (20 Hz snapshots: 0.6 s).
  int max_fighters = 64;         ///< Fighters tracked at once; more are ignored.
  /// A fighter missing from every snapshot for this long (server time) is gone: not shown, its
  /// slot reused.
  double forget_after_s = 1.0;
};

class FighterPoses {
 public:
  explicit FighterPoses(const FighterPosesConfig& config = {});

  /// Adds the fighters of the snapshot taken at server time `server_time_s`. A time already held
  /// for a fighter replaces that sample (later parts of the same tick); an older one is ignored.
  void push(double server_time_s, std::span<const protocol::FighterPoseState> fighters);
  /// The same for poses already dequantised (terrain bodies mapped onto the default skeleton).
  void push(double server_time_s, std::span<const FighterPoseSample> poses);
  /// Forgets everything (a new session).
  void clear();

  /// Every fighter to draw at server time `t`, sorted by avatar id (cleared first).
  void sample(double t, std::vector<FighterPoseSample>& out) const;

  /// Fighters tracked (present within forget_after_s of the newest snapshot).
  int size() const;
  double newest_time() const { return newest_time_s_; }
  const FighterPosesConfig& config() const { return config_; }

 private:
  template <class Entry, class Fill>
  void push_entries(double server_time_s, std::span<const Entry> entries, Fill fill);
  struct Track {
    bool live = false;
    uint32_t avatar = 0;
    int first = 0, count = 0;  ///< Ring of samples, oldest at `first`.
    std::vector<double> time_s;
    std::vector<FighterPoseSample> samples;
  };
  Track* find_or_add(uint32_t avatar);

  FighterPosesConfig config_;
  std::vector<Track> tracks_;
  std::vector<size_t> order_;  ///< Live track indices sorted by avatar id (sample()'s order).
  double newest_time_s_ = 0;
  bool has_time_ = false;
};

/// The `alpha` (0..1) way from `a` to `b`: pelvis lerped, rotations slerped along the shorter
/// arc. Where the two differ in morphology or joint count, the nearer one as it is.
void interpolate_fighter(const FighterPoseSample& a, const FighterPoseSample& b, float alpha,
                         FighterPoseSample& out);

/// World joint positions of `pose` on its morphology's skeleton (rest offsets, joint 0 = pelvis,
/// the pose's local rotations, FK): into `global_pos_m`, with `local_pos_m` and `global_rot` as
/// scratch (resized to the skeleton, no allocation once large enough). False, with nothing
/// written, when the morphology index or the joint count does not match `morphologies`.
bool fighter_joint_positions(std::span<const Morphology> morphologies, const FighterPoseSample& pose,
                             std::vector<vec3>& local_pos_m, std::vector<vec3>& global_pos_m,
                             std::vector<quat>& global_rot);

}  // namespace foresight::client
