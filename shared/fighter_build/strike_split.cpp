#include "fighter_build/strike_split.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace foresight {
namespace {

struct Candidate {
  DetectedStrike strike;
  float score = 0.0f;  ///< Peak approach speed in body sizes per second.
};

int frames_of(float seconds, float fps) { return std::max(1, static_cast<int>(std::lround(seconds * fps))); }

// The highest effector speed in [from, to] (clamped) and its frame.
int speed_peak(const TakeMotionView& take, int joint, int from, int to, float& peak) {
  from = std::clamp(from, 0, take.num_frames - 1);
  to = std::clamp(to, 0, take.num_frames - 1);
  int best = from;
  peak = -1.0f;
  for (int f = from; f <= to; ++f) {
    const float v = effector_speed_mps(take, joint, f);
    if (v > peak) {
      peak = v;
      best = f;
    }
  }
  return best;
}

// True when signal[f] is the largest value within +-half frames (ties go to the earliest frame,
// so a plateau yields one maximum).
bool local_max(const std::vector<float>& signal, int f, int half) {
  const int n = static_cast<int>(signal.size());
  for (int g = std::max(0, f - half); g <= std::min(n - 1, f + half); ++g) {
    if (g == f) continue;
    if (signal[static_cast<std::size_t>(g)] > signal[static_cast<std::size_t>(f)]) return false;
    if (g < f && signal[static_cast<std::size_t>(g)] == signal[static_cast<std::size_t>(f)]) return false;
  }
  return true;
}

void find_limb_candidates(const TakeMotionView& take, const StrikeSplitParams& p, const FighterLimb& limb,
                          bool is_arm, StrikeSide side, float floor_y, std::vector<Candidate>& out) {
  const int n = take.num_frames;
  const float length = limb.length_m();
  if (!(length > 0.0f)) return;
  const int pelvis = take.rig->pelvis;
  // The hit signal: reach for arms, ankle height for legs.
  std::vector<float> signal(static_cast<std::size_t>(n));
  for (int f = 0; f < n; ++f) {
    const vec3 e = take.pos(f, limb.end);
    signal[static_cast<std::size_t>(f)] =
        is_arm ? glm::length(e - take.pos(f, limb.root)) / length : (e.y - floor_y) / length;
  }
  const int approach = frames_of(p.approach_s, take.fps);
  const int half = frames_of(0.5f * p.min_gap_s, take.fps);
  const float min_speed = p.min_speed_body_per_s * take.rig->body_size_m;
  for (int f = 1; f + 1 < n; ++f) {
    const float s = signal[static_cast<std::size_t>(f)];
    if (!local_max(signal, f, half)) continue;
    if (is_arm) {
      if (s < p.min_arm_reach) continue;
      float lowest = s;
      for (int g = std::max(0, f - approach); g < f; ++g) lowest = std::min(lowest, signal[static_cast<std::size_t>(g)]);
      if (s - lowest < p.min_reach_rise) continue;
      // In front of the body: a fist flung sideways in a spin is not a punch.
      const Placement root = take.root_track[static_cast<std::size_t>(f)];
      const vec3 local = root.inverse().apply(take.pos(f, limb.end)) - root.inverse().apply(take.pos(f, pelvis));
      if (local.z < p.min_forward_arm * length) continue;
    } else if (s < p.min_kick_height_leg) {
      continue;
    }
    float peak = 0.0f;
    speed_peak(take, limb.end, f - approach, f, peak);
    if (peak < min_speed) continue;
    Candidate c;
    c.strike.hit_joint = limb.end;
    c.strike.kind = is_arm ? StrikeKind::kPunch : StrikeKind::kKick;
    c.strike.side = side;
    c.strike.hit_frame = f;
    c.strike.peak_speed_mps = peak;
    c.score = peak / take.rig->body_size_m;
    out.push_back(c);
  }
}

}  // namespace

float effector_speed_mps(const TakeMotionView& take, int joint, int frame) {
  if (take.num_frames < 2) return 0.0f;
  const int a = std::max(0, frame - 1), b = std::min(take.num_frames - 1, frame + 1);
  const int pelvis = take.rig->pelvis;
  const vec3 ra = take.pos(a, joint) - take.pos(a, pelvis);
  const vec3 rb = take.pos(b, joint) - take.pos(b, pelvis);
  return glm::length(rb - ra) * take.fps / static_cast<float>(b - a);
}

