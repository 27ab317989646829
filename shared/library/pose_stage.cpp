#include "library/pose_stage.hpp"

#include "anim/canonical_skeleton.hpp"
#include "anim/fk.hpp"
#include "library/foot_contact.hpp"
#include "library/pose_check.hpp"
#include "math/types.hpp"
#include "world/terrain.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace foresight {
namespace {

constexpr float kPatch_m = 0.06f;          // how far a planted part's contact patch reaches round the joint
constexpr float kPastEdge_m = 0.015f;      // how far past a step's edge a nudged part is put
constexpr vec2 kPatchDirections[] = {vec2(1.0f, 0.0f), vec2(-1.0f, 0.0f), vec2(0.0f, 1.0f),
                                     vec2(0.0f, -1.0f)};
constexpr float kLandingMargin_m = 0.03f;  // how far a foot may land from where it was expected
constexpr float kHanging_m = 0.02f;        // a planted part this far over the ground under it is not on it
constexpr float kLanded_m = 0.01f;         // an inertialized foot this close to its pose's height is down
constexpr float kKneeCone_rad = 1.05f;     // 60 deg: how far a shown knee may point from the animation's
constexpr float kClearlyBent_m = 0.02f;    // an animated knee this far off its hip-ankle line has a side

// Bollo's inertialization (GDC 2018, "Inertialization: High-Performance Animation Transitions in
// Gears of War"): an offset that starts at x0 changing at v0 (with no acceleration) and dies out
// at T with its rate and acceleration (a quintic); at(t) and rate_at(t), t into it.
template <typename V>
struct Inertialized {
  V x0, v0, a = V(0.0f), b = V(0.0f), c = V(0.0f);
  float T;
  Inertialized(V x0_, V v0_, float T_) : x0(x0_), v0(v0_), T(T_) {
    if (T <= 0.0f) return;
    a = -(6.0f * v0 * T + 12.0f * x0) / (2.0f * std::pow(T, 5.0f));
    b = (16.0f * v0 * T + 30.0f * x0) / (2.0f * std::pow(T, 4.0f));
    c = -(12.0f * v0 * T + 20.0f * x0) / (2.0f * std::pow(T, 3.0f));
  }
  V at(float t) const {
    if (T <= 0.0f || t >= T) return V(0.0f);
    t = std::max(t, 0.0f);
    return x0 + t * (v0 + t * t * (c + t * (b + t * a)));
  }
  V rate_at(float t) const {
    if (T <= 0.0f || t >= T) return V(0.0f);
    t = std::max(t, 0.0f);
    return v0 + t * t * (3.0f * c + t * (4.0f * b + t * 5.0f * a));
  }
};

// One exact step of a critically damped spring (stiffness k, 1/s) moving x towards target:
// stable at any dt, no overshoot, the rate continuous.
void spring_towards(float& x, float& v, float target, float k, float dt) {
  const float e = std::exp(-k * dt), d = x - target;
  x = target + (d + (v + k * d) * dt) * e;
  v = (v - k * (v + k * d) * dt) * e;
}

// x towards target with its acceleration bounded by `accel`: at the rate that arrives in `in_s`
// when that is within reach, never faster than it can brake from to arrive at rest, and never
// past the target.
void seek(float& x, float& v, float target, float in_s, float accel, float dt) {
  if (dt <= 0.0f) return;  // no time, no move (and no 0 / 0 when in_s is 0 too)
  // The fastest rate it can still brake from within d, a frame's braking at a time.
  const float d = target - x, step = 0.5f * accel * dt;
  const float brake = std::sqrt(2.0f * accel * std::abs(d) + step * step) - step;
  const float want = std::clamp(d / std::max(in_s, dt), -brake, brake);
  v += std::clamp(want - v, -accel * dt, accel * dt);
  if ((target - (x + v * dt)) * d <= 0.0f) x = target, v = 0.0f;
  else x += v * dt;
}

// Orientation warping: how much of a canonical joint's turn lag is the upper body's spring's (the
// rest the lower body's): none for the pelvis and legs, growing up the spine, all of it from the
// chest up (arms and head included).
float upper_body_share(int joint) {
  if (joint == kCanonHips || joint >= kCanonLeftUpLeg) return 0.0f;
  if (joint == kCanonSpine) return 1.0f / 3.0f;
  if (joint == kCanonSpine1) return 2.0f / 3.0f;
  return 1.0f;
}

// The point nearest p within r of both 0 and c (a landing's last step: it changes the foot's
// rate by at most r, and the stop after it is at most r); half way to c when no point is.
vec2 nearest_in_lens(vec2 p, vec2 c, float r) {
  const float d = glm::length(c);
  if (d >= 2.0f * r) return 0.5f * c;
  const auto inside = [r](vec2 q, vec2 centre) { return glm::length(q - centre) <= r * 1.0001f; };
  if (inside(p, vec2(0.0f)) && inside(p, c)) return p;
  // Onto the disc it is outside of, if that lands it in the other.
  for (const vec2 centre : {vec2(0.0f), c}) {
    if (inside(p, centre)) continue;
    const vec2 q = centre + (p - centre) * (r / glm::length(p - centre));
    if (inside(q, centre == c ? vec2(0.0f) : c)) return q;
  }
  // Else one of the lens's two corners (d > 0 here: the discs differ).
  const vec2 along = c / d, across(-along.y, along.x);
  const float h = std::sqrt(std::max(0.0f, r * r - 0.25f * d * d));
  const vec2 a = 0.5f * c + h * across, b = 0.5f * c - h * across;
  return glm::length(p - a) <= glm::length(p - b) ? a : b;
}

}  // namespace

// Shows show(1) (all of a move: an offset, a turn lag); where that puts a shown joint in [first,
// last] in a box the played pose is clear of (set_obstacles), the largest share that does not
// (bisection, 8 halvings: within 0.4 %). The pose is left showing that share, which is returned.
template <typename Show>
float PoseStage::show_clear(Show&& show, size_t first, size_t last) {
  show(1.0f);
  if (obstacles_ == nullptr || !shown_into_obstacle(first, last)) return 1.0f;
  float clear = 0.0f, stopped = 1.0f;
  for (int i = 0; i < 8; ++i) {
    const float mid = 0.5f * (clear + stopped);
    show(mid);
    (shown_into_obstacle(first, last) ? stopped : clear) = mid;
  }
  show(clear);
  return clear;
}

