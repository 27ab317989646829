#include "library_build/derived_motion.hpp"

#include "author/two_bone_ik.hpp"
#include "anim/canonical_skeleton.hpp"
#include "anim/fk.hpp"
#include "anim/root_motion.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {
namespace {

constexpr float kStopStartSeconds = 0.5f;  // a stop or a start eases over half a second
constexpr float kIdleSeconds = 0.5f;       // the idle loop: short, so a stand costs little time
constexpr float kMinWalkSpeed = 0.3f, kMaxWalkSpeed = 2.2f;  // m/s: what gets stops and starts
constexpr int kMaxStarts = 12;
constexpr float kBendDegrees = 40.0f;   // per walking piece (about half a second): 80 deg/s
constexpr float kMinBendSpeed = 0.5f;   // m/s: slower steps are turned on the spot instead
// A derived clip starts or ends on the very pose it joins, but its ground placement is read from
// its own first frame, a few millimetres or a degree off the source clip's: a short blend takes
// that up so every join is exactly continuous.
constexpr int kJoinBlendFrames = 4;

float ease(float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// A pose relative to the ground placement it stands on: joint 0 in the placement's frame (its
// height as it is), the other joints parent-relative.
struct RelativePose {
  std::vector<vec3> pos;
  std::vector<quat> rot;
};

struct ClipTrack {
  std::vector<Placement> placements;
};

RelativePose relative_pose(const Clip& clip, int frame, const Placement& at) {
  RelativePose r;
  const auto p = clip.frame_pos(frame);
  const auto q = clip.frame_rot(frame);
  r.pos.assign(p.begin(), p.end());
  r.rot.assign(q.begin(), q.end());
  r.pos[0] = from_ground(rotate_ground(ground(p[0]) - at.pos_m, -at.heading_rad), p[0].y);
  r.rot[0] = quat_from_heading(-at.heading_rad) * q[0];
  return r;
}

RelativePose blend(const RelativePose& a, const RelativePose& b, float w) {
  RelativePose r = a;
  for (size_t j = 0; j < a.pos.size(); ++j) {
    r.pos[j] = glm::mix(a.pos[j], b.pos[j], w);
    const quat qb = glm::dot(a.rot[j], b.rot[j]) < 0.0f ? -b.rot[j] : b.rot[j];
    r.rot[j] = glm::normalize(glm::slerp(a.rot[j], qb, w));
  }
  return r;
}

void place(const RelativePose& r, const Placement& at, Clip& clip, int frame) {
  auto p = clip.frame_pos(frame);
  auto q = clip.frame_rot(frame);
  std::copy(r.pos.begin(), r.pos.end(), p.begin());
  std::copy(r.rot.begin(), r.rot.end(), q.begin());
  p[0] = at.apply(r.pos[0]);
  q[0] = at.apply(r.rot[0]);
}

Clip new_clip(const Skeleton& skeleton, const std::string& name, float fps, int frames) {
  Clip c;
  c.name = name;
  c.fps = fps;
  c.resize(skeleton, frames);
  return c;
}

// Ground velocity (m/s, clip space) and turn rate (rad/s) at `frame`, from its neighbours.
void velocity_at(const ClipTrack& t, int frame, float fps, vec2& v, float& turn) {
  const int n = static_cast<int>(t.placements.size());
  const int a = std::max(frame - 1, 0), b = std::min(frame + 1, n - 1);
  const float dt = static_cast<float>(b - a) / fps;
  v = (t.placements[static_cast<size_t>(b)].pos_m - t.placements[static_cast<size_t>(a)].pos_m) / dt;
  turn = (t.placements[static_cast<size_t>(b)].heading_rad - t.placements[static_cast<size_t>(a)].heading_rad) / dt;
}

// A turn on the spot in two steps with the feet planted: the body turns about the pelvis, eased;
// the foot on the turning side steps to its place in the new facing during the first half, the
// other foot in the second; a foot on the ground stays exactly where it is (two-bone leg IK).
// First and last frames are the standing pose, unturned and turned.
Clip planted_turn(const Skeleton& skeleton, const RelativePose& stand, float angle, int frames,
                  const std::string& name, float fps) {
  Clip turn = new_clip(skeleton, name, fps, frames);
  const int n = skeleton.num_joints();
  // The standing pose's world joints at heading 0, and at the turn's end.
  std::vector<vec3> global_pos(static_cast<size_t>(n)), gp(static_cast<size_t>(n));
  std::vector<quat> global_rot(static_cast<size_t>(n)), gr(static_cast<size_t>(n));
  fk_pose(skeleton, stand.pos, stand.rot, global_pos, global_rot);
  const int ankles[2] = {kCanonLeftFoot, kCanonRightFoot};
  const int hips[2] = {kCanonLeftUpLeg, kCanonRightUpLeg};
  const int lead = angle > 0.0f ? 0 : 1;  // the foot on the turning side steps first
  const Placement end{vec2(0.0f), angle};
  for (int k = 0; k < frames; ++k) {
    const float t = static_cast<float>(k) / static_cast<float>(frames - 1);
    const Placement body{vec2(0.0f), angle * ease(t)};
    place(stand, body, turn, k);
    auto pos = turn.frame_pos(k);
    auto rot = turn.frame_rot(k);
    // Globals of the turned standing pose (pelvis and hips follow the body).
    fk_pose(skeleton, pos, rot, gp, gr);
    for (int side = 0; side < 2; ++side) {
      // Swing window: the lead foot over [0.05, 0.5], the other over [0.5, 0.95].
      const float from = side == lead ? 0.05f : 0.5f, to = from + 0.45f;
      const float s = ease((t - from) / (to - from));
      const vec3 lift_off = global_pos[static_cast<size_t>(ankles[side])], landing = end.apply(lift_off);
      vec3 target = glm::mix(lift_off, landing, s);
      target.y += 0.06f * std::sin(kPi * s);  // lifted while it swings
      const float foot_yaw = angle * s;
      const int hip = hips[side];
      const int knee = hip + 1, ankle = hip + 2;
      const float upper = glm::length(skeleton.rest_offsets_m[static_cast<size_t>(knee)]);
      const float lower = glm::length(skeleton.rest_offsets_m[static_cast<size_t>(ankle)]);
      const vec3 knee_forward(std::sin(foot_yaw), 0.0f, std::cos(foot_yaw));
      const author::TwoBoneSolution leg = author::solve_two_bone(gp[static_cast<size_t>(hip)], target, upper, lower,
                                                                 knee_forward, author::HingeSide::kKnee);
      const quat pelvis = gr[static_cast<size_t>(skeleton.parents[static_cast<size_t>(hip)])];
      rot[static_cast<size_t>(hip)] = glm::normalize(glm::inverse(pelvis) * leg.upper_global);
      rot[static_cast<size_t>(knee)] = leg.lower_local;
      // The foot keeps its standing orientation, turned by its own yaw.
      const quat foot = quat_from_heading(foot_yaw) * global_rot[static_cast<size_t>(ankle)];
      rot[static_cast<size_t>(ankle)] = glm::normalize(glm::inverse(leg.upper_global * leg.lower_local) * foot);
    }
  }
  return turn;
}

// What the capture has of what steering needs (the report says so; derivation runs anyway:
// its joins are what connect every walking piece to a stand).
void detect_captured(const std::vector<ClipTrack>& tracks, float fps, DerivedMotionReport& report) {
  const int second = static_cast<int>(std::lround(fps));
  for (const ClipTrack& t : tracks) {
    const int n = static_cast<int>(t.placements.size());
    std::vector<float> speed(static_cast<size_t>(n));
    for (int f = 0; f < n; ++f) {
      vec2 v;
      float turn;
      velocity_at(t, f, fps, v, turn);
      speed[static_cast<size_t>(f)] = glm::length(v);
    }
    const int span = std::min(second, n - 1);  // a whole short clip, else a second
    for (int f = 0; span > 0 && f + span < n; ++f) {
      const int g = f + span;
      float fastest = 0.0f;
      for (int k = f; k <= g; ++k) fastest = std::max(fastest, speed[static_cast<size_t>(k)]);
      const float turned = std::fabs(t.placements[static_cast<size_t>(g)].heading_rad - t.placements[static_cast<size_t>(f)].heading_rad);
      report.captured_idle |= span == second && fastest < 0.15f && turned < radians(10.0f);
      const float travelled = glm::length(t.placements[static_cast<size_t>(g)].pos_m - t.placements[static_cast<size_t>(f)].pos_m);
      report.captured_turn_on_spot |= travelled < 0.3f * static_cast<float>(span) / fps && turned >= radians(30.0f);
    }
    const int window = static_cast<int>(std::lround(1.5f * fps));
    for (int f = 0; f < n; ++f)
      for (int g = f + 1; g < std::min(n, f + window); ++g) {
        report.captured_stop |= speed[static_cast<size_t>(f)] >= 0.8f && speed[static_cast<size_t>(g)] < 0.15f;
        report.captured_start |= speed[static_cast<size_t>(f)] < 0.15f && speed[static_cast<size_t>(g)] >= 0.8f;
      }
  }
}

}  // namespace

namespace {

// One derivation: the library's clips and graph as they grow, and what every step needs.
class Deriver {
 public:
  Deriver(const Skeleton& skeleton, std::vector<Clip>& clips, std::vector<uint32_t>& tags, MotionGraph& graph,
          DerivedMotionReport& report)
      : skeleton_(skeleton), clips_(clips), tags_(tags), graph_(graph), report_(report),
        fps_(clips[0].fps), captured_(static_cast<int>(clips.size())), captured_segments_(graph.num_segments()),
        ease_frames_(std::max(2, static_cast<int>(std::lround(kStopStartSeconds * fps_)))),
        stops_of_(clips.size(), 0), starts_of_(clips.size(), 0) {
    tracks_.resize(clips.size());
    for (size_t c = 0; c < clips.size(); ++c)
      extract_root_track(clips[c], find_forward_axis(skeleton, clips[c]), tracks_[c].placements);
  }

