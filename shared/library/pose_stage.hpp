#pragma once
// The pose stage: what is shown (drawn by the client, measured by the motion-quality bench) is the
// playback's pose after this, one stage per avatar, called once per shown frame.
//
//  1. Inertialization. When the sampled pose jumps (any joint moves further in one frame than the
//     library's clips ever move one: a snapshot correction, a reconnect) or another segment is
//     entered without a transition however little it moves (a fallback to idle: no blend carries
//     the pose on), the jump becomes an offset from the new pose that dies out over
//     `inertialize_s` (a quintic: it starts and lands at rest; a long one, whose quintic would
//     accelerate faster than the guard (6.) allows, more slowly) instead of a pop. A foot the
//     new pose plants but the offset still holds in the air (a fallback in mid-stride) is
//     landing, not planted, until it is within 1 cm of its pose's height. A switch with a
//     transition (whose blend carries the pose on, not its rate) carries the upper body's rate
//     on: the spine, arms and head are shown going on as the segment left would have, and the
//     difference dies out over `inertialize_s` (Bollo's inertialization; the legs are the foot
//     locks', the pelvis carries them). With obstacles (set_obstacles), an offset that would show
//     a joint in a box the played pose is clear of is cut to the share that stays clear.
//  2. Turn easing. Root steering turns the whole body about the root at up to 540 deg/s, starting
//     and stopping at full speed: a hand 0.4 m from the root would jump 0.13 m a frame. The
//     steering's part of the turn (the segment's start rotated while the segment plays on) is
//     shown through critically damped springs (3.): the body follows within a few frames, its
//     turning speed eased in and out. With obstacles (set_obstacles), a lag that would show a
//     joint in a box the played pose is clear of (a hand swinging behind the turn, along a
//     wall) is cut to the share that stays clear.
//  3. Orientation warping. The pelvis and legs follow the root's turn more closely than the upper
//     body (two springs: `lower_turn_stiffness` for them, `turn_stiffness` from the chest up, the
//     spine blending a third and two thirds of the way), so the feet step where the root goes
//     while the shoulders and head keep facing a few frames longer. (Turning the legs with the
//     root exactly shows the steering's frame-to-frame reversals as knee and foot pops: measured.)
//  4. Ground adaptation (with a terrain, set_ground). Flat-ground clips are shown over the ground
//     under them: each planted foot is raised or lowered by leg IK to the ground under its planted
//     part (the heel before the ball, where the lock holds it), the ball and toe following the
//     ground's rise along the foot (the foot pitched with the slope); the whole body goes down to
//     the lower foot (the pelvis is lowered on slopes and steps, so the lower leg reaches without
//     stretching). A swinging foot goes to the ground where the clip next plants it, at the rate
//     that brings it there as it lands (a step up is taken in the air; one found too late to take
//     without a pop is not, unless the landing has no lower ground near it: then it is climbed
//     over the rest of the swing), never below the ground under its front (a step down waits for
//     the edge); a landing that will be nudged off an edge (below) is swung to the nudged spot.
//     A foot is raised, and a swinging foot's front lifted over ground rising under it, with the
//     acceleration bounded (`max_foot_ground_accel_mps2`): a step up found in the swing's last
//     frames (steering turned the landing onto it) is reached late, the foot not planted until it
//     is within 1 cm of its ground and at rest, instead of popping up. A planted part on or just
//     past a step's edge (its contact patch, a few cm, reaching both sides) rests on the side
//     nearest the foot's height, the foot nudged off the edge; a planted part that is then shown
//     more than 2 cm over the ground under it (a heel or ball hanging past the edge the other
//     part stands behind) hangs: not planted; a planted foot a few cm off its
//     ground is put on it. Otherwise the heights follow their targets through critically damped
//     springs, the body's slower than the feet's. A hole under a foot keeps its last height.
//  5. Foot locking. While the clip plants a foot (foot_contact.hpp: heel or ball), that part keeps
//     the ground position it had when it was planted (its height stays the clip's over the ground
//     under it, 4.), through root steering, blends and the
//     decaying offsets above; the leg reaches it by two-bone IK (hip, knee, ankle: bone lengths
//     kept, the knee bent the way the animation bends it, never fully straight; an inertialized
//     knee kept within 60 deg of the played knee's side), and the foot
//     below the ankle moves with the ankle. When the body has turned or moved so far over a
//     planted foot that it is more than `max_lock_offset_m` from where the clip has it (turning on
//     the spot by root steering), the foot steps there: over `release_s`, lifted along a low arc
//     (`step_height_m`), shown as not planted. When the clip lifts the foot the lock's offset
//     dies out over `release_s`. Either way the foot is let go of as it was shown moving, and the
//     offset dies out with its rate and acceleration (a quintic): a held foot from rest (the
//     offset's rate cancels the played foot's: steering sweeps a foot 0.15 m a frame), one that
//     lands and steps at once with its last move. Landing is the same the other way round: a
//     foot the clip plants while the turn still sweeps it is put down short of where the pose
//     lands it, so it comes to rest over two frames instead of stopping dead in one
//     (touch_down). A held ball the leg cannot reach any more (the body gone on at push-off)
//     lifts the heel, the foot turning about the ball, instead of being dragged. A foot in the
//     air (let go of, or stepping, from the frame after a step starts) is never shown on a leg
//     straighter than the pose's: its offset gives way first (near straight, the knee would
//     swing cm for mm of reach).
//  6. Acceleration guard. What the steps above leave is shown with no joint's velocity changing
//     in a frame by more than the library's own clips change theirs 99.9 % of the time
//     (MotionLibrary::pop_threshold_m, the measure of a pop): a frame that would is shown with
//     every joint's change held back alike to `guard_share` of it (the legs then solved again at
//     their bones' lengths, and the share raised until their knees are within it too), and the
//     part held back is an offset that dies out through a critically damped spring
//     (`guard_stiffness`): inertialization of a spike, a few cm at most for a few frames. A foot
//     a lock holds is neither moved nor judged; nothing held back is shown in a box the played
//     pose is clear of (set_obstacles). What is left for it is near the threshold (a knee at the
//     start of a walking turn, a toe at a walk's last frame, a capture's own noisy frame, a
//     fallback from a run into idle: docs/MOTION_QUALITY.md "An acceleration guard").
// Works on world joint positions, which is what the client draws (a bone per parent-child pair)
// and what is measured; joint rotations are not rewritten. No allocation after the first frame.
#include "library/motion_library.hpp"
#include "library/playback.hpp"
#include "world/scene.hpp"