PoseStage::PoseStage(const MotionLibrary& library, PoseStageConfig config)
    : library_(library), config_(config) {
  // A jump is anything beyond the fastest joint of any clip (a kick's foot, about 0.3 m a frame
  // at 30 fps), with a margin for root steering's rotation of the whole body.
  jump_m_ = 1.25f * library.max_joint_step_m + 0.02f;
  const auto n = static_cast<size_t>(library.num_joints());
  animated_.resize(n);
  shown_.resize(n);
  previous_.resize(n);
  previous_animated_.resize(n);
  offset_.resize(n);
  offset_rate_.resize(n);
  sampled_.resize(n);
  frame_pose_.resize(n);
  previous_frame_pose_.resize(n);
  landing_.resize(n);
  unturned_.resize(n);
  offset_now_.resize(n);
  unguarded_.resize(n);
  guard_from_.resize(n);
  guard_offset_.assign(n, vec3(0.0f));
  guard_rate_.assign(n, vec3(0.0f));
  shown_rate_.resize(n);
  rotations_.resize(n);
  turn_share_.resize(n);
  const bool canonical = library.num_joints() == kCanonJointCount;
  for (size_t j = 0; j < n; ++j)
    turn_share_[j] = config_.orientation_warping && canonical ? upper_body_share(static_cast<int>(j)) : 1.0f;
}

// Everything carried from frame to frame: before, only the previous frame and the ground were
// forgotten, so a jump's decaying offset, a turn's lag and the foot locks went on pulling the
// next pose towards where the avatar had been (0.8 m: test AfterResetItShowsWhatANewStageWould).
void PoseStage::reset() {
  has_previous_ = has_ground_ = has_shown_rate_ = false;
  std::fill(guard_offset_.begin(), guard_offset_.end(), vec3(0.0f));
  std::fill(guard_rate_.begin(), guard_rate_.end(), vec3(0.0f));
  turn_lag_[0] = turn_lag_[1] = TurnLag{};
  offset_left_s_ = 0.0f;
  for (FootLock& f : feet_) f = FootLock{};
  has_pose_parts_[0] = has_pose_parts_[1] = false;
  body_y_ = body_vy_ = 0.0f;
  for (int foot = 0; foot < 2; ++foot) {
    foot_y_[foot] = foot_vy_[foot] = 0.0f;
    front_lift_[foot][0] = front_lift_[foot][1] = front_lift_v_[foot][0] = front_lift_v_[foot][1] = 0.0f;
    foothold_nudge_[foot] = swing_nudge_[foot] = vec2(0.0f);
  }
}

std::span<const vec3> PoseStage::update(const PlaybackState& state, float dt_s, float frame_alpha) {
  playback_pose(library_, state, pose_);
  fk_pose(library_.skeleton, pose_.local_pos_m, pose_.local_rot, frame_pose_, rotations_);
  animated_ = frame_pose_;
  if (frame_alpha > 0.0f) {  // between two frames: joint positions interpolated, as drawn before
    PlaybackState next = state;
    next.frame += 1;
    playback_pose(library_, next, pose_);
    fk_pose(library_.skeleton, pose_.local_pos_m, pose_.local_rot, shown_, rotations_);
    for (size_t j = 0; j < animated_.size(); ++j) animated_[j] += frame_alpha * (shown_[j] - animated_[j]);
  }
  const Segment& seg = library_.graph.segments[state.segment];
  const int clip_frame = std::min(seg.first_frame + state.frame, library_.clips[seg.clip].num_frames - 1);
  contact_ = library_.foot_contact.empty() ? 0 : library_.foot_contact_at(seg.clip, clip_frame);
  shown_ = animated_;
  foothold_nudge_[0] = foothold_nudge_[1] = vec2(0.0f);  // set by adapt_to_ground, if it runs
  if (config_.inertialization) inertialize(state, dt_s);
  if (config_.turn_easing) ease_turn(state, dt_s);
  if (config_.ground_adaptation && ground_ != nullptr) adapt_to_ground(state, frame_alpha, dt_s);
  if (config_.foot_locking && library_.num_joints() > kCanonRightToeEnd)
    for (int foot = 0; foot < 2; ++foot) lock_foot(foot, dt_s);
  guard_acceleration(state, dt_s);
  has_shown_rate_ = has_previous_ && dt_s > 0.0f;
  if (has_shown_rate_)
    for (size_t j = 0; j < shown_.size(); ++j) shown_rate_[j] = (shown_[j] - previous_[j]) / dt_s;
  previous_ = shown_;
  previous_animated_ = animated_;
  previous_frame_pose_.swap(frame_pose_);
  previous_state_ = state;
  has_previous_ = true;
  return shown_;
}

void PoseStage::guard_acceleration(const PlaybackState& state, float dt_s) {
  std::copy(shown_.begin(), shown_.end(), unguarded_.begin());
  if (!config_.acceleration_guard || library_.pop_threshold_m <= 0.0f) return;  // (no threshold: nothing to keep within)
  // A planted foot (ankle, ball, toe end) stays where it is held: the guard neither moves it nor
  // judges it (its lock's own moves are the lock's: a step's arc, a roll).
  const bool legs = library_.num_joints() > kCanonRightToeEnd;
  bool held[2] = {false, false};
  const auto held_joint = [&](size_t j) {
    for (int foot = 0; foot < 2; ++foot)
      if (held[foot] && j >= static_cast<size_t>(foot_heel_joint(foot)) && j <= static_cast<size_t>(foot_heel_joint(foot)) + 2)
        return true;
    return false;
  };
  if (legs)
    for (int foot = 0; foot < 2; ++foot) held[foot] = feet_[foot].locked;
  bool offset = false;
  for (size_t j = 0; j < shown_.size(); ++j) {
    vec3& o = guard_offset_[j];
    vec3& v = guard_rate_[j];
    if (held_joint(j)) o = v = vec3(0.0f);
    if (o == vec3(0.0f) && v == vec3(0.0f)) continue;
    for (int a = 0; a < 3; ++a) spring_towards(o[a], v[a], 0.0f, config_.guard_stiffness, dt_s);
    // Done at a mm (the spring's tail would keep the legs' solve and the obstacle check running
    // for another half second; the snap is 1 mm/frame^2, under 1 % of a pop).
    if (glm::dot(o, o) < 1e-6f && glm::dot(v, v) < 1e-4f) o = v = vec3(0.0f);
    shown_[j] += o;
    offset = true;
  }
  const bool judged = has_shown_rate_ && dt_s > 0.0f;  // the last frame's rates (update() sets them after this)
  // The largest change of velocity a frame may show: the threshold is per clip frame (m per
  // frame^2), a change of velocity of threshold x fps.
  const float allowed = config_.guard_share * library_.pop_threshold_m * fps(state);
  const auto largest_change = [&] {  // (squared until the end: this runs once per bisection step)
    float largest = 0.0f;
    for (size_t j = 0; judged && j < shown_.size(); ++j)
      if (!held_joint(j)) {
        const vec3 change = (shown_[j] - previous_[j]) / dt_s - shown_rate_[j];
        largest = std::max(largest, glm::dot(change, change));
      }
    return std::sqrt(largest);
  };
  const float largest = largest_change();
  if (offset || largest > allowed) {
    // Each joint's change of velocity held back by `share` alike (a bone's length changes by that
    // share of its ends' difference), then the legs at their bones' lengths again, the knee on
    // its side: a held foot where it is held, one in the air on a leg no straighter than the
    // pose's. The knees that solves for are judged too: the least share that keeps every joint
    // within the bound (bisection) is shown.
    std::copy(shown_.begin(), shown_.end(), guard_from_.begin());
    const auto show = [&](float share) {
      for (size_t j = 0; j < shown_.size(); ++j)
        shown_[j] = guard_from_[j] -
                    (judged && !held_joint(j) ? share * ((guard_from_[j] - previous_[j]) - shown_rate_[j] * dt_s) : vec3(0.0f));
      if (legs)
        for (int foot = 0; foot < 2; ++foot) reach(foot, vec3(0.0f), held[foot] ? Reach::kFoot : Reach::kFootNoStraighter);
      return largest_change() <= allowed;
    };
    float share = largest > allowed ? 1.0f - allowed / largest : 0.0f;
    if (!show(share)) {
      float low = share, high = 1.0f;
      for (int i = 0; i < 6; ++i) {
        const float mid = 0.5f * (low + high);
        (show(mid) ? high : low) = mid;
      }
      share = high;
      show(share);
    }
    if (share > 0.0f) ++guarded_frames_;
    // Where what it holds back would show a joint in a box the played pose is clear of (a hand
    // going on into a wall the walk turned away from), as much of it as stays clear is shown.
    std::copy(shown_.begin(), shown_.end(), guard_from_.begin());
    const float clear = show_clear(
        [&](float part) {
          for (size_t j = 0; j < shown_.size(); ++j) shown_[j] = unguarded_[j] + part * (guard_from_[j] - unguarded_[j]);
        },
        0, shown_.size() - 1);
    for (size_t j = 0; j < shown_.size(); ++j) guard_offset_[j] = shown_[j] - unguarded_[j], guard_rate_[j] *= clear;
  }
}