  void run() {
    detect_captured(tracks_, fps_, report_);
    find_standing_pose();
    add_idle_and_turns();
    add_stops_and_starts();
    // Anything that ends standing may go on to anything that starts standing.
    for (int from : standing_ends_)
      for (int to : standing_starts_) graph_.transitions.push_back({from, to, kJoinBlendFrames});
    add_bends();
    graph_.finalize();
  }

 private:
  // The standing pose: the stillest, most compact frame among the upright ones.
  void find_standing_pose() {
    std::vector<float> pelvis_heights;
    for (int c = 0; c < captured_; ++c)
      for (int f = 0; f < clips_[static_cast<size_t>(c)].num_frames; ++f)
        pelvis_heights.push_back(clips_[static_cast<size_t>(c)].frame_pos(f)[0].y);
    std::nth_element(pelvis_heights.begin(), pelvis_heights.begin() + pelvis_heights.size() / 2, pelvis_heights.end());
    const float upright = 0.93f * pelvis_heights[pelvis_heights.size() / 2];
    int best_clip = 0, best_frame = 0;
    float best_score = 1e30f;
    std::vector<vec3> pos;
    const int n = skeleton_.num_joints();
    for (int c = 0; c < captured_; ++c) {
      const Clip& clip = clips_[static_cast<size_t>(c)];
      fk_clip_positions(skeleton_, clip, pos);
      for (int f = 1; f + 1 < clip.num_frames; ++f) {
        if (clip.frame_pos(f)[0].y < upright) continue;
        const float speed = glm::length(velocity(c, f).ground);
        float ankles = 0.0f;
        for (int j : {kCanonLeftFoot, kCanonRightFoot})
          ankles += glm::length(pos[static_cast<size_t>(f + 1) * n + j] - pos[static_cast<size_t>(f - 1) * n + j]) * fps_ / 2.0f;
        // A compact pose too (arms down, feet together): the idle's body disc is what must fit
        // wherever the avatar stops. Each 10 cm of reach counts like 0.1 m/s of motion.
        const vec2 centre = ground(pos[static_cast<size_t>(f) * n]);
        float reach = 0.0f;
        for (int j = 0; j < n; ++j) reach = std::max(reach, glm::length(ground(pos[static_cast<size_t>(f) * n + j]) - centre));
        const float score = speed + 0.5f * ankles + reach;
        if (score < best_score) {
          best_score = score, best_clip = c, best_frame = f;
          report_.standing_speed_m_per_s = speed;
        }
      }
    }
    report_.standing_clip = clips_[static_cast<size_t>(best_clip)].name;
    report_.standing_frame = best_frame;
    stand_ = relative_pose(clips_[static_cast<size_t>(best_clip)], best_frame, placement(best_clip, best_frame));
  }

