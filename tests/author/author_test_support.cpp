#include "author/author_test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace foresight::author::testing {

const DefaultLibrarySpec& library() {
  static const DefaultLibrarySpec lib = build_default_library();
  return lib;
}

const AuthoredClip* find_clip(std::string_view name) {
  for (const AuthoredClip& c : library().clips)
    if (c.clip.name == name) return &c;
  return nullptr;
}

int joint(std::string_view name) { return library().skeleton.find_joint(name); }

std::vector<vec3> clip_positions(const Clip& clip) {
  std::vector<vec3> pos;
  fk_clip_positions(library().skeleton, clip, pos);
  return pos;
}

std::vector<Placement> clip_root_track(const Clip& clip) {
  std::vector<Placement> track;
  extract_root_track(clip, find_forward_axis(library().skeleton, clip), track);
  return track;
}

SkateReport foot_skate(const Clip& clip) {
  const std::vector<vec3> pos = clip_positions(clip);
  SkateReport report;
  for (const char* name : {"LeftFoot", "LeftToeBase", "RightFoot", "RightToeBase"}) {
    const int j = joint(name);
    float lowest = std::numeric_limits<float>::max();
    for (int f = 0; f < clip.num_frames; ++f) lowest = std::min(lowest, at(pos, clip, f, j).y);
    for (int f = 0; f + 1 < clip.num_frames; ++f) {
      const vec3 a = at(pos, clip, f, j), b = at(pos, clip, f + 1, j);
      const bool low = a.y <= lowest + kContactHeightM && b.y <= lowest + kContactHeightM;
      const bool still = std::abs(b.y - a.y) * clip.fps < kContactVerticalMps;
      if (!low || !still) continue;
      ++report.contact_frames;
      const float speed = glm::length(ground(b) - ground(a)) * clip.fps;
      if (speed > report.worst_mps) report = {speed, name, f, report.contact_frames};
    }
  }
  return report;
}

float transition_gap_m(const Clip& a, const Clip& b) {
  const std::vector<vec3> pa = clip_positions(a), pb = clip_positions(b);
  const Placement end_a = clip_root_track(a).back();
  const Placement start_b = clip_root_track(b).front();
  const Placement b_to_a = end_a.compose(start_b.inverse());
  float worst = 0.0f;
  for (int j = 0; j < a.num_joints; ++j) {
    const vec3 from_a = at(pa, a, a.num_frames - 1, j);
    const vec3 from_b = b_to_a.apply(at(pb, b, 0, j));
    worst = std::max(worst, glm::length(from_a - from_b));
  }
  return worst;
}

Chain chain_clips(const std::vector<std::string>& names) {
  Chain chain;
  chain.num_joints = library().skeleton.num_joints();
  Placement at_start{};
  for (size_t i = 0; i < names.size(); ++i) {
    const Clip& clip = find_clip(names[i])->clip;
    const std::vector<vec3> pos = clip_positions(clip);
    const std::vector<Placement> track = clip_root_track(clip);
    const Placement place = at_start.compose(track.front().inverse());
    const int frames = i + 1 < names.size() ? clip.num_frames - 1 : clip.num_frames;
    for (int f = 0; f < frames; ++f) {
      for (int j = 0; j < clip.num_joints; ++j) chain.pos.push_back(place.apply(at(pos, clip, f, j)));
      chain.root.push_back(place.compose(track[f]));
      ++chain.num_frames;
    }
    at_start = place.compose(track.back());
  }
  return chain;
}

float max_joint_height(const Clip& clip, int j) {
  const std::vector<vec3> pos = clip_positions(clip);
  float h = -std::numeric_limits<float>::max();
  for (int f = 0; f < clip.num_frames; ++f) h = std::max(h, at(pos, clip, f, j).y);
  return h;
}

float min_joint_height(const Clip& clip, int j) {
  const std::vector<vec3> pos = clip_positions(clip);
  float h = std::numeric_limits<float>::max();
  for (int f = 0; f < clip.num_frames; ++f) h = std::min(h, at(pos, clip, f, j).y);
  return h;
}

}  // namespace foresight::author::testing