void PoseStage::ease_turn(const PlaybackState& state, float dt_s) {
  // The steering's turn this frame: the same segment playing on with its start rotated.
  if (has_previous_ && state.segment == previous_state_.segment && state.frame >= previous_state_.frame)
    for (TurnLag& lag : turn_lag_)
      lag.offset_rad -= wrap_angle(state.segment_start.heading_rad - previous_state_.segment_start.heading_rad);
  bool turning = false;
  for (int part = 0; part < 2; ++part) {
    TurnLag& lag = turn_lag_[part];
    spring_towards(lag.offset_rad, lag.speed_rad_s, 0.0f, part == 0 ? config_.lower_turn_stiffness : config_.turn_stiffness, dt_s);
    if (std::abs(lag.offset_rad) < 1e-5f && std::abs(lag.speed_rad_s) < 1e-4f) lag = TurnLag{};
    turning = turning || lag.offset_rad != 0.0f;
  }
  if (!turning) return;
  // About the root where it stands (the steering itself turns about where it stood the frame
  // before, playback_steer_pivot; easing about that point measured worse: maze 4.1 pops a minute).
  const vec2 pivot = playback_root(library_, state).pos_m;
  std::copy(shown_.begin(), shown_.end(), unturned_.begin());
  // Where the lag would show a joint (a hand swinging behind the turn) in a box the played pose
  // is clear of, as much of it as stays clear is shown, and it goes on from there.
  const float clear = show_clear([&](float share) { turn_about(pivot, share); }, 0, shown_.size() - 1);
  for (TurnLag& lag : turn_lag_) lag.offset_rad *= clear, lag.speed_rad_s *= clear;
}

void PoseStage::turn_about(vec2 pivot, float share) {
  for (size_t j = 0; j < shown_.size(); ++j) {
    const float yaw = share * (turn_lag_[0].offset_rad +
                               turn_share_[j] * (turn_lag_[1].offset_rad - turn_lag_[0].offset_rad));
    const vec2 g = pivot + rotate_ground(ground(unturned_[j]) - pivot, yaw);
    shown_[j] = vec3(g.x, unturned_[j].y, g.y);
  }
}

bool PoseStage::shown_into_obstacle(size_t first, size_t last) const {
  const BodyHeights shown = body_heights(library_, shown_), played = body_heights(library_, animated_);
  for (size_t j = first; j <= last; ++j)
    if (joint_flesh_collides(library_, *obstacles_, shown_[j], shown) &&
        !joint_flesh_collides(library_, *obstacles_, animated_[j], played))
      return true;
  return false;
}

// The ground under the ball of `foot` where the clip next plants that foot: the first planted
// frame of the playing segment after this one, or the segment's end (where its successor starts)
// if the foot lands later. Steering may still turn the segment; this is asked again every frame.
// `height` is the ground under the part it will rest on, `at` where that part lands, `in_s` when.
bool PoseStage::landing_ground(const PlaybackState& state, float frame_alpha, int foot, float& height, float& in_s,
                               vec2& at) {
  const Segment& seg = library_.graph.segments[state.segment];
  const int last_clip_frame = library_.clips[seg.clip].num_frames - 1;
  const uint8_t bits = foot_ball_bit(foot) | foot_heel_bit(foot);
  PlaybackState landing = state;
  uint8_t lands = 0;
  // (A client may show a segment's end, frame == num_frames(), before its successor is known.)
  for (landing.frame = std::min(state.frame + 1, seg.num_frames()); landing.frame < seg.num_frames(); ++landing.frame)
    if ((lands = bits & library_.foot_contact_at(seg.clip, std::min(seg.first_frame + landing.frame, last_clip_frame))))
      break;
  in_s = (static_cast<float>(landing.frame - state.frame) - frame_alpha) / library_.clips[seg.clip].fps;
  playback_pose(library_, landing, pose_);
  fk_pose(library_.skeleton, pose_.local_pos_m, pose_.local_rot, landing_, rotations_);
  // It will rest as a planted foot does (adapt_to_ground): on its heel, or on its ball when only
  // the ball lands or the ball's ground is a step above the heel's.
  const vec3 heel = landing_[static_cast<size_t>(foot_heel_joint(foot))];
  const vec3 ball = landing_[static_cast<size_t>(foot_ball_joint(foot))];
  float gh = 0.0f, gb = 0.0f;
  const bool has_heel = lowest_ground_near(ground(heel), gh), has_ball = lowest_ground_near(ground(ball), gb);
  const bool on_ball =
      lands == foot_ball_bit(foot) || (has_ball && has_heel && gb - gh > 0.5f * glm::length(ball - heel));
  height = on_ball || !has_heel ? gb : gh;
  at = ground(on_ball || !has_heel ? ball : heel);
  return on_ball || !has_heel ? has_ball : has_heel;
}