#include <span>
#include <vector>

namespace foresight {

struct CollisionWorld;

struct PoseStageConfig {
  bool foot_locking = true;
  bool inertialization = true;
  bool turn_easing = true;
  float turn_stiffness = 20.0f;  ///< 1/s: the upper body's spring (lag while turning at 540 deg/s: 2 x rate / stiffness, 54 deg).
  float inertialize_s = 0.2f;
  float release_s = 0.3f;
  float max_lock_offset_m = 0.10f;
  float step_height_m = 0.05f;  ///< Apex of a step taken when the body turned too far over a planted foot.
  bool orientation_warping = true;  ///< The lower body's turn lag shorter than the upper body's (3. above).
  float lower_turn_stiffness = 30.0f;  ///< 1/s: the pelvis and legs' (36 deg behind at 540 deg/s).
  bool ground_adaptation = true;    ///< Needs set_ground (4. above).
  /// 1/s: a 0.18 m step is 98 % taken by a foot in 0.3 s; its largest acceleration (k^2 x step,
  /// 80 mm/frame^2) stays under the built-in library's 99.9th percentile (121: no pop).
  float foot_ground_stiffness = 20.0f;
  float body_ground_stiffness = 10.0f;  ///< 1/s: the pelvis follows the lower foot more slowly.
  /// A planted foot this close to its ground is put on it at once (a larger gap: the spring).
  float planted_snap_m = 0.05f;
  /// m/s: the fastest a swinging foot is raised towards a step up it will land on.
  float max_foot_rise_mps = 1.2f;
  /// m/s^2: the largest acceleration of a foot's height towards its ground (36: 40 mm/frame^2 at
  /// 30 Hz, under a third of the built-in library's pop threshold; an 18 cm step found at the
  /// last moment is climbed in 0.14 s).
  float max_foot_ground_accel_mps2 = 36.0f;
  /// m/s^2: a foot the clip plants while it is shown moving faster than it can stop at this
  /// (steering sweeps a landing foot up to 0.15 m a frame) is put down nearer, so it comes to rest
  /// over two frames (5. above). 54: 60 mm/frame^2 at 30 Hz, half the built-in library's pop
  /// threshold; the clips' own strikes are left as authored (at 36 the stage moved some of them
  /// by a few mm and their balls skated: maze skate p95 0.03 -> 1.4 cm/s, measured).
  float max_landing_accel_mps2 = 54.0f;
  bool acceleration_guard = true;  ///< 6. above.
  /// Of MotionLibrary::pop_threshold_m: the largest change of a joint's velocity shown in a frame
  /// (per clip frame; at other frame rates the same change of velocity, which is what a linearly
  /// interpolated clip shows).
  float guard_share = 0.95f;
  float guard_stiffness = 20.0f;  ///< 1/s: the held-back part's spring (settled in about 0.2 s).
};

class PoseStage {
 public:
  explicit PoseStage(const MotionLibrary& library, PoseStageConfig config = {});