  void add_idle_and_turns() {
    const int idle_frames = static_cast<int>(std::lround(kIdleSeconds * fps_)) + 1;
    Clip idle = new_clip(skeleton_, "derived_idle", fps_, idle_frames);
    for (int k = 0; k < idle_frames; ++k) place(stand_, Placement{}, idle, k);
    const int id = add_clip(std::move(idle), kTagIdle);
    standing_ends_.push_back(id), standing_starts_.push_back(id);
    ++report_.idles;
    for (int degrees_turned : {45, 90, 135})
      for (int sign : {1, -1}) {
        const float angle = radians(static_cast<float>(sign * degrees_turned));
        const int frames = static_cast<int>(std::lround((0.35f + 0.45f * degrees_turned / 90.0f) * fps_)) + 1;
        Clip turn = planted_turn(skeleton_, stand_, angle, frames,
                                 std::string("derived_turn_") + (sign > 0 ? "left_" : "right_") + std::to_string(degrees_turned), fps_);
        const int turn_id = add_clip(std::move(turn), kTagIdle | kTagTurn);
        standing_ends_.push_back(turn_id), standing_starts_.push_back(turn_id);
        ++report_.turns;
      }
  }

  // Stops from the end of every walking segment; starts into walks of every curvature; a stop and
  // a start for any clip still without one.
  void add_stops_and_starts() {
    struct StartCandidate {
      int segment;
      float turn;
    };
    std::vector<StartCandidate> candidates;
    for (int s = 0; s < captured_segments_; ++s) {
      const Segment seg = graph_.segments[static_cast<size_t>(s)];  // add_stop grows the graph
      const float speed = glm::length(velocity(seg.clip, seg.end_frame).ground);
      if (speed >= kMinWalkSpeed && speed <= kMaxWalkSpeed) add_stop(s);
      const Velocity start = velocity(seg.clip, seg.first_frame);
      const float start_speed = glm::length(start.ground);
      if (seg.first_frame >= ease_frames_ && start_speed >= kMinWalkSpeed && start_speed <= kMaxWalkSpeed)
        candidates.push_back({s, start.turn});
    }
    // Candidates spread evenly by turn rate.
    std::sort(candidates.begin(), candidates.end(),
              [](const StartCandidate& a, const StartCandidate& b) { return a.turn < b.turn; });
    const size_t starts = std::min<size_t>(candidates.size(), kMaxStarts);
    for (size_t i = 0; i < starts; ++i)
      add_start(candidates[starts > 1 ? i * (candidates.size() - 1) / (starts - 1) : 0].segment);
    // A clip left without a stop or a start (a run, a backward walk, a standing take) would drop
    // out of the graph: it gets one whatever its speed, into its first segment, out of its last.
    for (int c = 0; c < captured_; ++c) {
      int first = -1, last = -1;
      for (int s = 0; s < captured_segments_; ++s)
        if (graph_.segments[static_cast<size_t>(s)].clip == c) {
          if (first < 0) first = s;
          last = s;
        }
      if (first < 0) continue;
      if (starts_of_[static_cast<size_t>(c)] == 0) add_start(first);
      if (stops_of_[static_cast<size_t>(c)] == 0) add_stop(last);
    }
  }