// The shortest move of p on the ground plane along an axis that puts it over ground within 1 cm
// of `height` (the edge at most kPatch_m away), and kPastEdge_m past the edge; none if no such.
vec2 PoseStage::nudge_onto(vec2 p, float height) const {
  const auto on = [&](vec2 q) {
    float g = 0.0f;
    return terrain_height_at(*ground_, q, g) && std::abs(g - height) <= 0.01f;
  };
  if (on(p)) return vec2(0.0f);
  vec2 best(0.0f);
  float shortest = 2.0f;
  for (const vec2 d : kPatchDirections) {
    if (!on(p + kPatch_m * d)) continue;
    float off = 0.0f, in = 1.0f;  // the edge lies between
    for (int i = 0; i < 6; ++i) (on(p + (0.5f * (off + in)) * kPatch_m * d) ? in : off) = 0.5f * (off + in);
    if (in < shortest) shortest = in, best = (in * kPatch_m + kPastEdge_m) * d;
  }
  return best;
}

// The ground at p, or the lower side of a step's edge within kLandingMargin_m of it: where a
// swinging foot will land moves by a few cm while steering turns and a transition blends in, and
// a foot that then lands on the edge is nudged off it (adapt_to_ground).
bool PoseStage::lowest_ground_near(vec2 p, float& height) const {
  if (!terrain_height_at(*ground_, p, height)) return false;
  for (const vec2 d : kPatchDirections) {
    float g = 0.0f;
    if (terrain_height_at(*ground_, p + kLandingMargin_m * d, g)) height = std::min(height, g);
  }
  return true;
}

