#include "fighter_adapt_bench.hpp"

#include "fighter_build/fighter_cast.hpp"
#include "lab/lab_experiments.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <vector>

namespace foresight::bench {
namespace {


bool finite_pose(const PoseBuffers& p) {
  for (const vec3& x : p.global_pos_m)
    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) return false;
  return true;
}

// A direction in the half space in front of the fighter (clip +Z), uniformly on the hemisphere.
vec3 forward_direction(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (;;) {
    const vec3 d(u(rng), u(rng), std::abs(u(rng)));
    const float l = glm::length(d);
    if (l > 0.05f && l <= 1.0f) return d / l;
  }
}

}  // namespace

FighterAdaptBenchResult run_fighter_adapt_bench(const FighterAdaptBenchOptions& options) {
  using Clock = std::chrono::steady_clock;
  const FighterCast cast;
  FighterAdaptBenchResult r;
  if (!cast.error.empty()) {
    r.error = cast.error;
    return r;
  }
  const author::DefaultLibrarySpec& lib = cast.library;
  const LimbModel& source_model = cast.source_model;
  const std::vector<Morphology>& morphs = cast.morphs;
  const std::vector<LimbModel>& models = cast.models;
  std::string error;

  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<double> frame_us, limb_us, torso_us, reach_cm, torso_cm, skate;
  StrikeAdapter adapter;
  int draw = 0;
  for (const author::AuthoredClip& c : lib.clips) {
    if (!c.strike) continue;
    for (size_t m = 0; m < morphs.size(); ++m) {
      const LimbCharacter fighter{&morphs[m].skeleton, &models[m]};
      StrikeRequest req;
      req.source = {&lib.skeleton, &source_model};
      req.clip = &c.clip;
      req.hit_frame = c.strike->hit_frame;
      req.kick = c.strike->kind == "kick";
      req.side = c.strike->side == "left" ? kFighterLeft : kFighterRight;
      const FighterLimb& limb = req.kick ? models[m].rig.leg[static_cast<size_t>(req.side)]
                                         : models[m].rig.arm[static_cast<size_t>(req.side)];
      // The unadapted hit-frame limb root (the alignment is the identity here; a placement would
      // only move everything rigidly).
      adapter.begin(req, fighter, AdaptSettings{}, {}, {}, error);
      adapter.pose_frame(adapter.hit_index());
      const vec3 hit_root = adapter.retargeted().global_pos_m[static_cast<size_t>(limb.root)];
      const float L = limb.length_m();
      for (int t = 0; t < options.strikes_per_case; ++t, ++draw) {
        const int cls = draw % 3;  // 0 limb, 1 torso, 2 far
        const float dist = cls == 0 ? L * (0.55f + 0.42f * unit(rng))
                         : cls == 1 ? L + 0.12f * unit(rng)
                                    : L + 0.5f + unit(rng);
        req.target_m = hit_root + forward_direction(rng) * dist;
        if (req.target_m.y < 0.05f) req.target_m.y = 0.05f + 0.3f * unit(rng);
        adapter.begin(req, fighter, AdaptSettings{}, {}, {}, error);
        const size_t support = static_cast<size_t>(adapter.support_contact_joint());
        vec3 last(0.0f), first(0.0f);
        float path = 0.0f;
        float hit_error = 0.0f;
        for (int k = 0; k < adapter.num_frames(); ++k) {
          const auto t0 = Clock::now();
          const AdaptedFrame f = adapter.pose_frame(k);
          const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
          frame_us.push_back(us);
          (f.ccd_iterations > 0 ? torso_us : limb_us).push_back(us);
          if (!finite_pose(adapter.pose())) ++r.non_finite;
          const vec3 p = adapter.pose().global_pos_m[support];
          if (k == 0) first = p;
          else path += glm::length(p - last);
          last = p;
          r.foot_drift_cm_max = std::max(r.foot_drift_cm_max, 100.0 * glm::length(p - first));
          if (k == adapter.hit_index()) hit_error = glm::length(f.effector_m - req.target_m);
          ++r.frames;
        }
        ++r.strikes;
        const float seconds = static_cast<float>(adapter.num_frames() - 1) / c.clip.fps;
        skate.push_back(100.0 * path / std::max(seconds, 1e-3f));
        if (cls == 0) {
          ++r.limb_targets;
          reach_cm.push_back(100.0 * hit_error);
        } else if (cls == 1) {
          ++r.torso_targets;
          reach_cm.push_back(100.0 * hit_error);
          torso_cm.push_back(100.0 * hit_error);
          if (hit_error > 0.01f) ++r.torso_targets_missed;
          if (hit_error > 0.01f && req.kick) ++r.torso_kick_targets_missed;
        } else {
          ++r.far_targets;
        }
      }
    }
  }
  r.adapt_us_per_frame_p50 = lab::percentile(frame_us, 50.0);
  r.adapt_us_per_frame_p99 = lab::percentile(frame_us, 99.0);
  r.limb_us_per_frame_p50 = lab::percentile(limb_us, 50.0);
  r.torso_us_per_frame_p50 = lab::percentile(torso_us, 50.0);
  r.torso_us_per_frame_p99 = lab::percentile(torso_us, 99.0);
  r.reach_error_cm_p50 = lab::percentile(reach_cm, 50.0);
  r.reach_error_cm_p99 = lab::percentile(reach_cm, 99.0);
  r.reach_error_torso_cm_p99 = lab::percentile(torso_cm, 99.0);
  double sum = 0.0;
  for (double s : skate) sum += s;
  r.foot_skate_cm_per_s = skate.empty() ? 0.0 : sum / static_cast<double>(skate.size());
  return r;
}

}  // namespace foresight::bench
