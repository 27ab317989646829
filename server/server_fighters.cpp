// The server's NPC fighters (issue 6, docs/FIGHTER.md): spawned from the scene's NPC points, each
// tick they perceive the nearest player and their brain steers their avatar like a player's keys.
#include "server.hpp"

#include "anim/fk.hpp"
#include "fighter/fighter_rig.hpp"
#include "fighter/morphology.hpp"
#include "lookahead/scene_path.hpp"
#include "protocol/quantize.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <limits>

namespace foresight::server {

bool Server::spawn_fighters(std::string& error) {
  FighterRig rig;
  std::string rig_error;
  head_joint_ =
      fighter_rig_from_skeleton(library_.skeleton, rig, rig_error) ? rig.head : library_.skeleton.find_joint("Head");
  head_pose_.resize(library_.num_joints());
  head_global_pos_.resize(static_cast<size_t>(library_.num_joints()));
  head_global_rot_.resize(static_cast<size_t>(library_.num_joints()));

  const int wanted = config_.fighters < 0 ? static_cast<int>(scene_.npcs.size()) : config_.fighters;
  if (wanted == 0) return true;
  fighter_route_clearance_m_ = moving_body_clearance_m(library_);
  fighter_route_height_m_ = lowest_moving_body_m(library_);
  const Clock::time_point t0 = Clock::now();
  fighter_assets_ = fighter_assets_build(library_, config_.fighter_strikes, config_.fighter_strikes_sidecar,
                                         config_.fighter_cache_dir, error);
  if (!fighter_assets_) {
    error = "fighters: " + error;
    return false;
  }
  fighter_retriever_ = std::make_unique<FighterRetriever>(fighter_assets_->index);
  std::fprintf(stderr, "foresight-server: fighter database: %zu strikes from %zu takes, %d pose clusters (%.0f ms)\n",
               fighter_assets_->database.entries.size(), fighter_assets_->database.takes.size(),
               fighter_assets_->index.k,
               std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  FighterBrainConfig brain;
  brain.auto_attack = config_.fighters_auto_attack;
  brain.cooldown_s = static_cast<float>(config_.fighter_cooldown_s);
  for (int i = 0; i < wanted; ++i) {
    Placement at;
    std::string name = "fighter-" + std::to_string(i + 1);
    bool placed = false;
    if (i < static_cast<int>(scene_.npcs.size())) {
      const NpcSpawn& npc = scene_.npcs[static_cast<size_t>(i)];
      name = npc.name;
      const Placement spawn{npc.pos_m, npc.heading_rad};
      placed = find_free_place({&spawn, 1}, at);
    }
    if (!placed) placed = find_spawn(at);
    if (!placed) {
      std::fprintf(stderr, "foresight-server: no free place for fighter '%s': not spawned\n", name.c_str());
      continue;
    }
    const uint32_t id = next_avatar_++;
    // Fighters walk with the paper's controller: their strikes are planned from where the clips
    // take them, and steering's turns put the target off by more than a fist (reach error 9.8 cm
    // against under 5 cm in Fighter.StrikesWithTheMocapStrikesInTheDatabase).
    MotionTreeConfig fighter_tree = tree_config_;
    fighter_tree.steer_rad_per_s = 0.0f;
    // Footwork closes the last few tenths of a metre, where a walk's first step would touch the
    // target (without it a fighter stopped 1.3 m off side-stepped on the spot).
    fighter_tree.excluded_tags &= ~static_cast<uint32_t>(kTagFootwork);
    GraphAvatar body;
    body.id = id;
    body.npc = true;
    body.avatar = std::make_unique<LookaheadAvatar>(library_, world_, fighter_tree, spawn_segment_, at);
    const int morphology = config_.fighter_morphology >= 0 ? config_.fighter_morphology % kNumMorphologies
                                                           : i % kNumMorphologies;
    auto npc = std::make_unique<FighterNpc>(brain, morphology, name);
    npc->motion.init(*fighter_assets_, npc->morphology);
    npc->motion.pose_locomotion(library_, body.avatar->playback());
    const Handle body_handle = graph_avatars_.add(std::move(body));
    graph_avatars_.get(body_handle)->fighter = fighters_.add({id, body_handle, std::move(npc)});
    roster_.add({id, AvatarKind::kGraph, body_handle});
    reservations_.add(static_cast<int>(id), library_, spawn_segment_, 0, at);
    std::fprintf(stderr, "foresight-server: fighter %u '%s' (%s) at (%.1f, %.1f)\n", id, name.c_str(),
                 morphology_specs()[static_cast<size_t>(morphology)].name, at.pos_m.x, at.pos_m.y);
    ++num_fighters_;
  }
  return true;
}

const PoseBuffers* Server::fighter_pose(uint32_t avatar_id) const {
  const Fighter* f = fighter(avatar_id);
  return f != nullptr ? &f->npc->motion.pose() : nullptr;
}

bool Server::order_fighter(uint32_t avatar_id, StrikeOrder order) {
  Fighter* f = fighter(avatar_id);
  if (f == nullptr) return false;
  // The target is its current one (the nearest player), its head stored now.
  const GraphAvatar* target = player_avatar(f->npc->target_id);
  if (target == nullptr) return false;  // no target yet
  f->npc->brain.order(order, static_cast<double>(tick_) / config_.tick_hz, target->id, head_position(*target->avatar));
  return true;
}

std::vector<uint32_t> Server::fighter_ids() const {
  std::vector<uint32_t> ids;
  for (const Fighter& f : fighters_.items()) ids.push_back(f.id);
  return ids;
}

vec3 Server::head_position(const LookaheadAvatar& avatar) {
  const PlaybackState& s = avatar.playback();
  const Placement root = avatar.root();
  if (head_joint_ < 0) return vec3(root.pos_m.x, 1.6f, root.pos_m.y);
  motion_library_sample(library_, s.segment, s.frame, s.segment_start, s.incoming_transition, head_pose_);
  fk_pose(library_.skeleton, head_pose_.local_pos_m, head_pose_.local_rot, head_global_pos_, head_global_rot_);
  return head_global_pos_[static_cast<size_t>(head_joint_)];
}

void Server::think_fighters() {
  const double now_s = static_cast<double>(tick_) / config_.tick_hz;
  for (Fighter& f : fighters_.items()) {
    FighterNpc& npc = *f.npc;
    GraphAvatar& body = *graph_avatars_.get(f.body);
    const Placement self = body.avatar->root();
    // The nearest player is the target (fighters do not fight each other).
    const GraphAvatar* target = nullptr;
    float best = std::numeric_limits<float>::max();
    for (const GraphAvatar& p : graph_avatars_.items()) {
      if (p.npc) continue;
      const float d = glm::length(p.avatar->root().pos_m - self.pos_m);
      if (d < best) {
        best = d;
        target = &p;
      }
    }
    FighterSenses senses;
    senses.now_s = now_s;
    senses.self_pos_m = self.pos_m;
    const PlaybackState& s = body.avatar->playback();
    senses.can_strike = (library_.graph.segments[static_cast<size_t>(s.segment)].tags & kTagIdle) != 0;
    if (target != nullptr) {
      senses.has_target = true;
      senses.target_id = target->id;
      senses.target_pos_m = target->avatar->root().pos_m;
      senses.way_m = fighter_way(npc, self.pos_m, senses.target_pos_m, now_s);
      senses.target_head_m = head_position(*target->avatar);
    }
    npc.target_id = senses.has_target ? senses.target_id : 0;
    const FighterDecision d = npc.brain.think(senses);
    if (d.strike) {
      StrikeChoice choice;
      std::string error;
      if (npc.motion.start_strike(*fighter_retriever_, d.kind, d.target_head_m, self, choice, error)) {
        npc.strike_kind = d.kind;
        npc.strike_target = d.target_id;
        npc.strike_target_head_m = d.target_head_m;
      } else {
        ++counters_.fighter_strike_failures;
        std::fprintf(stderr, "foresight-server: fighter %u could not strike: %s\n", f.id, error.c_str());
        npc.brain.strike_finished(now_s);
      }
    }
    // The brain's world direction as a player's keys with the camera looking along +Z
    // (control_world_direction: yaw 0 puts forward at +Z and right at -X).
    ControlInput in;
    in.camera_dir = vec2(-d.move_world.x, d.move_world.y);
    if (in.camera_dir != body.input.camera_dir || in.camera_yaw_rad != body.input.camera_yaw_rad) {
      body.input = in;
      body.input_changed = true;
    }
  }
}

vec2 Server::fighter_way(FighterNpc& npc, vec2 from, vec2 to, double now_s) {
  // Straight at the target while a body of the walker's width sees it; else around the walls, to
  // the farthest corner of the route in sight (a target behind a wall or a dead end in between).
  if (scene_segment_clear(world_, from, to, fighter_route_clearance_m_, fighter_route_height_m_)) {
    npc.route.clear();
    return to;
  }
  if (npc.route.empty() || glm::length(to - npc.route_goal_m) > 1.0f || now_s - npc.route_at_s > 1.0) {
    npc.route_at_s = now_s;
    npc.route_goal_m = to;
    if (!scene_route(world_, from, to, fighter_route_clearance_m_, fighter_route_height_m_, npc.route)) {
      npc.route.clear();
      ++counters_.fighter_route_failures;
    }
  }
  if (npc.route.size() < 2) return to;
  for (size_t i = npc.route.size() - 1; i >= 1; --i)
    if (scene_segment_clear(world_, from, npc.route[i], fighter_route_clearance_m_, fighter_route_height_m_))
      return npc.route[i];
  return npc.route[1];
}

void Server::animate_fighters(int64_t frames_due) {
  const double now_s = static_cast<double>(tick_) / config_.tick_hz;
  for (const Fighter& f : fighters_.items()) {
    FighterMotion& motion = f.npc->motion;
    GraphAvatar& body = *graph_avatars_.get(f.body);
    for (int64_t k = 0; k < frames_due && motion.striking(); ++k) {
      const StrikeFrame frame = motion.step_strike();
      if (frame.hit_frame) judge_strike(f, frame);
      if (frame.finished) f.npc->brain.strike_finished(now_s);
    }
    if (!motion.striking()) motion.pose_locomotion(library_, body.avatar->playback());
    body.striking = motion.striking();  // the snapshot's flag
  }
}

void Server::collect_fighter_poses() {
  fighter_poses_.clear();
  fighter_rotations_.clear();
  snapshot_events_.clear();
  for (const Fighter& f : fighters_.items()) {
    const PoseBuffers& pose = f.npc->motion.pose();
    FighterPoseOut out;
    out.avatar = f.id;
    out.morphology = static_cast<uint8_t>(f.npc->morphology);
    for (int k = 0; k < 3; ++k) out.pelvis_mm[k] = protocol::quantize_mm(pose.local_pos_m[0][k]);
    out.first_rotation = fighter_rotations_.size();
    out.num_rotations = std::min(pose.local_rot.size(), protocol::kMaxFighterJoints);
    for (size_t j = 0; j < out.num_rotations; ++j) fighter_rotations_.push_back(protocol::quantize_rotation(pose.local_rot[j]));
    fighter_poses_.push_back(out);
  }
  for (const StrikeEvent& e : strike_events_) {
    if (tick_ - e.tick > protocol::kStrikeEventRepeatTicks) continue;
    snapshot_events_.emplace_back(e.sequence, e.fighter, e.target, protocol::quantize_mm(e.effector_m.x),
                                  protocol::quantize_mm(e.effector_m.y), protocol::quantize_mm(e.effector_m.z),
                                  static_cast<uint16_t>(std::clamp(e.miss_m * 1000.0f, 0.0f, 65535.0f)), e.hit,
                                  e.kick);
  }
}

void Server::judge_strike(const Fighter& f, const StrikeFrame& frame) {
  const vec3 effector_m = frame.effector_m;
  StrikeEvent e;
  e.sequence = next_strike_event_++;
  e.tick = tick_;
  e.fighter = f.id;
  e.target = f.npc->strike_target;
  e.kick = f.npc->strike_kind == StrikeOrder::kKick;
  e.effector_m = effector_m;
  e.reach_error_m = frame.reach_error_m;
  e.miss_m = std::numeric_limits<float>::max();
  if (const GraphAvatar* target = player_avatar(e.target))
    e.miss_m = glm::length(head_position(*target->avatar) - effector_m);
  e.hit = e.miss_m <= config_.fighter_hit_radius_m;
  ++counters_.fighter_strikes;
  if (e.hit) ++counters_.fighter_hits;
  if (strike_events_.size() >= kStrikeEventsKept) strike_events_.pop_front();
  strike_events_.push_back(e);
}

}  // namespace foresight::server