void PoseStage::adapt_to_ground(const PlaybackState& state, float frame_alpha, float dt_s) {
  if (library_.num_joints() <= kCanonRightToeEnd) return;
  // The ground is read where each part will be shown: a locked foot (lock_foot, next) is moved on
  // the ground plane so its held part stands where it is held, and its other parts with it.
  // A foot being let go of (lifted, or landing again before its offset has decayed) is shown at
  // the rest of that offset.
  vec2 lock_shift[2];
  for (int foot = 0; foot < 2; ++foot) {
    const FootLock& lock = feet_[foot];
    if (lock.locked) lock_shift[foot] = ground(lock.at) - ground(shown_[static_cast<size_t>(lock.joint)]);
    else lock_shift[foot] = ground(let_go_offset(lock, lock.release_left_s - dt_s));
  }
  const auto height_at = [this, &lock_shift](int foot, size_t joint, float& h) {
    return terrain_height_at(*ground_, ground(shown_[joint]) + lock_shift[foot], h);
  };
  // A planted part rests on the surface under its contact patch (a few cm across) nearest the
  // foot's height: a part that lands on or creeps over a step's edge stays on the step it stands
  // on, the foot nudged off the edge, instead of taking the other step's height at once. The
  // foot's other planted part is nudged onto that surface too when the foot could not pitch to
  // its own (a ball a few cm past the edge the heel stands behind).
  const auto foothold = [this, &lock_shift](int foot, size_t part, size_t other, bool other_down, float reach,
                                            float& h) {
    const vec2 at = ground(shown_[part]) + lock_shift[foot];
    for (const vec2 d : kPatchDirections) {
      float g = 0.0f;
      if (terrain_height_at(*ground_, at + kPatch_m * d, g) &&
          std::abs(g - foot_y_[foot]) + 0.01f < std::abs(h - foot_y_[foot]))
        h = g;
    }
    vec2 nudge = nudge_onto(at, h);
    float g = 0.0f;
    const vec2 other_at = ground(shown_[other]) + lock_shift[foot] + nudge;
    if (other_down && terrain_height_at(*ground_, other_at, g) && std::abs(g - h) > reach) nudge += nudge_onto(other_at, h);
    foothold_nudge_[foot] = nudge;
    lock_shift[foot] += nudge;
  };
  float target[2], landing_in_s[2] = {0.0f, 0.0f};
  bool planted_now[2];
  for (int foot = 0; foot < 2; ++foot) {
    const auto heel = static_cast<size_t>(foot_heel_joint(foot)), ball = static_cast<size_t>(foot_ball_joint(foot));
    const bool heel_down = contact_ & foot_heel_bit(foot), ball_down = contact_ & foot_ball_bit(foot);
    float gh = 0.0f, gb = 0.0f;
    const bool has_heel = height_at(foot, heel, gh), has_ball = height_at(foot, ball, gb);
    target[foot] = foot_y_[foot];  // over a hole: where it was
    planted_now[foot] = has_ground_ && ((heel_down && has_heel) || (ball_down && has_ball));
    // Across a stair's edge (the ball's ground higher than the foot can pitch to, below) the foot
    // rests on the step with its heel hanging, as a foot on a stair does; otherwise on its heel.
    const float pitch_reach = 0.5f * glm::length(shown_[ball] - shown_[heel]);
    if (heel_down && ball_down && has_heel && has_ball && gb - gh > pitch_reach) {
      target[foot] = gb;
      foothold(foot, ball, heel, false, pitch_reach, target[foot]);
    } else if (heel_down && has_heel) {  // the ball then pitches to its own ground
      target[foot] = gh;
      foothold(foot, heel, ball, ball_down, pitch_reach, target[foot]);
    } else if (ball_down && has_ball) {
      target[foot] = gb;
      foothold(foot, ball, heel, false, pitch_reach, target[foot]);
    } else if (has_ball || has_heel) {
      // Swinging: the foot goes to the ground where it will land, over the rest of the swing, so
      // that it lands there (a step up is taken while the foot is in the air), and never below
      // the ground under its front (a step down waits for the edge).
      lowest_ground_near(ground(shown_[has_ball ? ball : heel]) + lock_shift[foot], target[foot]);  // found: has_*
      float landing = 0.0f;
      vec2 landing_at(0.0f);
      // A step up found too late to be taken without a pop is not when the foot can land short of
      // it (below); a landing on an edge is nudged off it.
      if (landing_ground(state, frame_alpha, foot, landing, landing_in_s[foot], landing_at)) {
        const bool rises = landing - foot_y_[foot] <= config_.max_foot_rise_mps * std::max(landing_in_s[foot], dt_s);
        // Where a step up is not taken, the foot lands on the ground nearest its height within
        // its contact patch (foothold); with none there (the landing well onto the step) it must
        // climb however late: over the rest of the swing, not in the last frame under its front.
        float lands_on = landing;
        if (!rises)
          for (const vec2 d : kPatchDirections) {
            float g = 0.0f;
            if (terrain_height_at(*ground_, landing_at + kPatch_m * d, g) &&
                std::abs(g - foot_y_[foot]) < std::abs(lands_on - foot_y_[foot]))
              lands_on = g;
          }
        if (lands_on == landing) target[foot] = std::max(target[foot], landing);
        // A landing on a step's edge will be nudged off it onto the side the foot comes down on
        // (foothold, when planted): the swing goes there over the rest of its way, so the foot
        // does not jump on its first frame down.
        const vec2 off_edge = nudge_onto(landing_at, lands_on);
        swing_nudge_[foot] += (off_edge - swing_nudge_[foot]) * std::min(1.0f, dt_s / std::max(landing_in_s[foot], dt_s));
      }
    }
    if (planted_now[foot] || !has_ground_) swing_nudge_[foot] = vec2(0.0f);  // a planted foot's is the lock's
  }
  const float body_target = std::min(target[0], target[1]);
  if (!has_ground_) {
    for (int foot = 0; foot < 2; ++foot) foot_y_[foot] = target[foot], foot_vy_[foot] = 0.0f;
    body_y_ = body_target;
    body_vy_ = 0.0f;
    has_ground_ = true;
  } else {
    for (int foot = 0; foot < 2; ++foot) {
      float& y = foot_y_[foot];
      float& vy = foot_vy_[foot];
      const bool at_rest = std::abs(vy) * dt_s <= kLanded_m;
      if (planted_now[foot] && at_rest && std::abs(target[foot] - y) <= config_.planted_snap_m) {
        // A planted foot a little off its ground (it landed where the swing did not expect) is
        // put on it: a few cm in one frame is a smaller acceleration than a landing's own. (Not
        // one still climbing fast: stopping it dead would be a pop; it lands late, below.)
        y = target[foot];
        vy = 0.0f;
      } else if (planted_now[foot]) {
        // The clip plants a foot that is not down yet (a step up or down found too late to take
        // in the air: steering turned the landing across an edge in the swing's last frames): it
        // goes on to the ground at the bounded acceleration and lands late, not planted (neither
        // held nor counted on the ground) until it is there and has come to rest.
        seek(y, vy, target[foot], 0.0f, config_.max_foot_ground_accel_mps2, dt_s);
        const bool down_at_rest = std::abs(target[foot] - y) <= kLanded_m && std::abs(vy) * dt_s <= kLanded_m;
        if (down_at_rest) y = target[foot], vy = 0.0f;
        else contact_ &= static_cast<uint8_t>(~(foot_heel_bit(foot) | foot_ball_bit(foot)));
      } else if (landing_in_s[foot] > 0.0f) {
        // In the air: at the rate that arrives when it lands (asked again every frame). Raised
        // with its acceleration bounded (a step up that steering turned the landing onto late is
        // reached late, above, not popped to); lowered at that rate at once (a step down waits for
        // the edge, and the body, never above the lower foot, follows it down: measured, a
        // bounded start there bent the standing knee faster).
        if (target[foot] < y) {
          vy = (target[foot] - y) / std::max(landing_in_s[foot], dt_s);
          y += vy * dt_s;
        } else {
          seek(y, vy, target[foot], landing_in_s[foot], config_.max_foot_ground_accel_mps2, dt_s);
        }
      } else {
        spring_towards(y, vy, target[foot], config_.foot_ground_stiffness, dt_s);
      }
    }
    spring_towards(body_y_, body_vy_, body_target, config_.body_ground_stiffness, dt_s);
  }
  // The body never stays above the lower foot: that leg could not reach down.
  const float body = std::min({body_y_, foot_y_[0], foot_y_[1]});
  for (vec3& p : shown_) p.y += body;
  for (int foot = 0; foot < 2; ++foot) {
    reach(foot, vec3(swing_nudge_[foot].x, foot_y_[foot] - body, swing_nudge_[foot].y));
    // The foot aligned to the slope: the ball follows the ground's rise from where the foot is
    // held, then the toe from the ball, each pitched about its parent by at most 30 degrees. A
    // swinging foot only lifts its front over ground that rises under it: it does not reach down
    // (it may be carried above the ground under it towards a step up).
    const auto ankle = static_cast<size_t>(foot_heel_joint(foot)), toe = ankle + 2;
    const bool planted = contact_ & (foot_heel_bit(foot) | foot_ball_bit(foot));
    float from = foot_y_[foot];
    for (size_t part = ankle + 1; part <= toe; ++part) {
      float g = 0.0f;
      if (!height_at(foot, part, g)) break;
      const vec3 parent = shown_[part - 1];
      const float length = glm::length(shown_[part] - parent);
      float rise = std::clamp(g - from, planted ? -0.5f * length : 0.0f, 0.5f * length);
      from = g;
      // A swinging foot's front is lifted at the bounded acceleration (a step's edge passing under
      // it does not flick it up in a frame); a planted one is pitched to its ground at once.
      float& lift = front_lift_[foot][part - ankle - 1];
      float& lift_v = front_lift_v_[foot][part - ankle - 1];
      if (planted) lift = rise, lift_v = 0.0f;
      else seek(lift, lift_v, rise, 0.0f, config_.max_foot_ground_accel_mps2, dt_s), rise = lift;
      if (length < 1e-4f || std::abs(rise) < 1e-5f) continue;
      const vec3 raised = shown_[part] + vec3(0.0f, rise, 0.0f) - parent;
      const vec3 delta = parent + raised * (length / glm::length(raised)) - shown_[part];
      for (size_t j = part; j <= toe; ++j) shown_[j] += delta;
    }
    // A part the clip plants that is shown well above the ground under it (a ball past a step's
    // edge the foot stands on, the foot still coming down to lower ground) hangs: not planted.
    for (const auto& [part, bit] : {std::pair{ankle, foot_heel_bit(foot)}, std::pair{ankle + 1, foot_ball_bit(foot)}}) {
      float g = 0.0f;
      if ((contact_ & bit) && terrain_height_at(*ground_, ground(shown_[part]), g) &&
          shown_[part].y - animated_[part].y - g > kHanging_m)
        contact_ &= static_cast<uint8_t>(~bit);
    }
  }
}