  // The walk plays on from the segment's end while its ground speed and turn rate ease to zero and
  // the pose blends into the standing pose.
  void add_stop(int s) {
    const Segment seg = graph_.segments[static_cast<size_t>(s)];
    const Velocity vel = velocity(seg.clip, seg.end_frame);
    const vec2 v = vel.ground;
    const float turn = vel.turn;
    Clip stop = new_clip(skeleton_, "derived_stop_" + seg.name, fps_, ease_frames_ + 1);
    Placement at = placement(seg.clip, seg.end_frame);
    float turned = 0.0f;
    const Clip& source = clips_[static_cast<size_t>(seg.clip)];
    for (int k = 0; k <= ease_frames_; ++k) {
      if (k > 0) {
        const float keep = 1.0f - ease((static_cast<float>(k) - 0.5f) / static_cast<float>(ease_frames_));
        at.pos_m += rotate_ground(v, turned) * keep / fps_;
        turned += turn * keep / fps_;
        at.heading_rad += turn * keep / fps_;
      }
      const int f = std::min(seg.end_frame + k, source.num_frames - 1);
      const RelativePose walk = relative_pose(source, f, placement(seg.clip, f));
      place(blend(walk, stand_, ease(static_cast<float>(k) / static_cast<float>(ease_frames_))), at, stop, k);
    }
    ++stops_of_[static_cast<size_t>(seg.clip)];
    const int id = add_clip(std::move(stop), kTagLocomotion);
    graph_.transitions.push_back({s, id, kJoinBlendFrames});
    standing_ends_.push_back(id);
    ++report_.stops;
  }

