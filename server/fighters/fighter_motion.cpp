#include "fighters/fighter_motion.hpp"

#include "anim/fk.hpp"

#include <cmath>

namespace foresight::server {
namespace {

constexpr int kBlendOutFrames = 6;  // after a strike, back to locomotion over 0.2 s

// The placement of a take's clip space in the world that puts the strike's start root on
// `start_root`: retargeting scales the clip's ground offsets from its origin by the legs' ratio,
// so the start root's offset is scaled the same way before it is cancelled.
Placement clip_alignment(const LimbCharacter& take, const Placement& r0, const LimbCharacter& fighter,
                         const Placement& start_root) {
  const float scale = fighter.model->leg_length_m / std::max(take.model->leg_length_m, 1e-3f);
  const float heading = wrap_angle(start_root.heading_rad - r0.heading_rad);
  return {start_root.pos_m - rotate_ground(scale * r0.pos_m, heading), heading};
}

}  // namespace

void FighterMotion::init(const FighterAssets& assets, int morphology) {
  assets_ = &assets;
  morphology_ = morphology;
  fighter_ = assets.fighter(morphology);
  const int n = fighter_.skeleton->num_joints();
  pose_.resize(n);
  last_strike_.resize(n);
}

void FighterMotion::pose_locomotion(const MotionLibrary& library, const PlaybackState& s) {
  if (striking_) return;
  Pose& sampled = sampled_;
  sampled.resize(library.num_joints());  // sized once
  motion_library_sample(library, s.segment, s.frame, s.segment_start, s.incoming_transition, sampled);
  const LimbCharacter source{&library.skeleton, &assets_->library_model};
  retarget_pose(source, sampled.local_pos_m, sampled.local_rot, playback_root(library, s), fighter_,
                playback_root(library, s), pose_.spans());
  if (blend_left_ > 0) {  // ease out of the strike's last pose
    const float w = static_cast<float>(blend_left_) / static_cast<float>(kBlendOutFrames + 1);
    for (size_t j = 0; j < pose_.local_rot.size(); ++j) pose_.local_rot[j] = glm::slerp(pose_.local_rot[j], last_strike_.local_rot[j], w);
    pose_.local_pos_m[0] = glm::mix(pose_.local_pos_m[0], last_strike_.local_pos_m[0], w);
    fk_pose(*fighter_.skeleton, pose_.local_pos_m, pose_.local_rot, pose_.global_pos_m, pose_.global_rot);
    --blend_left_;
  }
}

bool FighterMotion::start_strike(FighterRetriever& retriever, StrikeOrder order, vec3 target_m, const Placement& root,
                                 StrikeChoice& choice, std::string& error) {
  // Face the target: the query's root frame looks at it, so retrieval and the strike's alignment
  // turn the fighter towards it while the strike blends in.
  const vec2 to_target = vec2(target_m.x, target_m.z) - root.pos_m;
  const Placement facing{root.pos_m, glm::length(to_target) > 1e-3f ? std::atan2(to_target.x, to_target.y) : root.heading_rad};
  RetrievalQuery q;
  fighter_key_points_m(fighter_.model->rig, pose_.global_pos_m, facing, q.pose_key_points_m);
  q.body_size_m = fighter_.model->rig.body_size_m;
  const vec2 t = facing.inverse().apply(vec2(target_m.x, target_m.z));
  q.target_m = vec3(t.x, target_m.y, t.y);
  if (order == StrikeOrder::kPunch) q.kind = StrikeKind::kPunch;
  if (order == StrikeOrder::kKick) q.kind = StrikeKind::kKick;
  RetrievalResult r;
  if (!retriever.retrieve(q, RetrievalParams{}, r)) {
    error = "no strike of that kind in the database";
    return false;
  }
  const FighterEntry& e = assets_->database.entries[static_cast<size_t>(r.entry)];
  const LimbCharacter take = assets_->take(e.take);
  const Clip& clip = assets_->database.takes[static_cast<size_t>(e.take)].clip;
  StrikeRequest req;
  req.source = take;
  req.clip = &clip;
  req.start_frame = r.start_frame;
  req.hit_frame = e.hit_frame;
  req.end_frame = e.end_frame;
  req.kick = e.kind == StrikeKind::kKick;
  req.side = e.side == StrikeSide::kLeft ? kFighterLeft : kFighterRight;
  const Placement r0 = assets_->take_root_tracks[static_cast<size_t>(e.take)][static_cast<size_t>(r.start_frame)];
  req.alignment = clip_alignment(take, r0, fighter_, facing.compose(r.alignment));
  req.target_m = target_m;
  if (!adapter_.begin(req, fighter_, AdaptSettings{}, pose_.local_pos_m, pose_.local_rot, error)) return false;
  choice.entry = r.entry;
  choice.scope = r.scope;
  choice.target_distance_m = r.target_distance * q.body_size_m;
  striking_ = true;
  frame_ = 0;
  return true;
}

StrikeFrame FighterMotion::step_strike() {
  StrikeFrame f;
  if (!striking_) return f;
  const AdaptedFrame a = adapter_.pose_frame(frame_);
  f.effector_m = a.effector_m;
  f.reach_error_m = a.reach_error_m;
  f.hit_frame = frame_ == adapter_.hit_index();
  if (++frame_ >= adapter_.num_frames()) {
    f.finished = true;
    striking_ = false;
    last_strike_ = adapter_.pose();  // same size: no allocation
    blend_left_ = kBlendOutFrames;
  }
  return f;
}

}  // namespace foresight::server