void PoseStage::inertialize(const PlaybackState& state, float dt_s) {
  const size_t n = animated_.size();
  if (has_previous_) {
    // Another segment entered without a transition (a fallback to idle) is a jump however little
    // its joints move (a transition's blend carries the pose on, a fallback nothing); so is any
    // joint moving further in a frame than the clips ever do. (An idle restarted by a fallback
    // while standing is left to the jump test: its loop's ends meet.)
    const bool switched = state.segment != previous_state_.segment;
    bool jumped = switched && state.incoming_transition < 0;
    for (size_t j = 0; j < n && !jumped; ++j) jumped = glm::length(animated_[j] - previous_animated_[j]) > jump_m_;
    if (jumped) {
      // What was shown last frame is where the new pose starts from: the jump is carried as an
      // offset and decays. Foot locks are taken again where the feet now are.
      float farthest = 0.0f;
      for (size_t j = 0; j < n; ++j) {
        offset_[j] = previous_[j] - animated_[j], offset_rate_[j] = vec3(0.0f);
        farthest = std::max(farthest, glm::length(offset_[j]));
      }
      // The quintic's largest acceleration is 5.77 x its distance / its time^2: a long jump (a
      // 1 m correction) dies out more slowly, within the acceleration guard's (6.), instead of
      // being held back by it and overshooting.
      offset_span_s_ = config_.inertialize_s;
      if (config_.acceleration_guard && library_.pop_threshold_m > 0.0f)
        offset_span_s_ = std::max(offset_span_s_, std::sqrt(5.7735f * farthest / (config_.guard_share * library_.pop_threshold_m)) /
                                                      fps(state));
      offset_left_s_ = offset_span_s_;
      ++discontinuities_;
      for (FootLock& f : feet_) f = FootLock{};
      has_pose_parts_[0] = has_pose_parts_[1] = false;  // their rates would span the jump
      turn_lag_[0] = turn_lag_[1] = TurnLag{};
      dt_s = 0.0f;
    } else if (switched && dt_s > 0.0f) {
      carry_switch(state, dt_s);
      dt_s = 0.0f;
    }
  }
  offset_left_s_ = std::max(0.0f, offset_left_s_ - dt_s);
  const float T = offset_span_s_;
  if (offset_left_s_ > 0.0f) {
    for (size_t j = 0; j < n; ++j) offset_now_[j] = Inertialized(offset_[j], offset_rate_[j], T).at(T - offset_left_s_);
    // Where an offset carried on would show a joint in a box the played pose is clear of (a
    // switch's carried forearm swinging on 1 cm into the wall the new segment turns along: Bandai
    // maze, measured), as much of it as stays clear is shown, and it goes on from there (the
    // offset is linear in its start).
    const float clear = show_clear(
        [&](float share) {
          for (size_t j = 0; j < n; ++j) shown_[j] = animated_[j] + share * offset_now_[j];
        },
        0, n - 1);
    for (size_t j = 0; j < n; ++j) offset_[j] *= clear, offset_rate_[j] *= clear;
  }
  // Each joint's offset is its own: the legs get their bones' lengths back by IK to where the
  // offset ankles are (measured: without it a fallback on the Bandai capture showed a shin 7 cm
  // short for a few frames).
  if (offset_left_s_ <= 0.0f || library_.num_joints() <= kCanonRightToeEnd) return;
  for (int foot = 0; foot < 2; ++foot) {
    reach(foot, vec3(0.0f));
    // A foot the new pose plants but the decaying offset still holds in the air (a fallback to
    // idle in mid-stride) is landing, not planted: it is neither held nor counted as on the ground
    // until it is down.
    const auto ball = static_cast<size_t>(foot_ball_joint(foot)), heel = static_cast<size_t>(foot_heel_joint(foot));
    if (std::max(shown_[ball].y - animated_[ball].y, shown_[heel].y - animated_[heel].y) > kLanded_m)
      contact_ &= static_cast<uint8_t>(~(foot_ball_bit(foot) | foot_heel_bit(foot)));
  }
}

// A transition's blend carries the pose on but not its rate: a hand swinging 9 cm a frame at the
// end of one segment may start the next at rest (the Bandai capture's derived stops and starts:
// 158-282 mm/frame^2). As in Bollo's inertialization, the pose is shown going on as the segment
// left would have (its pose and rate now), and the offset from the new segment and the difference
// of their rates die out over inertialize_s (an offset still dying out carries on in it). Both rates
// are second-order differences over three of their own frames (the segment left: its last two
// and the one it would have played now; the new one: its first three), so the motions' own
// accelerations cancel and only the switch's change of rate is carried (one-sided first
// differences, two frames apart, carried the motions' own deceleration: the Bandai dash's hands
// looping at 137-172 mm/frame^2, measured); the steering's turn of the segment's start is
// ease_turn's, not this. Only from the spine up: carried in the pelvis and legs
// too, the offsets fought the foot locks and the leg IK (Bandai obstacles, 10 seeds: 3.3 -> 5.8
// pops a minute, ground max 0.4 -> 3.5 cm, 2 shown collisions; measured).
void PoseStage::carry_switch(const PlaybackState& state, float dt_s) {
  const float T = offset_span_s_, left_s = offset_left_s_ - dt_s;
  for (size_t j = 0; j < offset_.size(); ++j) {  // where an offset dying out is now, and its rate
    const Inertialized dying(offset_[j], offset_rate_[j], T);
    offset_[j] = dying.at(T - left_s), offset_rate_[j] = dying.rate_at(T - left_s);
  }
  // Adds `weight` x `pose` (of a segment of `s`'s) to the offset and `rate_weight` x it / (2
  // frames) to its rate, for the joints from the spine up.
  const size_t upper_end = library_.num_joints() == kCanonJointCount ? kCanonLeftUpLeg : kCanonSpine;
  const auto add = [&](const std::vector<vec3>& pose, const PlaybackState& s, float weight, float rate_weight) {
    const float per_s = rate_weight * 0.5f * fps(s);
    for (size_t j = kCanonSpine; j < upper_end; ++j) offset_[j] += weight * pose[j], offset_rate_[j] += per_s * pose[j];
  };
  // The pose of `s` at `frame`, clamped to its segment.
  const auto sample = [this](PlaybackState s, int frame) -> const std::vector<vec3>& {
    s.frame = std::clamp(frame, 0, library_.graph.segments[s.segment].num_frames());
    playback_pose(library_, s, pose_);
    fk_pose(library_.skeleton, pose_.local_pos_m, pose_.local_rot, sampled_, rotations_);
    return sampled_;
  };
  // The segment left, now, at its rate backwards (its frame before was sampled last update)...
  const PlaybackState& left = previous_state_;
  add(sample(left, left.frame + 1), left, 1.0f, 3.0f);
  add(previous_frame_pose_, left, 0.0f, -4.0f);
  add(sample(left, left.frame - 1), left, 0.0f, 1.0f);
  // ...less the new one, at its rate forwards (its frame now was sampled this update).
  add(frame_pose_, state, -1.0f, 3.0f);
  add(sample(state, state.frame + 1), state, 0.0f, -4.0f);
  add(sample(state, state.frame + 2), state, 0.0f, 1.0f);
  offset_left_s_ = offset_span_s_ = config_.inertialize_s;
}