  // The reverse: from the standing pose into the walk's own frames before the segment, the speed
  // easing up to the walk's.
  void add_start(int s) {
    const Segment seg = graph_.segments[static_cast<size_t>(s)];
    const Velocity vel = velocity(seg.clip, seg.first_frame);
    const vec2 v = vel.ground;
    const float turn = vel.turn;
    Clip start = new_clip(skeleton_, "derived_start_" + seg.name, fps_, ease_frames_ + 1);
    Placement at = placement(seg.clip, seg.first_frame);
    float turned = 0.0f;
    const Clip& source = clips_[static_cast<size_t>(seg.clip)];
    for (int k = ease_frames_; k >= 0; --k) {
      if (k < ease_frames_) {
        const float keep = ease((static_cast<float>(k) + 0.5f) / static_cast<float>(ease_frames_));
        turned -= turn * keep / fps_;
        at.heading_rad -= turn * keep / fps_;
        at.pos_m -= rotate_ground(v, turned) * keep / fps_;
      }
      // Before the clip's first frame the walk's first pose stands in.
      const int f = std::max(seg.first_frame - ease_frames_ + k, 0);
      const RelativePose walk = relative_pose(source, f, placement(seg.clip, f));
      place(blend(stand_, walk, ease(static_cast<float>(k) / static_cast<float>(ease_frames_))), at, start, k);
    }
    ++starts_of_[static_cast<size_t>(seg.clip)];
    const int id = add_clip(std::move(start), kTagLocomotion);
    graph_.transitions.push_back({id, s, kJoinBlendFrames});
    standing_starts_.push_back(id);
    ++report_.starts;
  }

