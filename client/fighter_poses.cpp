#include "fighter_poses.hpp"

#include "anim/fk.hpp"
#include "protocol/quantize.hpp"

#include <algorithm>
#include <cmath>

namespace foresight::client {

namespace {

void from_wire(const protocol::FighterPoseState& f, FighterPoseSample& out) {
  out.avatar = f.avatar;
  out.morphology = f.morphology;
  out.num_joints = static_cast<uint16_t>(std::min<size_t>(f.num_joints, protocol::kMaxFighterJoints));
  out.pelvis_m = f.pelvis_m;
  for (size_t j = 0; j < out.num_joints; ++j) out.local_rot[j] = protocol::dequantize_rotation(f.rotations[j]);
}

}  // namespace

void interpolate_fighter(const FighterPoseSample& a, const FighterPoseSample& b, float alpha,
                         FighterPoseSample& out) {
  alpha = std::clamp(alpha, 0.0f, 1.0f);
  if (a.morphology != b.morphology || a.num_joints != b.num_joints) {
    out = alpha < 0.5f ? a : b;
    return;
  }
  out.avatar = a.avatar;
  out.morphology = a.morphology;
  out.num_joints = a.num_joints;
  out.pelvis_m = a.pelvis_m + alpha * (b.pelvis_m - a.pelvis_m);
  for (size_t j = 0; j < a.num_joints; ++j) {
    // q and -q are the same rotation: take the shorter arc.
    const quat qa = a.local_rot[j];
    quat qb = b.local_rot[j];
    if (glm::dot(qa, qb) < 0.0f) qb = -qb;
    out.local_rot[j] = glm::normalize(glm::slerp(qa, qb, alpha));
  }
}

FighterPoses::FighterPoses(const FighterPosesConfig& config) : config_(config) {
  config_.samples_per_fighter = std::max(config_.samples_per_fighter, 2);
  config_.max_fighters = std::max(config_.max_fighters, 1);
  tracks_.resize(static_cast<size_t>(config_.max_fighters));
  for (Track& t : tracks_) {
    t.time_s.resize(static_cast<size_t>(config_.samples_per_fighter));
    t.samples.resize(static_cast<size_t>(config_.samples_per_fighter));
  }
  order_.reserve(tracks_.size());
}

void FighterPoses::clear() {
  for (Track& t : tracks_) {
    t.live = false;
    t.count = 0;
  }
  order_.clear();
  newest_time_s_ = 0;
  has_time_ = false;
}

int FighterPoses::size() const { return static_cast<int>(order_.size()); }

FighterPoses::Track* FighterPoses::find_or_add(uint32_t avatar) {
  const auto it = std::lower_bound(order_.begin(), order_.end(), avatar,
                                   [this](size_t i, uint32_t id) { return tracks_[i].avatar < id; });
  if (it != order_.end() && tracks_[*it].avatar == avatar) return &tracks_[*it];
  for (size_t i = 0; i < tracks_.size(); ++i) {
    Track& t = tracks_[i];
    if (t.live) continue;
    t.live = true;
    t.avatar = avatar;
    t.first = 0;
    t.count = 0;
    order_.insert(it, i);  // within the reserved capacity
    return &t;
  }
  return nullptr;  // every slot taken
}

void FighterPoses::push(double server_time_s, std::span<const protocol::FighterPoseState> fighters) {
  push_entries(server_time_s, fighters, from_wire);
}

void FighterPoses::push(double server_time_s, std::span<const FighterPoseSample> poses) {
  push_entries(server_time_s, poses, [](const FighterPoseSample& p, FighterPoseSample& out) { out = p; });
}

template <class Entry, class Fill>
void FighterPoses::push_entries(double server_time_s, std::span<const Entry> entries, Fill fill) {
  if (!has_time_ || server_time_s > newest_time_s_) newest_time_s_ = server_time_s;
  has_time_ = true;
  const int cap = config_.samples_per_fighter;
  for (const Entry& f : entries) {
    Track* t = find_or_add(f.avatar);
    if (t == nullptr) continue;
    int slot;
    if (t->count > 0) {
      const int newest = (t->first + t->count - 1) % cap;
      const double newest_s = t->time_s[static_cast<size_t>(newest)];
      if (server_time_s < newest_s) continue;  // older than what we have: too late to matter
      if (server_time_s == newest_s) {
        slot = newest;  // the same tick again
      } else if (t->count < cap) {
        slot = (t->first + t->count) % cap;
        ++t->count;
      } else {
        slot = t->first;  // drop the oldest
        t->first = (t->first + 1) % cap;
      }
    } else {
      slot = t->first;
      t->count = 1;
    }
    t->time_s[static_cast<size_t>(slot)] = server_time_s;
    fill(f, t->samples[static_cast<size_t>(slot)]);
  }
  // Fighters absent for a while are gone.
  std::erase_if(order_, [this](size_t i) {
    Track& t = tracks_[i];
    const int newest = (t.first + t.count - 1) % config_.samples_per_fighter;
    const bool gone = t.count == 0 || newest_time_s_ - t.time_s[static_cast<size_t>(newest)] > config_.forget_after_s;
    if (gone) {
      t.live = false;
      t.count = 0;
    }
    return gone;
  });
}

void FighterPoses::sample(double t, std::vector<FighterPoseSample>& out) const {
  out.clear();
  const int cap = config_.samples_per_fighter;
  for (size_t index : order_) {
    const Track& track = tracks_[index];
    if (track.count == 0) continue;
    auto at = [&](int i) { return static_cast<size_t>((track.first + i) % cap); };
    // The last sample at or before t (before the oldest: the oldest, held).
    int i0 = 0;
    while (i0 + 1 < track.count && track.time_s[at(i0 + 1)] <= t) ++i0;
    const size_t s0 = at(i0);
    FighterPoseSample& shown = out.emplace_back();
    if (t <= track.time_s[s0] || i0 + 1 >= track.count) {
      shown = track.samples[s0];  // early, exactly on a sample, or late: held
    } else {
      const size_t s1 = at(i0 + 1);
      const double span = track.time_s[s1] - track.time_s[s0];
      const auto alpha = static_cast<float>((t - track.time_s[s0]) / span);
      interpolate_fighter(track.samples[s0], track.samples[s1], alpha, shown);
    }
    shown.avatar = track.avatar;
  }
}

bool fighter_joint_positions(std::span<const Morphology> morphologies, const FighterPoseSample& pose,
                             std::vector<vec3>& local_pos_m, std::vector<vec3>& global_pos_m,
                             std::vector<quat>& global_rot) {
  if (pose.morphology >= morphologies.size()) return false;
  const Skeleton& skeleton = morphologies[pose.morphology].skeleton;
  const int n = skeleton.num_joints();
  if (n == 0 || n != pose.num_joints) return false;
  const auto count = static_cast<size_t>(n);
  local_pos_m.assign(skeleton.rest_offsets_m.begin(), skeleton.rest_offsets_m.end());
  local_pos_m[0] = pose.pelvis_m;
  global_pos_m.resize(count);
  global_rot.resize(count);
  fk_pose(skeleton, local_pos_m, std::span<const quat>(pose.local_rot.data(), count), global_pos_m, global_rot);
  return true;
}

}  // namespace foresight::client