void PoseStage::lock_foot(int foot, float dt_s) {
  FootLock& f = feet_[foot];
  const bool ball = (contact_ & foot_ball_bit(foot)) != 0;
  const bool heel = (contact_ & foot_heel_bit(foot)) != 0;
  f.release_left_s = std::max(0.0f, f.release_left_s - dt_s);
  // Where the pose has this foot's parts, before any hold moves them, and where it had them.
  const vec2 was[2] = {pose_parts_[foot][0], pose_parts_[foot][1]};
  const bool had = has_pose_parts_[foot];
  pose_parts_[foot][0] = ground(shown_[static_cast<size_t>(foot_heel_joint(foot))]);
  pose_parts_[foot][1] = ground(shown_[static_cast<size_t>(foot_ball_joint(foot))]);
  has_pose_parts_[foot] = true;
  if (ball || heel) {
    const int joint = ball ? foot_ball_joint(foot) : foot_heel_joint(foot);
    const vec3 here = shown_[static_cast<size_t>(joint)];
    const bool held_before = f.locked && f.joint == joint;
    if (f.release_left_s > 0.0f && f.stepping) {
      // A step under way: the foot travels to where the clip has it along a low arc, and is
      // planted there when it lands.
      const float lift = config_.step_height_m * std::sin(kPi * (1.0f - f.release_left_s / config_.release_s));
      reach_clear(foot, let_go_offset(f, f.release_left_s) + vec3(0.0f, lift, 0.0f));
      contact_ &= static_cast<uint8_t>(~(foot_ball_bit(foot) | foot_heel_bit(foot)));
      f.locked = false;
      return;
    }
    // Planted now: hold the planted part where it is shown now. Rolling from one part to the
    // other (heel to ball, or ball to heel where a capture lifts the ball first): the part now
    // held stays where it was shown last frame, so the roll does not slide it.
    if (!f.locked) {
      f = FootLock{true, joint, here + let_go_offset(f, f.release_left_s)};
      touch_down(joint, f.at, dt_s);
    }
    else if (f.joint != joint) f = FootLock{true, joint, previous_[static_cast<size_t>(joint)]};
    f.at += vec3(foothold_nudge_[foot].x, 0.0f, foothold_nudge_[foot].y);  // off a step's edge (adapt_to_ground)
    // Held on the ground plane only: its height is the clip's over the ground (adapt_to_ground).
    vec3 offset = f.at - here;
    offset.y = 0.0f;
    // The offset's rate if the foot is let go of now, so that it carries on as shown: a foot held
    // since last frame at rest while the pose's part moves on at its rate (a steering sweep); a
    // foot that lands this frame (or rolls onto another part) with its last move as shown. On that
    // frame the pose's rate is the swing's or a segment switch's (18 cm a frame entering a Bandai
    // start mid-stride, the foot then planted), which says nothing of where the pose goes next:
    // cancelling it drove the foot back 18 cm a frame (a toe at 229-247 mm/frame^2, measured).
    vec2 rate(0.0f);
    if (had && dt_s > 0.0f)
      rate = held_before ? (was[ball ? 1 : 0] - ground(here)) / dt_s
                         : (ground(f.at) - ground(previous_[static_cast<size_t>(joint)])) / dt_s;
    if (glm::length(offset) > config_.max_lock_offset_m) {
      // The body has turned or moved too far over the planted foot: it steps to where the clip
      // has it, lifted from this frame on (the leg may not even reach the hold).
      f.locked = false;
      f.joint = joint;
      f.stepping = true;
      let_go_from(f, offset, rate);
      reach(foot, offset);  // (kFootNoStraighter here: 5 more maze pops in 400 seeds, measured)
      contact_ &= static_cast<uint8_t>(~(foot_ball_bit(foot) | foot_heel_bit(foot)));
      return;
    }
    let_go_from(f, offset, rate);  // ready for the lift
    f.stepping = false;
    reach(foot, offset);
    if (ball) push_off(foot, here + offset);
    return;
  }
  f.locked = false;
  if (f.release_left_s > 0.0f) reach_clear(foot, let_go_offset(f, f.release_left_s));
}

// A foot let go of is shown at an offset from the pose's, on a leg no straighter than the pose's
// (Reach::kFootNoStraighter): where that would show the leg in a box the played one is clear of (a
// swinging toe 2 cm into a crate beside the path, measured), only the share of the offset that
// stays clear is shown (show_clear, as for the eased turn).
void PoseStage::reach_clear(int foot, vec3 offset) {
  const size_t knee = static_cast<size_t>(foot == 0 ? kCanonLeftLeg : kCanonRightLeg), toe_end = knee + 3;
  std::array<vec3, 4> leg;
  std::copy(shown_.begin() + static_cast<long>(knee), shown_.begin() + static_cast<long>(toe_end) + 1, leg.begin());
  show_clear(
      [&](float share) {
        std::copy(leg.begin(), leg.end(), shown_.begin() + static_cast<long>(knee));
        reach(foot, share * offset, Reach::kFootNoStraighter);
      },
      knee, toe_end);
}

// A foot the clip plants while it is still shown moving fast (steering sweeps a landing foot
// 0.3-0.5 m from the root up to 0.15 m a frame, and the lower body's turn lag carries it on for a
// few frames after the played turn stops) would stop dead in one frame: a toe at 121-155
// mm/frame^2, over the pop threshold, at nearly every landing in a turn. It is held instead where
// its last move changes its rate by at most max_landing_accel_mps2 and stops at most that (the
// nearest such place to where the pose lands it; half its incoming move when there is none), so it
// comes to rest over two frames; a landing as authored is within that and left alone. The hold is
// then a few cm short of the pose's foot, which the leg reaches by IK (and max_lock_offset_m still
// steps). Slowing the root or the lower body's turn before a landing did the same but cost response
// or showed in the planted leg (docs/MOTION_QUALITY.md).
void PoseStage::touch_down(int joint, vec3& at, float dt_s) const {
  if (!has_shown_rate_ || dt_s <= 0.0f) return;
  const vec2 last = ground(previous_[static_cast<size_t>(joint)]);
  const vec2 step_in = ground(shown_rate_[static_cast<size_t>(joint)]) * dt_s;
  const vec2 step = ground(at) - last;
  const float most = config_.max_landing_accel_mps2 * dt_s * dt_s;  // m a frame
  const vec2 held = last + nearest_in_lens(step, step_in, most);
  at.x = held.x;
  at.z = held.y;
}

// A foot let go of (lifted, or stepping) is shown at an offset from the pose that dies out over
// release_s (a quintic: the offset, its rate and its acceleration reach 0 together) and starts at
// the held part's offset and at the rate that leaves it moving as it was shown (lock_foot): a
// held foot sets off from rest however fast the pose's foot moves (steering sweeps a foot 0.5 m
// from the root 0.15 m a frame), where a decaying offset alone took on all of that speed in one
// frame (a pop at each step steering forced).
vec3 PoseStage::let_go_offset(const FootLock& lock, float left_s) const {
  if (left_s <= 0.0f) return vec3(0.0f);
  const float T = config_.release_s;
  return from_ground(Inertialized(lock.let_go_offset, lock.let_go_rate, T).at(T - left_s), 0.0f);
}