  // Walking turns sharper than the capture's: each nearly straight walking piece bent both ways.
  // Its ground path turns at a constant rate on top of the capture's own; the poses relative to
  // the ground stay the capture's, so a bent piece joins wherever its original does.
  void add_bends() {
    std::vector<std::vector<int>> bends_of(static_cast<size_t>(graph_.num_segments()));
    for (int s = 0; s < captured_segments_; ++s) {
      const Segment seg = graph_.segments[static_cast<size_t>(s)];
      const Placement a = placement(seg.clip, seg.first_frame), b = placement(seg.clip, seg.end_frame);
      const float speed = glm::length(b.pos_m - a.pos_m) / (static_cast<float>(seg.num_frames()) / fps_);
      if (speed < kMinBendSpeed || speed > kMaxWalkSpeed || std::fabs(b.heading_rad - a.heading_rad) > radians(30.0f))
        continue;
      for (int sign : {1, -1}) {
        const Clip& source = clips_[static_cast<size_t>(seg.clip)];  // add_clip below may move `clips_`
        const float bend = radians(sign * kBendDegrees);
        const int frames = seg.num_frames() + 1;
        Clip bent = new_clip(skeleton_, std::string("derived_bend_") + (sign > 0 ? "left_" : "right_") + seg.name, fps_, frames);
        Placement at = a;
        for (int k = 0; k < frames; ++k) {
          const int f = seg.first_frame + k;
          const Placement& p = placement(seg.clip, f);
          const float extra = bend * static_cast<float>(k) / static_cast<float>(frames - 1);
          if (k > 0) {
            const vec2 step = p.pos_m - placement(seg.clip, f - 1).pos_m;
            at.pos_m += rotate_ground(step, extra - 0.5f * bend / static_cast<float>(frames - 1));
          }
          at.heading_rad = p.heading_rad + extra;
          place(relative_pose(source, f, p), at, bent, k);
        }
        bends_of[static_cast<size_t>(s)].push_back(add_clip(std::move(bent), seg.tags));
        ++report_.bends;
      }
    }
    // Every transition of an original piece, for its bent copies too (in, out, and between bends).
    const size_t original_transitions = graph_.transitions.size();
    const auto variants = [&](int seg) {
      std::vector<int> out{seg};
      if (seg < static_cast<int>(bends_of.size()))
        out.insert(out.end(), bends_of[static_cast<size_t>(seg)].begin(), bends_of[static_cast<size_t>(seg)].end());
      return out;
    };
    for (size_t t = 0; t < original_transitions; ++t) {
      const Transition tr = graph_.transitions[t];
      for (int from : variants(tr.from))
        for (int to : variants(tr.to))
          if (from != tr.from || to != tr.to)
            graph_.transitions.push_back({from, to, std::max(tr.blend_frames, kJoinBlendFrames)});
    }
  }

  int add_clip(Clip clip, uint32_t tag) {
    const int id = graph_.num_segments();
    graph_.segments.push_back({clip.name, static_cast<int>(clips_.size()), 0, clip.num_frames - 1, tag});
    clips_.push_back(std::move(clip));
    tags_.push_back(tag);
    return id;
  }

  const Placement& placement(int clip, int frame) const {
    return tracks_[static_cast<size_t>(clip)].placements[static_cast<size_t>(frame)];
  }
  struct Velocity {
    vec2 ground;  ///< m/s, clip space
    float turn;   ///< rad/s
  };
  Velocity velocity(int clip, int frame) const {
    Velocity out{};
    velocity_at(tracks_[static_cast<size_t>(clip)], frame, fps_, out.ground, out.turn);
    return out;
  }

  const Skeleton& skeleton_;
  std::vector<Clip>& clips_;
  std::vector<uint32_t>& tags_;
  MotionGraph& graph_;
  DerivedMotionReport& report_;
  const float fps_;
  const int captured_;           // clips_[0, captured_) are the capture's
  const int captured_segments_;  // graph_.segments[0, captured_segments_) are theirs
  const int ease_frames_;        // frames of a stop or a start
  std::vector<ClipTrack> tracks_;
  std::vector<int> stops_of_, starts_of_;  // per captured clip
  RelativePose stand_;
  std::vector<int> standing_ends_;    // segments that end in the standing pose
  std::vector<int> standing_starts_;  // segments that begin in it
};

}  // namespace

void derive_steering_motion(const Skeleton& skeleton, std::vector<Clip>& clips, std::vector<uint32_t>& tags,
                            MotionGraph& graph, DerivedMotionReport& report) {
  report = DerivedMotionReport{};
  if (clips.empty() || skeleton.num_joints() != kCanonJointCount) return;
  Deriver(skeleton, clips, tags, graph, report).run();
}

}  // namespace foresight