  /// The shown pose of `state` (`frame_alpha` of the way to its next frame), `dt_s` after the
  /// previous call: world joint positions.
  std::span<const vec3> update(const PlaybackState& state, float dt_s, float frame_alpha = 0.0f);
  /// Forget the previous frame (a new avatar, a teleport the caller wants shown as one).
  void reset();
  /// The ground the feet are adapted to (4. above); nullptr (the default): the clips' own flat
  /// floor, as authored. The terrain must outlive the stage or the next call.
  void set_ground(const Terrain* terrain) { ground_ = terrain; }
  /// The boxes the offsets, the eased turn and a let-go foot must not show a joint in where the
  /// played pose is clear of them (1., 2., 5. above); nullptr (the default): none.
  /// Must outlive the stage or the next call.
  void set_obstacles(const CollisionWorld* world) { obstacles_ = world; }

  /// The pose as sampled this frame, before the stage.
  std::span<const vec3> animated() const { return animated_; }
  std::span<const vec3> shown() const { return shown_; }
  /// The pose before the acceleration guard (6. above): the same as shown() where it held nothing back.
  std::span<const vec3> unguarded() const { return unguarded_; }
  /// This frame's FootContactBit byte: the clip frame's, less the feet the stage is stepping and
  /// those an inertialized jump still holds in the air (landing).
  uint8_t contact() const { return contact_; }
  /// Frames whose sampled pose jumped (or entered a segment without a transition) and were
  /// inertialized, since construction.
  int discontinuities() const { return discontinuities_; }
  /// Frames the acceleration guard (6. above) held a change back on, since construction.
  int guarded_frames() const { return guarded_frames_; }
  /// A joint moving farther than this in a frame is a jump (MotionLibrary::max_joint_step_m
  /// with a margin for root steering).
  float jump_m() const { return jump_m_; }
  const PoseStageConfig& config() const { return config_; }