void strike_window(const TakeMotionView& take, int hit_joint, int hit_frame, const StrikeSplitParams& p,
                   int& start, int& end) {
  assert(hit_frame >= 0 && hit_frame < take.num_frames);
  const int last = take.num_frames - 1;
  if (start < 0) {
    // Back from the approach peak until the effector was (nearly) still: the wind-up's start.
    float peak = 0.0f;
    const int lo = std::max(0, hit_frame - frames_of(p.approach_s, take.fps));
    int s = speed_peak(take, hit_joint, lo, hit_frame, peak);
    while (s > lo && effector_speed_mps(take, hit_joint, s) > p.window_speed_fraction * peak) --s;
    start = std::min(s, std::max(0, hit_frame - 1));
  }
  if (end < 0) {
    float peak = 0.0f;
    const int hi = std::min(last, hit_frame + frames_of(p.retract_s, take.fps));
    int e = speed_peak(take, hit_joint, hit_frame + 1, hi, peak);
    while (e < hi && effector_speed_mps(take, hit_joint, e) > p.window_speed_fraction * peak) ++e;
    end = std::max(e, std::min(last, hit_frame + 1));
  }
}

std::vector<DetectedStrike> strike_detect(const TakeMotionView& take, const StrikeSplitParams& p) {
  std::vector<DetectedStrike> result;
  if (take.rig == nullptr || take.num_frames < 3) return result;
  const FighterRig& rig = *take.rig;
  float floor_y = take.pos(0, rig.leg[0].end).y;
  for (int f = 0; f < take.num_frames; ++f)
    for (int side = 0; side < 2; ++side) floor_y = std::min(floor_y, take.pos(f, rig.leg[static_cast<std::size_t>(side)].end).y);

  std::vector<Candidate> candidates;
  for (int side = 0; side < 2; ++side) {
    const StrikeSide s = side == kFighterLeft ? StrikeSide::kLeft : StrikeSide::kRight;
    find_limb_candidates(take, p, rig.arm[static_cast<std::size_t>(side)], true, s, floor_y, candidates);
    find_limb_candidates(take, p, rig.leg[static_cast<std::size_t>(side)], false, s, floor_y, candidates);
  }
  // Fastest effector first; a later candidate too close in time to an accepted one is the same
  // strike seen from a limb that only followed along. Ties by frame then joint (deterministic).
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.score != b.score) return a.score > b.score;
    if (a.strike.hit_frame != b.strike.hit_frame) return a.strike.hit_frame < b.strike.hit_frame;
    return a.strike.hit_joint < b.strike.hit_joint;
  });
  const int gap = frames_of(p.min_gap_s, take.fps);
  for (const Candidate& c : candidates) {
    bool clash = false;
    for (const DetectedStrike& r : result) clash = clash || std::abs(r.hit_frame - c.strike.hit_frame) < gap;
    if (!clash) result.push_back(c.strike);
  }
  std::sort(result.begin(), result.end(),
            [](const DetectedStrike& a, const DetectedStrike& b) { return a.hit_frame < b.hit_frame; });
  for (DetectedStrike& d : result) {
    d.start_frame = -1;
    d.end_frame = -1;
    strike_window(take, d.hit_joint, d.hit_frame, p, d.start_frame, d.end_frame);
  }
  // Windows of neighbours must not overlap: one frame belongs to one strike.
  for (std::size_t i = 0; i + 1 < result.size(); ++i) {
    DetectedStrike& a = result[i];
    DetectedStrike& b = result[i + 1];
    if (a.end_frame < b.start_frame) continue;
    const int mid = (a.hit_frame + b.hit_frame) / 2;
    a.end_frame = std::clamp(std::min(a.end_frame, mid), a.hit_frame, b.hit_frame - 1);
    b.start_frame = std::clamp(std::max(b.start_frame, a.end_frame + 1), 0, b.hit_frame);
  }
  return result;
}

}  // namespace foresight