// Starts letting go of a foot held `offset` from the pose this frame, the offset changing at
// `rate` (m/s; lock_foot: the foot carries on as shown).
void PoseStage::let_go_from(FootLock& lock, vec3 offset, vec2 rate) const {
  lock.release_left_s = config_.release_s;
  lock.let_go_offset = ground(offset);
  lock.let_go_rate = rate;
}

// At push-off the body may have gone on further than the leg reaches to the held ball (a hold
// nudged off a step's edge, steering): the heel rises, the foot turning about the ball, as a foot
// pushing off does, instead of the ball being dragged from where it is held.
void PoseStage::push_off(int foot, vec3 ball_at) {
  const size_t hip = static_cast<size_t>(foot == 0 ? kCanonLeftUpLeg : kCanonRightUpLeg);
  const size_t knee = hip + 1, ankle = hip + 2, ball = static_cast<size_t>(foot_ball_joint(foot));
  if (glm::length(ground(shown_[ball]) - ground(ball_at)) < 1e-3f) return;  // reached
  const float foot_length = glm::length(shown_[ball] - shown_[ankle]);
  const float leg =
      0.995f * (glm::length(animated_[knee] - animated_[hip]) + glm::length(animated_[ankle] - animated_[knee]));
  const vec3 h = shown_[hip];
  const float d = glm::length(ball_at - h);
  if (d >= leg + foot_length || d < 1e-4f) return;  // out of reach even on the toes
  // The ankle on the circle where the leg's reach meets the foot's length about the ball, nearest
  // where the foot held rigidly would put it.
  const vec3 u = (ball_at - h) / d;
  const float along = (d * d + leg * leg - foot_length * foot_length) / (2.0f * d);
  const float radius = std::sqrt(std::max(0.0f, leg * leg - along * along));
  const vec3 centre = h + u * along;
  vec3 side = shown_[ankle] + (ball_at - shown_[ball]) - centre;
  side -= u * glm::dot(side, u);
  if (glm::dot(side, side) < 1e-8f) side = vec3(0.0f, 1.0f, 0.0f) - u * u.y;
  const vec3 toe_from_ball = shown_[ball + 1] - shown_[ball];
  reach(foot, centre + glm::normalize(side) * radius - shown_[ankle], Reach::kAnkleOnly);
  shown_[ball] = ball_at;
  shown_[ball + 1] = ball_at + toe_from_ball;
}

// Moves the foot by `offset` (the ankle, and the ball and toe with it but for Reach::kAnkleOnly)
// and bends the leg to reach it: the knee stays in the plane of hip, new ankle and the animated
// knee, at the bone lengths. With Reach::kFootNoStraighter the leg is not shown straighter than
// the animation's: a foot in the air is not held to its offset at the cost of the knee.
void PoseStage::reach(int foot, vec3 offset, Reach how) {
  const size_t hip = static_cast<size_t>(foot == 0 ? kCanonLeftUpLeg : kCanonRightUpLeg);
  const size_t knee = hip + 1, ankle = hip + 2;
  const vec3 h = shown_[hip], k = shown_[knee], a = shown_[ankle];
  // The animation's bone lengths, not the shown ones: an inertialized jump offsets every joint by
  // its own amount, which stretches or shrinks the shown bones until it has decayed.
  const float upper = glm::length(animated_[knee] - animated_[hip]), lower = glm::length(animated_[ankle] - animated_[knee]);
  if (upper < 1e-4f || lower < 1e-4f) return;
  // The knee's side: its offset from the hip-ankle line, shown and animated. The shown knee keeps
  // its side but within kKneeCone_rad of the animated knee's: an inertialized jump offsets the
  // knee by its own amount, and the shown knee it leaves can point sideways or back (a fallback
  // after a Bandai backward walk: 90 deg off the idle's knee for 3 frames). The lower body's turn
  // lag (36 deg at most) stays inside the cone; past it the bend is turned to the cone's edge.
  const vec3 shown_side = offset_from_line(k, h, a);
  vec3 own_side = offset_from_line(animated_[knee], animated_[hip], animated_[ankle]);
  const bool has_side = glm::length(own_side) > kClearlyBent_m;
  if (has_side) own_side = glm::normalize(own_side);
  const bool in_cone = !has_side || glm::dot(shown_side, own_side) >= std::cos(kKneeCone_rad) * glm::length(shown_side);
  if (glm::dot(offset, offset) < 1e-10f && std::abs(glm::length(k - h) - upper) < 1e-4f &&
      std::abs(glm::length(a - k) - lower) < 1e-4f && in_cone)
    return;
  vec3 target = a + offset;
  vec3 to = target - h;
  float d = glm::length(to);
  // Near straight, a few mm more reach swings the knee by cm: a let-go foot's offset (held back
  // where it was planted, the body gone on) kept the swinging leg straight while the animation's
  // bent, then the knee caught up in one frame, 121-133 mm/frame^2 (most built-in pops in the
  // maze's walk turns and on the doorways, measured: docs/MOTION_QUALITY.md).
  const float shortest = std::abs(upper - lower) + 1e-3f;
  float longest = 0.995f * (upper + lower);
  if (how == Reach::kFootNoStraighter) longest = std::clamp(glm::length(animated_[ankle] - animated_[hip]), shortest, longest);
  if (d < 1e-4f) return;
  const vec3 dir = to / d;
  d = std::clamp(d, shortest, longest);
  target = h + dir * d;
  // The bend: the shown knee's side, made square to the new line; the knee stays on that side.
  vec3 bend = shown_side - dir * glm::dot(shown_side, dir);
  if (glm::dot(bend, bend) < 1e-8f) bend = vec3(0.0f, 0.0f, 1.0f) - dir * dir.z;
  bend = glm::normalize(bend);
  if (has_side) {
    vec3 own = own_side - dir * glm::dot(own_side, dir);
    if (glm::dot(own, own) > 1e-8f) {
      own = glm::normalize(own);
      const float c = glm::dot(bend, own);
      if (c < std::cos(kKneeCone_rad)) {
        vec3 across = bend - own * c;
        if (glm::dot(across, across) < 1e-8f) across = glm::cross(dir, own);
        bend = own * std::cos(kKneeCone_rad) + glm::normalize(across) * std::sin(kKneeCone_rad);
      }
    }
  }
  const float along = (upper * upper - lower * lower + d * d) / (2.0f * d);
  const float out = std::sqrt(std::max(0.0f, upper * upper - along * along));
  const vec3 moved = target - a;
  shown_[knee] = h + dir * along + bend * out;
  shown_[ankle] = target;
  // The foot below the ankle (ball, toe end) moves with it.
  if (how != Reach::kAnkleOnly)
    for (size_t j = ankle + 1; j <= ankle + 2 && j < shown_.size(); ++j) shown_[j] += moved;
}

}  // namespace foresight