 private:
  struct FootLock {
    bool locked = false;
    int joint = -1;          ///< The planted part: heel (ankle) or ball.
    vec3 at{0.0f};           ///< Where it is held, world.
    float release_left_s = 0;  ///< Being let go of (let_go_offset).
    vec2 let_go_offset{0.0f};  ///< The held part's offset from the pose when let go (ground plane)...
    vec2 let_go_rate{0.0f};    ///< ...and its rate, m/s: the part moving on as shown (held: at rest).
    bool stepping = false;   ///< The release is a step: the foot is lifted, not planted.
  };
  void inertialize(const PlaybackState& state, float dt_s);
  void carry_switch(const PlaybackState& state, float dt_s);
  void ease_turn(const PlaybackState& state, float dt_s);
  void turn_about(vec2 pivot, float share);
  /// Whether a shown joint in [first, last] is in a box (set_obstacles) its played one is clear of.
  bool shown_into_obstacle(size_t first, size_t last) const;
  template <typename Show>
  float show_clear(Show&& show, size_t first, size_t last);
  void adapt_to_ground(const PlaybackState& state, float frame_alpha, float dt_s);
  bool landing_ground(const PlaybackState& state, float frame_alpha, int foot, float& height, float& in_s, vec2& at);
  bool lowest_ground_near(vec2 p, float& height) const;
  vec2 nudge_onto(vec2 p, float height) const;
  void lock_foot(int foot, float dt_s);
  void touch_down(int joint, vec3& at, float dt_s) const;
  vec3 let_go_offset(const FootLock& lock, float left_s) const;
  void let_go_from(FootLock& lock, vec3 offset, vec2 rate) const;
  /// How reach() moves a foot: the ball and toe with the ankle (kFoot); the ankle alone, the
  /// caller placing the rest (kAnkleOnly: push_off); with the foot, on a leg no straighter than
  /// the animation's (kFootNoStraighter: a foot in the air is not held to its offset at the
  /// cost of the knee).
  enum class Reach { kFoot, kAnkleOnly, kFootNoStraighter };
  void reach(int foot, vec3 offset, Reach how = Reach::kFoot);
  void reach_clear(int foot, vec3 offset);
  void push_off(int foot, vec3 ball_at);
  void guard_acceleration(const PlaybackState& state, float dt_s);
  /// The frame rate of the clip `s` plays.
  float fps(const PlaybackState& s) const { return library_.clips[library_.graph.segments[s.segment].clip].fps; }

  const MotionLibrary& library_;
  PoseStageConfig config_;
  float jump_m_ = 0.5f;
  Pose pose_;
  std::vector<vec3> animated_, shown_, previous_, previous_animated_, offset_, landing_;
  std::vector<vec3> offset_rate_, sampled_;  ///< The inertialized offset's starting rate; a pose carry_switch samples.
  std::vector<vec3> frame_pose_, previous_frame_pose_;  ///< The sampled pose on the frame (no frame_alpha): now, last update.
  std::vector<vec3> unturned_;  ///< shown_ before the turn lag (ease_turn).
  std::vector<vec3> offset_now_;  ///< The inertialized offset this frame (inertialize).
  std::vector<vec3> unguarded_, guard_offset_, guard_rate_;  ///< guard_acceleration: before it, what it holds back, its rate...
  std::vector<vec3> guard_from_;  ///< ...and the pose with the held-back part of earlier frames, before this frame's.
  std::vector<vec3> shown_rate_;  ///< Each shown joint's velocity over the last frame, m/s (touch_down, the guard).
  bool has_shown_rate_ = false;
  int guarded_frames_ = 0;
  std::vector<quat> rotations_;
  std::vector<float> turn_share_;  ///< Per joint: how much of the turn lag it shows (3. above).
  bool has_previous_ = false;
  PlaybackState previous_state_;
  struct TurnLag {
    float offset_rad = 0.0f;  ///< Shown minus played heading, decaying.
    float speed_rad_s = 0.0f;
  };
  TurnLag turn_lag_[2];  ///< The lower body's (pelvis, legs) and the upper body's (chest up).
  float offset_left_s_ = 0;
  float offset_span_s_ = 0.2f;  ///< How long the inertialized offset takes to die out (inertialize_s, or longer for a long jump).

  uint8_t contact_ = 0;
  int discontinuities_ = 0;
  FootLock feet_[2];
  vec2 pose_parts_[2][2] = {};  ///< Each foot's heel and ball on the ground before the locks (lock_foot).
  bool has_pose_parts_[2] = {false, false};
  const Terrain* ground_ = nullptr;
  const CollisionWorld* obstacles_ = nullptr;
  bool has_ground_ = false;  ///< The ground heights below have been taken.
  float body_y_ = 0.0f, body_vy_ = 0.0f;        ///< The body's shown height offset and its rate.
  float foot_y_[2] = {0, 0}, foot_vy_[2] = {0, 0};  ///< Each foot's, before the body's.
  float front_lift_[2][2] = {}, front_lift_v_[2][2] = {};  ///< Each foot's ball and toe pitch rise (m) and its rate.
  vec2 foothold_nudge_[2] = {vec2(0.0f), vec2(0.0f)};  ///< This frame's move of a planted part off a step's edge.
  vec2 swing_nudge_[2] = {vec2(0.0f), vec2(0.0f)};  ///< A swinging foot's way towards its landing's nudge.
};

}  // namespace foresight
