// The pose stage (issue 18): planted feet stay put while the root steers, jumps are inertialized,
// the steering's turn is eased, legs keep their bones; and the foot contact it relies on.
#include "anim/canonical_skeleton.hpp"
#include "library/foot_contact.hpp"
#include "library_build/library_source.hpp"
#include "library/pose_check.hpp"
#include "library/pose_stage.hpp"
#include "library_checks.hpp"
#include "foreign_capture.hpp"
#include "support/shown_motion.hpp"
#include "world/collision_world.hpp"
#include "world/terrain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace foresight {
namespace {

const MotionLibrary& library() {
  static const MotionLibrary lib = motion_library_default();
  return lib;
}

int planted_share_percent(const MotionLibrary& lib, const char* segment_name, uint8_t bits) {
  const int s = lib.graph.find_segment(segment_name);
  EXPECT_GE(s, 0) << segment_name;
  if (s < 0) return -1;
  const Segment& seg = lib.graph.segments[s];
  int planted = 0;
  for (int f = seg.first_frame; f < seg.end_frame; ++f) planted += (lib.foot_contact_at(seg.clip, f) & bits) != 0;
  return 100 * planted / std::max(1, seg.end_frame - seg.first_frame);
}

TEST(FootContact, StandingPlantsBothFeetAndWalkingAlternates) {
  const MotionLibrary& lib = library();
  ASSERT_EQ(lib.foot_contact.size(), lib.root_track.size());
  EXPECT_EQ(planted_share_percent(lib, "idle", kLeftHeel | kLeftBall), 100);
  EXPECT_EQ(planted_share_percent(lib, "idle", kRightHeel | kRightBall), 100);
  // A walking step: the stance foot is planted most of the step, the swing foot a part of it.
  for (const char* step : {"walk_l", "walk_r"}) {
    const int left = planted_share_percent(lib, step, kLeftHeel | kLeftBall);
    const int right = planted_share_percent(lib, step, kRightHeel | kRightBall);
    EXPECT_GE(std::max(left, right), 90) << step;
    EXPECT_LE(std::min(left, right), 60) << step;
  }
}

struct Leg {
  float upper, lower;
};
Leg leg(std::span<const vec3> p, int hip) {
  return {glm::length(p[hip + 1] - p[hip]), glm::length(p[hip + 2] - p[hip + 1])};
}

// The heading of the line from joint `right` to joint `left` (hips or shoulders).
float heading_across(std::span<const vec3> p, int left, int right) {
  const vec3 across = p[left] - p[right];
  return std::atan2(-across.z, across.x);
}

// walk_l shown through a stage without foot locking, its start turned 18 deg about the root on
// frame 1, as 540 deg/s steering does in one frame; turn() plays that frame, play_to() on.
struct SteeredWalk {
  const MotionLibrary& lib;
  PoseStage stage;
  PlaybackState s;
  explicit SteeredWalk(const MotionLibrary& l)
      : lib(l), stage(l, [] {
          PoseStageConfig c;
          c.foot_locking = false;
          return c;
        }()),
        s{l.graph.find_segment("walk_l"), 0, Placement{}, -1} {
    stage.update(s, 0.0f);
  }
  void turn() {
    s.frame = 1;
    s.segment_start = playback_turned_start(lib, s, 0.314f);
    stage.update(s, 1.0f / 30.0f);
  }
  void play_to(int frame) {
    while (s.frame < frame) {
      ++s.frame;
      stage.update(s, 1.0f / 30.0f);
    }
  }
  /// How far the shown line between two joints lags the played one (rad).
  float lag(int left, int right) const {
    return std::abs(wrap_angle(heading_across(stage.animated(), left, right) - heading_across(stage.shown(), left, right)));
  }
};

// The built-in idle at the origin, shown once through `stage` (both feet planted); false when
// the library has no idle.
bool stand_idle(PoseStage& stage, PlaybackState& s) {
  const int idle = library().graph.find_segment("idle");
  if (idle < 0) return false;
  s = PlaybackState{idle, 0, Placement{}, -1};
  stage.update(s, 0.0f);
  return true;
}

// Root steering turns a standing avatar about its root a few degrees a frame: the played feet
// swing round with it, the shown ones stay where they were planted, on legs of unchanged length.
TEST(PoseStage, PlantedFeetStayPutWhileTheRootTurns) {
  const MotionLibrary& lib = library();
  const int idle = lib.graph.find_segment("idle");
  ASSERT_GE(idle, 0);
  PoseStage stage(lib);
  PlaybackState s{idle, 0, Placement{vec2(1.0f, 2.0f), 0.3f}, -1};
  const int ball = kCanonLeftToeBase;
  std::span<const vec3> shown = stage.update(s, 0.0f);
  const vec3 planted = shown[ball];
  const Leg rest = leg(stage.animated(), kCanonLeftUpLeg);
  float played_moved = 0.0f, shown_moved = 0.0f;
  for (int f = 1; f <= 10; ++f) {
    // 2 deg a frame about the root (60 deg/s), as LookaheadAvatar::steer rotates a segment.
    s.segment_start = playback_turned_start(lib, s, 0.035f);
    s.frame = f % lib.graph.segments[idle].num_frames();
    shown = stage.update(s, 1.0f / 30.0f);
    played_moved = std::max(played_moved, glm::length(stage.animated()[ball] - planted));
    shown_moved = std::max(shown_moved, glm::length(shown[ball] - planted));
    const Leg now = leg(shown, kCanonLeftUpLeg);
    EXPECT_NEAR(now.upper, rest.upper, 1e-3f) << "frame " << f;
    EXPECT_NEAR(now.lower, rest.lower, 1e-3f) << "frame " << f;
  }
  EXPECT_GT(played_moved, 0.03f) << "the played foot swings round with the body";
  EXPECT_LT(shown_moved, 0.002f) << "the shown one stays planted";
}

// Turned far enough over a planted foot, the body steps it to where the clip has it: the foot is
// shown lifted (not planted) on the way, and ends where the clip has it.
TEST(PoseStage, TheBodyTurnedFarOverAPlantedFootStepsIt) {
  const MotionLibrary& lib = library();
  PoseStage stage(lib);
  PlaybackState s;
  ASSERT_TRUE(stand_idle(stage, s));
  const int idle = s.segment;
  bool lifted = false;
  for (int f = 1; f <= 60; ++f) {
    if (f <= 15) {  // 6 deg a frame for half a second: 90 deg
      s.segment_start = playback_turned_start(lib, s, 0.105f);
    }
    s.frame = f % lib.graph.segments[idle].num_frames();
    stage.update(s, 1.0f / 30.0f);
    lifted |= (stage.contact() & (kLeftHeel | kLeftBall)) == 0 || (stage.contact() & (kRightHeel | kRightBall)) == 0;
  }
  EXPECT_TRUE(lifted) << "a foot should have stepped";
  EXPECT_LT(test::max_distance(std::vector<vec3>(stage.shown().begin(), stage.shown().end()),
                               std::vector<vec3>(stage.animated().begin(), stage.animated().end())),
            0.01f)
      << "settled: shown where the clip has it";
}

// `segment` played from its start with its first five steered frames turned 18 deg each (540
// deg/s, a 90 deg key change): the largest acceleration of either foot's ankle, ball or toe end
// as shown (m/frame^2), and whether the turn forced a step (a part the clip plants shown lifted).
struct SteeredFeet {
  float worst_m = 0.0f;
  bool stepped = false;
  float step_start_m = 0.0f;  ///< A stepping foot's largest acceleration on its step's first two frames.
};
SteeredFeet feet_through_a_sharp_turn(const MotionLibrary& lib, int segment, float turn_rad = 0.314f) {
  PoseStage stage(lib);
  PlaybackState s{segment, 0, Placement{}, -1};
  const Segment& seg = lib.graph.segments[static_cast<size_t>(segment)];
  std::vector<std::vector<vec3>> feet;  // per frame
  int step_from[2] = {-1, -1};          // the frame each foot first steps
  SteeredFeet out;
  for (int f = 0; f < seg.num_frames(); ++f) {
    s.frame = f;
    if (f >= 1 && f <= 5) s.segment_start = playback_turned_start(lib, s, turn_rad);
    stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
    feet.emplace_back();
    for (const int j : {kCanonLeftFoot, kCanonLeftToeBase, kCanonLeftToeEnd, kCanonRightFoot, kCanonRightToeBase,
                        kCanonRightToeEnd})
      feet.back().push_back(stage.shown()[static_cast<size_t>(j)]);
    const uint8_t unshown = lib.foot_contact_at(seg.clip, seg.first_frame + f) & ~stage.contact();
    out.stepped |= unshown != 0;
    for (int foot = 0; foot < 2; ++foot)
      if ((unshown & (foot_heel_bit(foot) | foot_ball_bit(foot))) && step_from[foot] < 0) step_from[foot] = f;
  }
  const auto accel = [&](size_t f, size_t j) { return glm::length(feet[f + 1][j] - 2.0f * feet[f][j] + feet[f - 1][j]); };
  for (size_t f = 1; f + 1 < feet.size(); ++f)
    for (size_t j = 0; j < feet[f].size(); ++j) out.worst_m = std::max(out.worst_m, accel(f, j));
  for (int foot = 0; foot < 2; ++foot)
    for (int f = step_from[foot]; f >= 1 && f <= step_from[foot] + 1 && f + 1 < static_cast<int>(feet.size()); ++f)
      for (size_t j = 3 * static_cast<size_t>(foot); j < 3 * static_cast<size_t>(foot) + 3; ++j)
        out.step_start_m = std::max(out.step_start_m, accel(static_cast<size_t>(f), j));
  return out;
}

// Open ground with a post 1 cm square and 2 m high at `post`: something only a lagging joint
// can be shown in.
void build_post(vec2 post, CollisionWorld& world) {
  Scene scene;
  scene.bounds = {vec2(-20.0f), vec2(20.0f)};
  scene.boxes.push_back({"post", BoxKind::kWall, vec3(post.x - 0.005f, 0.0f, post.y - 0.005f),
                         vec3(post.x + 0.005f, 2.0f, post.y + 0.005f)});
  std::string error;
  ASSERT_TRUE(collision_world_build(scene, world, error)) << error;
}

// Plays a short run with `world`'s boxes as the stage's obstacles (nullptr: none), calling `at`
// with the stage after each frame.
using FrameCheck = std::function<void(int, const PoseStage&)>;
using PlayWith = std::function<void(const CollisionWorld*, const FrameCheck&)>;

// Without the boxes `play` shows a joint in `world`'s post that the played pose clears; with them,
// on no frame (the clip's own collisions aside), and on more than `min_checked` such frames.
// `also` sees every frame of the run with the boxes.
void expect_shown_clear_of_post(const MotionLibrary& lib, const CollisionWorld& world, const PlayWith& play,
                                int min_checked, const FrameCheck& also = nullptr) {
  int shown_in_post = 0, checked = 0;
  play(nullptr, [&](int, const PoseStage& stage) {
    shown_in_post += shown_joints_collide(lib, world, stage.shown()) && !shown_joints_collide(lib, world, stage.animated());
  });
  ASSERT_GT(shown_in_post, 0) << "without the boxes the stage shows a joint in the post";
  play(&world, [&](int f, const PoseStage& stage) {
    if (also) also(f, stage);
    if (shown_joints_collide(lib, world, stage.animated())) return;  // the clip's own
    ++checked;
    EXPECT_FALSE(shown_joints_collide(lib, world, stage.shown())) << "frame " << f;
  });
  EXPECT_GT(checked, min_checked);
}

// A foot let go of (lifted, or stepping) is shown at an offset from the pose's that dies out. Where
// that would show it in a box the played foot clears (traced in the obstacles: a swinging toe 2 cm
// into a crate), only the share of the offset that stays clear is shown. A walking step steered
// sharply (the turn alone, no lag: the offsets are the feet's), with a thin post put just past the
// foot joint shown furthest from its played place while the foot swings free.
TEST(PoseStage, AFootLetGoOfIsNotShownInABoxThePlayedFootClears) {
  const MotionLibrary& lib = library();
  const int walk = lib.graph.find_segment("walk_l");
  ASSERT_GE(walk, 0);
  PoseStageConfig config;
  config.turn_easing = false;
  const int frames = lib.graph.segments[static_cast<size_t>(walk)].num_frames();
  const PlayWith play = [&](const CollisionWorld* world, const FrameCheck& at) {  // the steered step
    PoseStage stage(lib, config);
    stage.set_obstacles(world);
    PlaybackState s{walk, 0, Placement{}, -1};
    for (int f = 0; f < frames; ++f) {
      s.frame = f;
      if (f >= 1 && f <= 5) s.segment_start = playback_turned_start(lib, s, 0.314f);
      stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
      at(f, stage);
    }
  };
  float farthest = 0.0f;
  vec2 post(0.0f);
  play(nullptr, [&](int, const PoseStage& stage) {
    for (int foot = 0; foot < 2; ++foot) {
      if (stage.contact() & (foot_heel_bit(foot) | foot_ball_bit(foot))) continue;  // planted: held
      for (int j = foot_heel_joint(foot); j <= foot_ball_joint(foot) + 1; ++j) {
        const vec2 off = ground(stage.shown()[static_cast<size_t>(j)]) - ground(stage.animated()[static_cast<size_t>(j)]);
        if (glm::length(off) <= farthest) continue;
        farthest = glm::length(off);
        post = ground(stage.shown()[static_cast<size_t>(j)]) + 0.05f * glm::normalize(off);
      }
    }
  });
  ASSERT_GT(farthest, 0.04f) << "a foot let go of is shown away from its played place";
  CollisionWorld world;
  ASSERT_NO_FATAL_FAILURE(build_post(post, world));
  EXPECT_NO_FATAL_FAILURE(expect_shown_clear_of_post(lib, world, play, frames / 2));
}

// Walking steps steered at 540 deg/s for 5 frames: the body turns so far over the planted foot
// that it steps. Before, a foot let go of (a forced step, or the clip lifting it) was shown at a
// decaying offset from the played foot, so it took on at once the speed at which steering sweeps
// the played foot (up to 0.15 m a frame): 118-127 mm/frame^2 here (129-151 in the maze's and
// stairs' runs), a pop at nearly every step steering forced. Now it sets off from rest: 69-77 here.
TEST(PoseStage, AFootLetGoOfWhileSteeringSetsOffFromRest) {
  const MotionLibrary& lib = library();
  for (const char* name : {"walk_l", "walk_r"}) {
    const int walk = lib.graph.find_segment(name);
    ASSERT_GE(walk, 0) << name;
    const SteeredFeet r = feet_through_a_sharp_turn(lib, walk);
    EXPECT_TRUE(r.stepped) << name << ": the turn should force a step";
    EXPECT_LT(r.worst_m, 0.1f) << name << ": largest foot acceleration, m/frame^2";
  }
}

// A walking segment played on into its first successor: the frames (of the two together) where a
// foot lands, after a swing of at least 4 frames and with 2 frames after it (a walk step lands on
// its successor's first frame; a capture's cut segments land anywhere).
struct Walk {
  int transition = -1;
  std::vector<std::array<int, 2>> landings;  ///< Frame, foot.
};
std::vector<Walk> walks(const MotionLibrary& lib) {
  std::vector<Walk> out;
  for (int g = 0; g < lib.graph.num_segments(); ++g) {
    const Segment& seg = lib.graph.segments[static_cast<size_t>(g)];
    const auto next = lib.graph.successors(g);
    if (!(seg.tags & kTagLocomotion) || lib.segment_motion[static_cast<size_t>(g)].end.pos_m.y < 0.3f ||
        next.empty())
      continue;
    Walk walk{static_cast<int>(&next[0] - lib.graph.transitions.data()), {}};
    const Segment& to = lib.graph.segments[static_cast<size_t>(next[0].to)];
    const int n = seg.num_frames(), frames = n + to.num_frames();
    for (int k = 0; k < 2; ++k) {
      int swing = 0;
      for (int f = 0; f + 2 < frames; ++f) {
        const bool down = (f < n ? lib.foot_contact_at(seg.clip, seg.first_frame + f)
                                 : lib.foot_contact_at(to.clip, to.first_frame + f - n)) &
                          (foot_heel_bit(k) | foot_ball_bit(k));
        if (down && swing >= 4 && f >= 5) walk.landings.push_back({f, k});
        swing = down ? 0 : swing + 1;
      }
    }
    if (!walk.landings.empty()) out.push_back(walk);
  }
  return out;
}

// The landing foot's largest acceleration (its heel, ball and toe, m/frame^2) from the frame before
// it lands to the frame after, the walk steered by `turn_rad` a frame over the 4 frames before the
// landing: the turn stops as the foot comes down and the shown lower body's lag carries the foot on
// (traced in the maze: a toe at 155 mm/frame^2 the frame after a landing).
float landing_accel(const MotionLibrary& lib, int transition, std::array<int, 2> landing, PoseStageConfig config,
                    float turn_rad = 0.314f) {
  const int from = lib.graph.transitions[static_cast<size_t>(transition)].from;
  const int n = lib.graph.segments[static_cast<size_t>(from)].num_frames();
  const auto [at, foot] = landing;
  PoseStage stage(lib, config);
  PlaybackState s{from, 0, Placement{}, -1};
  std::vector<std::array<vec3, 3>> shown;  // per frame: heel, ball, toe
  const auto heel = static_cast<size_t>(foot_heel_joint(foot));
  const auto ball = static_cast<size_t>(foot_ball_joint(foot));
  for (int f = 0; f <= at + 2; ++f) {
    if (f == n) playback_take(lib, s, transition);
    s.frame = f < n ? f : f - n;
    if (f >= at - 4 && f < at) s.segment_start = playback_turned_start(lib, s, turn_rad);
    stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
    shown.push_back({stage.shown()[heel], stage.shown()[ball], stage.shown()[ball + 1]});
  }
  float worst = 0.0f;
  for (auto f = static_cast<size_t>(at - 1); f <= static_cast<size_t>(at + 1); ++f)
    worst = std::max(worst, test::largest_joint_acceleration(shown[f - 1], shown[f], shown[f + 1]));
  return worst;
}

// Over every landing of every walk: the median and largest acceleration the steering adds to a
// landing foot (steered minus not), with the stage as it was before touch_down and as it is.
struct LandingAccel {
  float median_before = 0.0f, median_now = 0.0f, worst_before = 0.0f, worst_now = 0.0f;
  size_t landings = 0;
};
LandingAccel steered_landings(const MotionLibrary& lib) {
  PoseStageConfig dead_stop;  // as before touch_down: every landing stops dead
  dead_stop.max_landing_accel_mps2 = 1e9f;
  std::vector<float> before, now;
  for (const Walk& walk : walks(lib))
    for (const auto& landing : walk.landings) {
      const float own = landing_accel(lib, walk.transition, landing, {}, 0.0f);
      before.push_back(landing_accel(lib, walk.transition, landing, dead_stop) - own);
      now.push_back(landing_accel(lib, walk.transition, landing, {}) - own);
    }
  LandingAccel out;
  out.landings = now.size();
  if (now.empty()) return out;
  const auto median = [](std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  out.median_before = median(before), out.median_now = median(now);
  out.worst_before = *std::max_element(before.begin(), before.end());
  out.worst_now = *std::max_element(now.begin(), now.end());
  return out;
}

// A foot the clip plants while the turn still sweeps it is put down short of where the pose lands
// it, so it comes to rest over two frames: before, it stopped dead in one. Over the
// built-in walks' 40 landings the acceleration the turn adds to the landing foot was 78 mm/frame^2
// (median; 117 at most, nearly the pop threshold of 121 on its own), now 48 (75).
TEST(PoseStage, AFootLandingWhileTheTurnSweepsItComesToRestOverTwoFrames) {
  const LandingAccel r = steered_landings(library());
  ASSERT_GT(r.landings, 20u);
  EXPECT_GT(r.median_before, 0.07f) << "the turn adds to a landing that stops dead";
  EXPECT_LT(r.median_now, 0.06f);
  EXPECT_LT(r.worst_now, 0.09f);
}

// The same on capture the team did not make (the Bandai walk in inches under a dummy root, with
// its derived starts, stops and bends; its segments are cut anywhere in the stride): over its 86
// landings the largest acceleration the turn adds fell from 186 to 121 mm/frame^2, the median from
// 65 to 59 (its feet are often slower at the strike, where the stage leaves a landing as authored).
TEST(PoseStage, OnACaptureOfAnotherUnitAndRootAFootLandingWhileTheTurnSweepsItComesToRest) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  const LandingAccel r = steered_landings(lib);
  ASSERT_GT(r.landings, 20u);
  EXPECT_GT(r.worst_before, 0.15f) << "the turn adds to a landing that stops dead";
  EXPECT_LT(r.worst_now, 0.14f);
  EXPECT_LT(r.median_now, r.median_before);
}

// Every switch that lands a foot: a transition into a segment whose first frame plants a foot
// the segment before does not at its end (a step's strike, a start entered from a stop), the
// segment before steered over its last 4 frames: the landing foot's largest acceleration at each,
// sorted.
std::vector<float> switch_landings(const MotionLibrary& lib) {
  std::vector<float> accel;
  for (int i = 0; i < static_cast<int>(lib.graph.transitions.size()); ++i) {
    const Transition& t = lib.graph.transitions[static_cast<size_t>(i)];
    const Segment& from = lib.graph.segments[static_cast<size_t>(t.from)];
    const Segment& to = lib.graph.segments[static_cast<size_t>(t.to)];
    if (from.num_frames() < 5 || to.num_frames() < 3) continue;
    for (int k = 0; k < 2; ++k) {
      const uint8_t bits = foot_heel_bit(k) | foot_ball_bit(k);
      if (!(lib.foot_contact_at(from.clip, from.first_frame + from.num_frames() - 1) & bits) &&
          (lib.foot_contact_at(to.clip, to.first_frame) & bits))
        accel.push_back(landing_accel(lib, i, {from.num_frames(), k}, {}));
    }
  }
  std::sort(accel.begin(), accel.end());
  return accel;
}

// A foot that lands and must step at once (the turn carried the body more than max_lock_offset_m
// over it: a Bandai start entered from a stop while turning) is let go of moving as it was shown,
// not against the pose's rate on that frame: that was the swing's or the switch's (18 cm a frame),
// not the planted pose's, and cancelling it drove the foot back as fast (a toe at 229-247
// mm/frame^2 in the Bandai maze runs). On the Bandai walk in inches under a dummy root, over every
// switch that lands a foot: median 66 mm/frame^2 and worst 178 before, 50 and 105 now.
TEST(PoseStage, OnACaptureOfAnotherUnitAndRootAFootThatLandsAndStepsAtOnceCarriesOnAsShown) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  const std::vector<float> accel = switch_landings(lib);
  ASSERT_GT(accel.size(), 10u);
  EXPECT_LT(accel[accel.size() / 2], 0.058f) << "median";
  EXPECT_LT(accel.back(), 0.13f) << "worst";
}

// The same on capture the team did not make, in inches under a dummy root: every walking segment
// of the Bandai normal walk and its derived starts, stops and bends (at least 12 frames) turned
// sharply. The capture's own feet accelerate more than the built-in clips' (its pop threshold is
// 146 mm/frame^2), so what is asked is the step itself: a stepping foot's largest acceleration
// on the step's first two frames, median over the segments the turn makes step. Before the
// let-go from rest 70 mm/frame^2 (24-116), now 31 (19-90).
TEST(PoseStage, OnACaptureOfAnotherUnitAndRootAFootLetGoOfWhileSteeringSetsOffFromRest) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  std::vector<float> step_starts;
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const Segment& seg = lib.graph.segments[static_cast<size_t>(s)];
    if (!(seg.tags & kTagLocomotion) || seg.num_frames() < 12 || lib.segment_motion[static_cast<size_t>(s)].end.pos_m.y < 0.3f)
      continue;
    const SteeredFeet r = feet_through_a_sharp_turn(lib, s);
    if (r.stepped) step_starts.push_back(r.step_start_m);
  }
  ASSERT_GT(step_starts.size(), 10u) << "the turn should force steps on most of the walk";
  std::nth_element(step_starts.begin(), step_starts.begin() + step_starts.size() / 2, step_starts.end());
  EXPECT_LT(step_starts[step_starts.size() / 2], 0.045f) << "median step start, m/frame^2";
}

// Every walk of `lib` played into its successor and steered by `turn_rad` a frame (0.314: 540
// deg/s) over its first frames (the body turns away from a planted foot, which is then let go of):
// over the frames a foot is in the air (after its first), how far its leg is shown straighter than
// the pose's (m, the worst).
struct AirborneLegs {
  float straighter_m = 0.0f;
  int airborne_frames = 0;
};
AirborneLegs airborne_legs_through_steered_walks(const MotionLibrary& lib, float turn_rad = 0.314f) {
  AirborneLegs out;
  for (const Walk& walk : walks(lib)) {
    const Transition& t = lib.graph.transitions[static_cast<size_t>(walk.transition)];
    const int n = lib.graph.segments[static_cast<size_t>(t.from)].num_frames();
    const int frames = n + lib.graph.segments[static_cast<size_t>(t.to)].num_frames();
    PoseStage stage(lib, {});
    PlaybackState s{t.from, 0, Placement{}, -1};
    bool was_up[2] = {false, false};
    for (int f = 0; f < frames; ++f) {
      if (f == n) playback_take(lib, s, walk.transition);
      s.frame = f < n ? f : f - n;
      if (f >= 1 && f <= 5) s.segment_start = playback_turned_start(lib, s, turn_rad);
      stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
      const std::span<const vec3> shown = stage.shown(), played = stage.animated();
      for (int foot = 0; foot < 2; ++foot) {
        const bool up = !(stage.contact() & (foot_heel_bit(foot) | foot_ball_bit(foot)));
        const bool first_frame_up = up && !was_up[foot];  // a forced step's first frame still reaches for the hold
        was_up[foot] = up;
        if (!up || first_frame_up) continue;
        const auto hip = static_cast<size_t>(foot == 0 ? kCanonLeftUpLeg : kCanonRightUpLeg);
        out.straighter_m = std::max(out.straighter_m, glm::length(shown[hip + 2] - shown[hip]) -
                                                          glm::length(played[hip + 2] - played[hip]));
        ++out.airborne_frames;
      }
    }
  }
  return out;
}

// A foot in the air is not shown on a leg straighter than the pose's. A foot let go of is shown
// at an offset that dies out (held back where it was planted while the body turned on): its leg
// was kept straight while the pose's bent, then the knee caught up in one frame (the maze's walk
// turns and side steps: knees at 121-133 mm/frame^2, most of the built-in library's pops). Here,
// before: legs up to 2.4 (0.1 rad a frame) and 6.2 cm (0.314) straighter, and 3.9 cm on the
// capture. (The knee's acceleration is not asserted here: these walks' own knees reach 115-121
// mm/frame^2 either way; the bench's pops are the measure: docs/MOTION_QUALITY.md.)
TEST(PoseStage, AFootInTheAirIsNotShownOnALegStraighterThanThePoses) {
  const MotionLibrary& lib = library();
  for (const float turn : {0.1f, 0.314f}) {
    const AirborneLegs r = airborne_legs_through_steered_walks(lib, turn);
    ASSERT_GT(r.airborne_frames, 100);
    EXPECT_LT(r.straighter_m, 1e-3f) << turn << " rad a frame";
  }
}

TEST(PoseStage, OnACaptureOfAnotherUnitAndRootAFootInTheAirIsNotShownOnALegStraighterThanThePoses) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  const AirborneLegs r = airborne_legs_through_steered_walks(lib);
  ASSERT_GT(r.airborne_frames, 100);
  EXPECT_LT(r.straighter_m, 1e-3f);
}

// Over every transition of `lib` played straight through (unsteered, from a few frames before the
// switch to a few after): the largest acceleration of a joint from the spine up about the switch,
// as played and as shown, m/frame^2, sorted.
struct SwitchAccel {
  std::vector<float> played, shown;
};
SwitchAccel upper_body_at_switches(const MotionLibrary& lib) {
  SwitchAccel out;
  const auto peak = [](const std::vector<std::vector<vec3>>& frames, size_t from, size_t to) {
    float a = 0.0f;
    for (size_t f = from; f <= to; ++f)
      a = std::max(a, test::largest_joint_acceleration(frames[f - 1], frames[f], frames[f + 1], kCanonSpine, kCanonLeftUpLeg));
    return a;
  };
  for (int i = 0; i < static_cast<int>(lib.graph.transitions.size()); ++i) {
    const Transition& t = lib.graph.transitions[static_cast<size_t>(i)];
    const int n = lib.graph.segments[static_cast<size_t>(t.from)].num_frames();
    if (n < 4 || lib.graph.segments[static_cast<size_t>(t.to)].num_frames() < 4) continue;
    PoseStage stage(lib);
    PlaybackState s{t.from, n - 4, Placement{}, -1};
    std::vector<std::vector<vec3>> shown, played;
    for (int f = 0; f < 8; ++f) {
      if (f == 4) playback_take(lib, s, i);
      const std::span<const vec3> p = stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
      shown.emplace_back(p.begin(), p.end());
      played.emplace_back(stage.animated().begin(), stage.animated().end());
      ++s.frame;
    }
    out.played.push_back(peak(played, 3, 6));  // the switch is frame 4
    out.shown.push_back(peak(shown, 3, 6));
  }
  std::sort(out.played.begin(), out.played.end());
  std::sort(out.shown.begin(), out.shown.end());
  return out;
}

// A transition's blend carries the pose on but not its rate (a hand swinging on at the end of a
// derived stop, the derived start beginning at rest: 158-282 mm/frame^2 in the Bandai maze runs):
// the stage carries the upper body's rate through a switch and lets the difference die out. Over
// the built-in library's 468 transitions the largest acceleration from the spine up about the
// switch, 90th percentile, is 44 mm/frame^2 as played and 41 as shown (it was as played); the
// worst, 95 as played, is 106 as shown (a punch leaving the stance, under the pop threshold of
// 121; figures from a temporary print).
TEST(PoseStage, ASwitchCarriesTheUpperBodysRateOn) {
  const SwitchAccel r = upper_body_at_switches(library());
  ASSERT_GT(r.played.size(), 100u);
  const size_t p90 = r.played.size() * 9 / 10;
  EXPECT_LT(r.shown[p90], r.played[p90]);
  EXPECT_LT(r.shown.back(), 0.121f) << "no switch shows a pop";
}

// The same on capture the team did not make (the Bandai walk in inches under a dummy root, with
// its derived starts, stops and bends, 889 transitions; and with its rotation channels reordered
// too): 90th percentile 43 mm/frame^2 as played, 29 as shown; the worst 80 as played, 63 as shown
// (figures from a temporary print).
TEST(PoseStage, OnACaptureOfAnotherUnitRootAndChannelOrderASwitchCarriesTheUpperBodysRateOn) {
  FORESIGHT_REQUIRE_MOCAP();
  for (const char* order : {"", "XYZ"}) {
    MotionLibrary lib;
    ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library(order, lib));
    const SwitchAccel r = upper_body_at_switches(lib);
    ASSERT_GT(r.played.size(), 100u) << order;
    const size_t p90 = r.played.size() * 9 / 10;
    EXPECT_LT(r.shown[p90], 0.8f * r.played[p90]) << order;
    EXPECT_LT(r.shown.back(), r.played.back()) << order;
  }
}

// A body that moved 30 cm in one frame (less than a jump the stage inertializes) leaves its
// planted feet behind, out of the legs' reach: each steps to where the clip has it, and from that
// very frame it is lifted, not planted. (It was counted planted on the step's first frame while
// the leg, too short for the hold, raised it: 5 cm off the ground and 65 cm/s of skate in the
// terrain scene's runs.) Any foot counted planted stands where the clip's does, in height.
TEST(PoseStage, AFootStartingAStepIsNotPlantedOnThatFrame) {
  const MotionLibrary& lib = library();
  PoseStage stage(lib);
  PlaybackState s;
  ASSERT_TRUE(stand_idle(stage, s));
  const int idle = s.segment;
  ASSERT_EQ(stage.contact() & (kLeftHeel | kRightHeel), kLeftHeel | kRightHeel);
  ASSERT_GT(stage.jump_m(), 0.3f);
  for (int f = 1; f <= 20; ++f) {
    s.frame = f % lib.graph.segments[idle].num_frames();
    if (f == 1) s.segment_start.pos_m.y += 0.3f;
    stage.update(s, 1.0f / 30.0f);
    if (f == 1) {
      EXPECT_EQ(stage.contact(), 0) << "both feet step from the first frame";
    }
    for (int foot = 0; foot < 2; ++foot)
      for (const int joint : {foot_heel_joint(foot), foot_ball_joint(foot)}) {
        const uint8_t bit = joint == foot_heel_joint(foot) ? foot_heel_bit(foot) : foot_ball_bit(foot);
        if (!(stage.contact() & bit)) continue;
        EXPECT_NEAR(stage.shown()[static_cast<size_t>(joint)].y, stage.animated()[static_cast<size_t>(joint)].y, 0.01f)
            << "frame " << f << " foot " << foot;
      }
  }
  EXPECT_EQ(stage.contact() & (kLeftHeel | kRightHeel), kLeftHeel | kRightHeel) << "planted again once there";
  EXPECT_LT(test::max_distance(std::vector<vec3>(stage.shown().begin(), stage.shown().end()),
                               std::vector<vec3>(stage.animated().begin(), stage.animated().end())),
            0.01f);
}

// `lib`'s standing loop: its first segment tagged idle, not crouching or fighting (-1: none).
int standing_idle(const MotionLibrary& lib) {
  for (int g = 0; g < lib.graph.num_segments(); ++g)
    if ((lib.graph.segments[static_cast<size_t>(g)].tags & (kTagIdle | kTagCrouch | kTagFight)) == kTagIdle) return g;
  return -1;
}

// `lib`'s idle (its standing loop) shown through a stage with only the offsets (no foot locks), with
// `world`'s boxes (nullptr: none): frame 0 where it stands, then from frame 1 on a metre sideways
// (a jump, as a fallback or a correction is), to frame 11. Calls `at` with the stage each frame.
void play_jumped_idle(const MotionLibrary& lib, const CollisionWorld* world, const FrameCheck& at) {
  const int idle = standing_idle(lib);
  ASSERT_GE(idle, 0) << "the library has an idle";
  PoseStageConfig config;
  config.foot_locking = false;  // the offsets alone
  PoseStage stage(lib, config);
  stage.set_obstacles(world);
  PlaybackState s{idle, 0, Placement{}, -1};
  for (int f = 0; f < 12; ++f) {
    s.frame = f;
    if (f == 1) s.segment_start = Placement{vec2(1.0f, 0.0f), 0.0f};
    stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
    at(f, stage);
  }
}

// `lib`'s idle shown with the foot locks off (the guard alone, or nothing with `guard` false), with
// `world`'s boxes (nullptr: none): still for 5 frames, then from frame 6 on set off sideways (+x)
// at once at `step_m` a frame (a change of velocity no clip frame has, less than a jump), to frame
// 35. Calls `at` with the stage each frame.
void play_set_off(const MotionLibrary& lib, float step_m, bool guard, const CollisionWorld* world, const FrameCheck& at) {
  const int idle = standing_idle(lib);
  ASSERT_GE(idle, 0) << "the library has an idle";
  PoseStageConfig config;
  config.foot_locking = false;
  config.acceleration_guard = guard;
  PoseStage stage(lib, config);
  stage.set_obstacles(world);
  PlaybackState s{idle, 0, Placement{}, -1};
  const int frames = lib.graph.segments[static_cast<size_t>(idle)].num_frames();
  for (int f = 0; f <= 35; ++f) {
    s.frame = f % frames;
    if (f > 5) s.segment_start.pos_m.x += step_m;
    stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
    at(f, stage);
  }
}

// That run's largest shown joint acceleration, how far the shown pose is from the played one at
// its end (a second after the set-off), and the most a bone's shown length differed from its
// played one.
struct SetOff {
  float largest_accel_m = 0.0f;
  float behind_at_end_m = 0.0f;
  float bone_change_m = 0.0f;
};
SetOff set_off_at_once(const MotionLibrary& lib, float step_m, bool guard) {
  SetOff out;
  std::vector<vec3> before, now;
  play_set_off(lib, step_m, guard, nullptr, [&](int f, const PoseStage& stage) {
    const std::span<const vec3> shown = stage.shown(), played = stage.animated();
    if (f >= 2) out.largest_accel_m = std::max(out.largest_accel_m, test::largest_joint_acceleration(before, now, shown));
    for (int j = 1; j < lib.num_joints(); ++j) {
      const auto p = static_cast<size_t>(lib.skeleton.parents[static_cast<size_t>(j)]), c = static_cast<size_t>(j);
      out.bone_change_m = std::max(out.bone_change_m,
                                   std::abs(glm::length(shown[c] - shown[p]) - glm::length(played[c] - played[p])));
    }
    before = now;
    now.assign(shown.begin(), shown.end());
    out.behind_at_end_m = test::max_distance(now, std::vector<vec3>(played.begin(), played.end()));
  });
  return out;
}

// A pose whose velocity changes in one frame by more than the library's clips ever change theirs
// (a body set off at 1.25 x the pop threshold a frame; the stage's other steps leave such changes
// near the threshold: a knee at the start of a walking turn, a toe at a walk's last frame) is
// shown with no joint over the guard's share of the threshold; what it held back dies out (the
// body shown where it is played, within 1 mm, a second later), and no bone changes its length (the
// body's joints held back alike). Without the guard the frame shows the whole change.
void expect_a_set_off_shown_within_the_threshold(const MotionLibrary& lib) {
  const float threshold = lib.pop_threshold_m;
  ASSERT_GT(threshold, 0.05f);
  const SetOff raw = set_off_at_once(lib, 1.25f * threshold, false);
  EXPECT_GT(raw.largest_accel_m, 1.2f * threshold) << "without the guard: a pop";
  const SetOff guarded = set_off_at_once(lib, 1.25f * threshold, true);
  EXPECT_LE(guarded.largest_accel_m, PoseStageConfig{}.guard_share * threshold + 1e-4f);
  EXPECT_LT(guarded.behind_at_end_m, 0.001f);
  EXPECT_LT(guarded.bone_change_m, 0.001f);
}

TEST(PoseStage, AChangeOfVelocityOverThePopThresholdIsShownWithinIt) {
  expect_a_set_off_shown_within_the_threshold(library());
}

// The same on capture the team did not make (the Bandai walk in inches under a dummy root: its
// own threshold, 146 mm/frame^2).
TEST(PoseStage, OnACaptureOfAnotherUnitAndRootAChangeOfVelocityOverThePopThresholdIsShownWithinIt) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  expect_a_set_off_shown_within_the_threshold(lib);
}

// What the guard holds back is not shown in a box the played pose clears: the set-off above with a
// thin post just behind the body as the guard shows it on the first frame set off (inside its
// trailing joint's flesh; the played body, 3-4 cm further on, clears it).
void expect_a_held_back_set_off_clear_of_a_post(const MotionLibrary& lib) {
  const float step = 1.25f * lib.pop_threshold_m;
  vec2 post(0.0f);
  ASSERT_NO_FATAL_FAILURE(play_set_off(lib, step, true, nullptr, [&](int f, const PoseStage& stage) {
    if (f != 6) return;
    const std::span<const vec3> shown = stage.shown();
    const auto trailing = std::min_element(shown.begin(), shown.end(), [](vec3 a, vec3 b) { return a.x < b.x; });
    post = ground(*trailing) - vec2(lib.body_margin_m - 0.01f, 0.0f);
  }));
  CollisionWorld world;
  ASSERT_NO_FATAL_FAILURE(build_post(post, world));
  const PlayWith play = [&](const CollisionWorld* boxes, const FrameCheck& at) { play_set_off(lib, step, true, boxes, at); };
  EXPECT_NO_FATAL_FAILURE(expect_shown_clear_of_post(lib, world, play, 10));
}

TEST(PoseStage, WhatTheGuardHoldsBackIsNotShownInABoxThePlayedPoseClears) {
  expect_a_held_back_set_off_clear_of_a_post(library());
}

TEST(PoseStage, OnACaptureOfAnotherUnitAndRootWhatTheGuardHoldsBackIsNotShownInABoxThePlayedPoseClears) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  expect_a_held_back_set_off_clear_of_a_post(lib);
}

// A played pose that jumps (a fallback, a correction) is shown continuing from where it was,
// the jump decaying over inertialize_s.
TEST(PoseStage, AJumpIsInertializedNotShown) {
  vec3 before(0.0f);
  float previous_x = 0.0f;
  ASSERT_NO_FATAL_FAILURE(play_jumped_idle(library(), nullptr, [&](int f, const PoseStage& stage) {
    const std::span<const vec3> shown = stage.shown();
    if (f == 0) before = shown[0];
    if (f == 1) {
      EXPECT_EQ(stage.discontinuities(), 1);
      EXPECT_LT(glm::length(shown[0] - before), 0.05f) << "no jump on the first frame";
    }
    if (f >= 2) {
      EXPECT_GE(shown[0].x, previous_x - 1e-4f) << "moving over, never back";
      // The offset dies out as a quintic (its rate and acceleration start and end at 0): its
      // fastest frame moves 1.875 x 1 m / 6 frames, 0.31 m (a 1 m jump takes a little longer,
      // 0.24 s, so that its acceleration stays within the guard's: 0.26 m).
      EXPECT_LT(shown[0].x - previous_x, 0.33f) << "in steps, not a jump";
    }
    if (f == 11) {
      EXPECT_NEAR(shown[0].x, stage.animated()[0].x, 1e-3f) << "arrived after inertialize_s";
    }
    previous_x = shown[0].x;
  }));
}

// An inertialized offset (a jump here; traced as a switch's carried forearm: Bandai maze, 1 cm into
// the wall the new segment turns along) would show a joint in a box the played pose clears: only
// the share of the offset that stays clear is shown, and the rest still dies out smoothly. An idle
// jumped 1 m sideways, with a thin post just behind the body shown on its way.
void expect_an_inertialized_offset_clear_of_a_post(const MotionLibrary& lib) {
  vec2 post(0.0f);
  ASSERT_NO_FATAL_FAILURE(play_jumped_idle(lib, nullptr, [&](int f, const PoseStage& stage) {
    if (f != 2) return;
    const std::span<const vec3> shown = stage.shown();
    const auto trailing = std::min_element(shown.begin(), shown.end(), [](vec3 a, vec3 b) { return a.x < b.x; });
    post = ground(*trailing) - vec2(0.05f, 0.0f);  // 5 cm behind the body, which moves on in +x
  }));
  CollisionWorld world;
  ASSERT_NO_FATAL_FAILURE(build_post(post, world));
  float previous_x = 0.0f;
  const PlayWith play = [&](const CollisionWorld* boxes, const FrameCheck& at) { play_jumped_idle(lib, boxes, at); };
  EXPECT_NO_FATAL_FAILURE(expect_shown_clear_of_post(lib, world, play, 5, [&](int f, const PoseStage& stage) {
    if (f > 1) {
      EXPECT_LT(std::abs(stage.shown()[0].x - previous_x), 0.33f) << "frame " << f << ": in steps, not a jump";
    }
    previous_x = stage.shown()[0].x;
  }));
}

TEST(PoseStage, AnInertializedOffsetIsNotShownInABoxThePlayedPoseClears) {
  expect_an_inertialized_offset_clear_of_a_post(library());
}

TEST(PoseStage, OnACaptureOfAnotherUnitAndRootAnInertializedOffsetIsNotShownInABoxThePlayedPoseClears) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  expect_an_inertialized_offset_clear_of_a_post(lib);
}

// A jump from mid-stride (a foot in the air) to a stand that plants both feet, as a fallback to
// idle is: the decaying offset brings the raised foot down over inertialize_s, and while it is
// still up it is landing, not planted (not held, not counted on the ground); once down it is.
TEST(PoseStage, AFootAnInertializedJumpHoldsInTheAirIsNotPlantedUntilDown) {
  const MotionLibrary& lib = library();
  const int walk = lib.graph.find_segment("walk_l"), idle = lib.graph.find_segment("idle");
  ASSERT_GE(walk, 0);
  ASSERT_GE(idle, 0);
  PoseStage stage(lib);
  PlaybackState s{walk, 0, Placement{vec2(0.0f), 0.0f}, -1};
  stage.update(s, 0.0f);
  int raised = -1;  // a frame of the step with one foot well off the floor
  for (int f = 1; f < lib.graph.segments[walk].num_frames() && raised < 0; ++f) {
    s.frame = f;
    stage.update(s, 1.0f / 30.0f);
    for (int foot = 0; foot < 2; ++foot)
      if (stage.animated()[static_cast<size_t>(foot_ball_joint(foot))].y > 0.08f) raised = foot;
  }
  ASSERT_GE(raised, 0);
  const uint8_t raised_bits = foot_ball_bit(raised) | foot_heel_bit(raised);
  s = PlaybackState{idle, 0, Placement{vec2(0.6f, 0.0f), 0.0f}, -1};  // unblended, 60 cm on
  stage.update(s, 1.0f / 30.0f);
  ASSERT_EQ(stage.discontinuities(), 1);
  ASSERT_EQ(lib.foot_contact_at(lib.graph.segments[idle].clip, lib.graph.segments[idle].first_frame) & raised_bits,
            raised_bits) << "the stand plants it";
  EXPECT_EQ(stage.contact() & raised_bits, 0) << "shown in the air: landing";
  bool landed = false;
  for (int f = 1; f < 10; ++f) {
    s.frame = f;
    const std::span<const vec3> shown = stage.update(s, 1.0f / 30.0f);
    const auto ball = static_cast<size_t>(foot_ball_joint(raised));
    if (stage.contact() & raised_bits) {
      landed = true;
      EXPECT_LT(shown[ball].y - stage.animated()[ball].y, 0.011f) << "planted only once down";
    }
  }
  EXPECT_TRUE(landed);
}

// A fallback to idle without a transition where a walking segment ends (as the look-ahead falls
// back when nothing feasible is left; 13 such pops a minute on the terrain scene before): the
// joints move less than the jump test, but the switch has no blend, so it is inertialized all the
// same, and the shown pose accelerates less about the switch than the played one does.
TEST(PoseStage, ASwitchWithoutATransitionIsInertializedHoweverSmall) {
  const MotionLibrary& lib = library();
  const int idle = lib.graph.find_segment("idle");
  ASSERT_GE(idle, 0);
  const auto largest_acceleration = [](const std::vector<std::vector<vec3>>& frames, size_t at) {
    return test::largest_joint_acceleration(frames[at - 1], frames[at], frames[at + 1]);
  };
  for (const char* name : {"walk_l", "walk_r", "walk_slow_l", "walk_slow_r"}) {
    const int walk = lib.graph.find_segment(name);
    ASSERT_GE(walk, 0) << name;
    PoseStage stage(lib);
    std::vector<std::vector<vec3>> shown, played;
    PlaybackState s{walk, 0, Placement{}, -1};
    const size_t switch_at = static_cast<size_t>(lib.graph.segments[walk].num_frames());
    for (size_t f = 0; f <= switch_at + 8; ++f, ++s.frame) {
      if (f == switch_at) s = PlaybackState{idle, 0, playback_next_start(lib, s), -1};
      const std::span<const vec3> p = stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f);
      shown.emplace_back(p.begin(), p.end());
      played.emplace_back(stage.animated().begin(), stage.animated().end());
    }
    float moved = 0.0f;
    for (size_t j = 0; j < played[0].size(); ++j)
      moved = std::max(moved, glm::length(played[switch_at][j] - played[switch_at - 1][j]));
    float shown_peak = 0.0f;
    for (size_t f = switch_at - 1; f <= switch_at + 6; ++f) shown_peak = std::max(shown_peak, largest_acceleration(shown, f));
    const float played_peak = std::max(largest_acceleration(played, switch_at - 1), largest_acceleration(played, switch_at));
    EXPECT_LT(moved, stage.jump_m()) << name << ": a switch the jump test alone would not see";
    EXPECT_EQ(stage.discontinuities(), 1) << name;
    EXPECT_LT(shown_peak, played_peak) << name;
  }
}

// A jump into another pose (an idle stand to mid-stride somewhere else, as a correction or a
// fallback may be) gives every joint its own decaying offset; the legs keep their bones' lengths
// all the while (without solving them again a shin was shown 7 cm short).
TEST(PoseStage, AnInertializedJumpKeepsTheLegsBones) {
  const MotionLibrary& lib = library();
  const int idle = lib.graph.find_segment("idle"), walk = lib.graph.find_segment("walk_l");
  ASSERT_GE(idle, 0);
  ASSERT_GE(walk, 0);
  PoseStage stage(lib);
  PlaybackState s{idle, 0, Placement{}, -1};
  stage.update(s, 0.0f);
  const Leg rest = leg(stage.animated(), kCanonLeftUpLeg);
  s = PlaybackState{walk, lib.graph.segments[walk].num_frames() / 2, Placement{vec2(0.6f, 0.3f), 1.2f}, -1};
  float worst = 0.0f, moved = 0.0f;
  std::vector<vec3> before(stage.shown().begin(), stage.shown().end());
  for (int f = 0; f < 6 && s.frame < lib.graph.segments[walk].num_frames(); ++f, ++s.frame) {
    const std::span<const vec3> shown = stage.update(s, 1.0f / 30.0f);
    for (const int hip : {kCanonLeftUpLeg, kCanonRightUpLeg}) {
      const Leg now = leg(shown, hip), played = leg(stage.animated(), hip);
      worst = std::max({worst, std::abs(now.upper - played.upper), std::abs(now.lower - played.lower)});
    }
    if (f == 0) moved = test::max_distance(std::vector<vec3>(shown.begin(), shown.end()), before);
  }
  EXPECT_EQ(stage.discontinuities(), 1);
  EXPECT_LT(moved, 0.25f) << "the jump is not shown at once";
  EXPECT_LT(worst, 1e-3f) << "a leg bone changed length by " << worst << " m";
  EXPECT_NEAR(rest.upper, leg(stage.animated(), kCanonLeftUpLeg).upper, 1e-3f);
}

// A jump whose new pose faces another way (a fallback's stand turned, a correction) leaves the
// shown knees where the old pose had them while the offset dies out; a planted leg reached from
// there kept that knee's side, which may point sideways or back from the new pose's knee (a
// fallback after a Bandai backward walk: 90 deg off for 3 frames, a limit violation). Shown
// through the stage, a clearly bent knee stays near the played knee's side (60 deg in the leg's
// reach; the foot's hold after it moves the leg a little more: 68 measured, 168 before, knees
// bent backwards). Here a crouched stand (knees bent well forward) jumps to itself turned 150 deg.
TEST(PoseStage, AnInertializedJumpShowsNoKneeTurnedFarFromThePlayedOnes) {
  const MotionLibrary& lib = library();
  const int crouch = lib.graph.find_segment("crouch_idle");
  ASSERT_GE(crouch, 0);
  const auto side = [](std::span<const vec3> p, int hip) {
    const vec3 axis = p[hip + 2] - p[hip], k = p[hip + 1] - p[hip];
    return k - axis * (glm::dot(k, axis) / glm::dot(axis, axis));
  };
  PoseStage stage(lib);
  PlaybackState s{crouch, 0, Placement{}, -1};
  stage.update(s, 0.0f);
  ASSERT_GT(glm::length(side(stage.animated(), kCanonLeftUpLeg)), 0.05f) << "the crouch bends its knees";
  s.segment_start = Placement{vec2(0.2f, 0.1f), radians(150.0f)};
  float worst_deg = 0.0f;
  for (int f = 1; f < 10; ++f) {
    s.frame = f;
    stage.update(s, 1.0f / 30.0f);
    for (const int hip : {kCanonLeftUpLeg, kCanonRightUpLeg}) {
      const vec3 played = side(stage.animated(), hip), shown = side(stage.shown(), hip);
      const float c = glm::dot(played, shown) / (glm::length(played) * glm::length(shown));
      worst_deg = std::max(worst_deg, degrees(std::acos(std::clamp(c, -1.0f, 1.0f))));
    }
  }
  EXPECT_EQ(stage.discontinuities(), 1);
  EXPECT_LT(worst_deg, 75.0f);
}

// The steering's turn (a walking segment's start rotated 18 deg in one frame, as 540 deg/s
// does) is shown eased: less than that on the frame, all of it a few frames later.
TEST(PoseStage, TheSteeringTurnIsEased) {
  ASSERT_GE(library().graph.find_segment("walk_l"), 0);
  SteeredWalk w(library());
  w.turn();
  EXPECT_GT(w.lag(kCanonLeftUpLeg, kCanonRightUpLeg), 0.1f) << "the shown body lags the played one on the turn's frame";
  w.play_to(11);
  EXPECT_LT(w.lag(kCanonLeftUpLeg, kCanonRightUpLeg), 0.02f) << "caught up";
}

// reset() forgets everything the stage carries from frame to frame (a turn's lag, a jump's
// decaying offset, foot locks, the ground heights and the feet's lifts): the next pose, wherever
// it is, is shown as a new stage would show it, not pulled towards the avatar's old place.
TEST(PoseStage, AfterResetItShowsWhatANewStageWould) {
  const MotionLibrary& lib = library();
  const int walk = lib.graph.find_segment("walk_l");
  ASSERT_GE(walk, 0);
  Terrain ground;  // a step the walk crosses: ground heights and foot lifts are live too
  ground.steps.push_back({"step", vec3(-10.0f, 0.0f, 2.3f), vec3(10.0f, 0.12f, 10.0f)});
  PoseStage used(lib);
  used.set_ground(&ground);
  PlaybackState s{walk, 0, Placement{vec2(6.0f, 2.0f), 0.0f}, -1};
  used.update(s, 0.0f);
  for (int f = 1; f < 12; ++f) {  // steered hard, then a jump: lag, offsets and locks are live
    s.frame = f;
    s.segment_start = playback_turned_start(lib, s, 0.314f);
    used.update(s, 1.0f / 30.0f);
  }
  s.segment_start.pos_m += vec2(0.0f, 0.6f);
  used.update(s, 1.0f / 30.0f);
  used.reset();
  PoseStage fresh(lib);
  fresh.set_ground(&ground);
  const PlaybackState elsewhere{walk, 5, Placement{vec2(-3.0f, 1.0f), 1.2f}, -1};
  for (int f = 0; f < 4; ++f) {
    PlaybackState at = elsewhere;
    at.frame += f;
    const float dt = f == 0 ? 0.0f : 1.0f / 30.0f;
    const std::span<const vec3> a = used.update(at, dt), b = fresh.update(at, dt);
    float worst = 0.0f;
    for (size_t j = 0; j < a.size(); ++j) worst = std::max(worst, glm::length(a[j] - b[j]));
    EXPECT_LT(worst, 1e-5f) << "frame " << f << " after reset: a joint " << worst << " m from a new stage's";
  }
}

// Orientation warping: on the turn's frame the chest and shoulders lag the turn more than the
// pelvis does, and both catch up.
TEST(PoseStage, ThePelvisFollowsTheTurnBeforeTheShoulders) {
  ASSERT_GE(library().graph.find_segment("walk_l"), 0);
  SteeredWalk w(library());
  w.turn();
  const float pelvis = w.lag(kCanonLeftUpLeg, kCanonRightUpLeg), shoulders = w.lag(kCanonLeftArm, kCanonRightArm);
  EXPECT_GT(pelvis, 0.05f) << "eased, not snapped";
  EXPECT_GT(shoulders, pelvis + 0.03f) << "the upper body keeps facing longer";
  w.play_to(15);
  EXPECT_LT(w.lag(kCanonLeftUpLeg, kCanonRightUpLeg), 0.02f);
  EXPECT_LT(w.lag(kCanonLeftArm, kCanonRightArm), 0.02f);
}

// Along a wall: the turn's lag would show a joint (the one it moves farthest, a hand) inside a post
// the played pose is clear of, which the bench counts as a colliding frame. Given the scene's
// boxes, the stage shows only as much of the lag as stays clear, eases the rest, and catches up.
TEST(PoseStage, TheEasedTurnShowsNoJointInABoxThePlayedPoseClears) {
  const MotionLibrary& lib = library();
  ASSERT_GE(lib.graph.find_segment("walk_l"), 0);
  SteeredWalk free(lib);
  free.turn();
  const std::span<const vec3> lagged = free.stage.shown(), played = free.stage.animated();
  size_t far = 0;
  for (size_t j = 0; j < lagged.size(); ++j)
    if (glm::length(ground(lagged[j]) - ground(played[j])) > glm::length(ground(lagged[far]) - ground(played[far]))) far = j;
  const vec2 lag = ground(lagged[far]) - ground(played[far]);
  ASSERT_GT(glm::length(lag), 0.04f);
  const vec2 post = ground(lagged[far]) + 0.05f * glm::normalize(lag);  // 1 cm square, 2 m high
  CollisionWorld world;
  ASSERT_NO_FATAL_FAILURE(build_post(post, world));
  ASSERT_TRUE(shown_joints_collide(lib, world, lagged)) << "without the boxes the lag is shown in the post";
  ASSERT_FALSE(shown_joints_collide(lib, world, played)) << "the played pose clears it";

  SteeredWalk walled(lib);
  walled.stage.set_obstacles(&world);
  walled.turn();
  EXPECT_FALSE(shown_joints_collide(lib, world, walled.stage.shown()));
  EXPECT_GT(walled.lag(kCanonLeftUpLeg, kCanonRightUpLeg), 0.02f) << "the rest of the turn is still eased";
  for (int frame = 2; frame <= 15; ++frame) {
    walled.play_to(frame);
    if (shown_joints_collide(lib, world, walled.stage.animated())) continue;  // the clip's own
    EXPECT_FALSE(shown_joints_collide(lib, world, walled.stage.shown())) << "frame " << frame;
  }
  EXPECT_LT(walled.lag(kCanonLeftUpLeg, kCanonRightUpLeg), 0.02f) << "caught up";
  EXPECT_LT(walled.lag(kCanonLeftArm, kCanonRightArm), 0.02f);
}

// Ground adaptation: an idle avatar with its left foot on a 12 cm step, then on a 20 % slope.
// Planted parts stand as high over the ground under them as the clip has them over its floor,
// the pelvis goes no higher than the lower foot allows, bones keep their lengths, and on the
// slope the foot pitches with the ground.
float planted_ground_error(std::span<const vec3> shown, std::span<const vec3> animated, uint8_t contact,
                           const Terrain& terrain) {
  float worst = 0.0f;
  for (int foot = 0; foot < 2; ++foot)
    for (const auto& [joint, bit] : {std::pair{foot_heel_joint(foot), foot_heel_bit(foot)},
                                    std::pair{foot_ball_joint(foot), foot_ball_bit(foot)}}) {
      if (!(contact & bit)) continue;
      float g = 0.0f;
      EXPECT_TRUE(terrain_height_at(terrain, ground(shown[joint]), g));
      worst = std::max(worst, std::abs(shown[joint].y - (g + animated[joint].y)));
    }
  return worst;
}

// A client may show a segment at its end (frame == num_frames(), its successor not yet known):
// on uneven ground the stage then looks for the swinging foot's landing within the segment only
// (found by the client's screenshot tests under ASan: it sampled a frame past the end).
TEST(PoseStage, ASegmentShownAtItsEndOnUnevenGround) {
  const MotionLibrary& lib = library();
  const int walk = lib.graph.find_segment("walk_l");
  ASSERT_GE(walk, 0);
  Terrain step;
  step.steps.push_back({"step", vec3(-1.0f, 0.0f, 0.5f), vec3(1.0f, 0.12f, 3.0f)});
  PoseStage stage(lib);
  stage.set_ground(&step);
  PlaybackState s{walk, 0, Placement{}, -1};
  for (int f = 0; f <= lib.graph.segments[walk].num_frames(); ++f) {
    s.frame = f;
    for (const vec3& p : stage.update(s, f == 0 ? 0.0f : 1.0f / 30.0f)) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
  }
}

TEST(PoseStage, FeetStandOnTheGroundUnderThem) {
  const MotionLibrary& lib = library();
  const int idle = lib.graph.find_segment("idle");
  ASSERT_GE(idle, 0);
  PlaybackState s{idle, 0, Placement{}, -1};
  Terrain step;
  step.steps.push_back({"step", vec3(0.0f, 0.0f, -1.0f), vec3(1.0f, 0.12f, 1.0f)});  // under the left foot (+x)
  Terrain slope;
  slope.height_field = {vec2(-2.0f), 0.02f, 200, 200, {}};
  for (int iz = 0; iz < 200; ++iz)
    for (int ix = 0; ix < 200; ++ix) slope.height_field.heights_m.push_back(0.2f * (-2.0f + 0.02f * (iz + 0.5f)));
  for (const Terrain* terrain : {&step, &slope}) {
    PoseStage stage(lib);
    stage.set_ground(terrain);
    stage.update(s, 0.0f);
    for (int f = 1; f <= 45; ++f) {
      s.frame = f % lib.graph.segments[idle].num_frames();
      stage.update(s, 1.0f / 30.0f);
    }
    const std::span<const vec3> shown = stage.shown(), animated = stage.animated();
    ASSERT_NE(stage.contact() & (kLeftHeel | kLeftBall), 0);
    EXPECT_LT(planted_ground_error(shown, animated, stage.contact(), *terrain), 0.005f);
    for (const int hip : {kCanonLeftUpLeg, kCanonRightUpLeg}) {
      EXPECT_NEAR(leg(shown, hip).upper, leg(animated, hip).upper, 1e-3f);
      EXPECT_NEAR(leg(shown, hip).lower, leg(animated, hip).lower, 1e-3f);
      EXPECT_LT(glm::length(shown[hip + 2] - shown[hip]), 0.996f * (leg(animated, hip).upper + leg(animated, hip).lower));
    }
    if (terrain == &step) {
      EXPECT_NEAR(shown[kCanonLeftFoot].y - animated[kCanonLeftFoot].y, 0.12f, 0.005f) << "on the step";
      EXPECT_NEAR(shown[kCanonRightFoot].y, animated[kCanonRightFoot].y, 0.005f) << "on the floor";
      EXPECT_LE(shown[kCanonHips].y, animated[kCanonHips].y + 1e-3f) << "the pelvis is not lifted off the lower foot";
    } else {
      const float lower_foot = std::min(shown[kCanonLeftFoot].y - animated[kCanonLeftFoot].y,
                                        shown[kCanonRightFoot].y - animated[kCanonRightFoot].y);
      EXPECT_NEAR(shown[kCanonHips].y - animated[kCanonHips].y, lower_foot, 1e-3f) << "lowered to the lower foot";
      for (const int ankle : {kCanonLeftFoot, kCanonRightFoot}) {  // the foot pitched with the slope
        const vec3 sa = shown[ankle + 1] - shown[ankle], aa = animated[ankle + 1] - animated[ankle];
        EXPECT_NEAR(glm::length(sa), glm::length(aa), 1e-3f);
        EXPECT_NEAR(sa.y - aa.y, 0.2f * sa.z, 0.01f);
      }
    }
  }
}

// A foot planted across a stair's edge (heel over the floor, ball over a 15 cm step) rests on
// the step, its heel hanging, as a foot on a stair does: placed at the heel's level, the ball
// would stand 15 cm inside the step. The hanging heel is not on the ground: only the ball counts
// planted.
TEST(PoseStage, AFootAcrossAStepEdgeRestsOnTheStep) {
  const MotionLibrary& lib = library();
  const int idle = lib.graph.find_segment("idle");
  ASSERT_GE(idle, 0);
  PlaybackState s{idle, 0, Placement{}, -1};
  PoseStage flat(lib);
  const std::span<const vec3> played = flat.update(s, 0.0f);
  const vec3 heel = played[static_cast<size_t>(foot_heel_joint(0))], ball = played[static_cast<size_t>(foot_ball_joint(0))];
  ASSERT_GT(ball.z - heel.z, 0.05f);  // the ball ahead of the heel
  Terrain stair;  // from between the left heel and ball forwards, under the left foot only
  stair.steps.push_back({"stair", vec3(heel.x - 0.08f, 0.0f, 0.5f * (heel.z + ball.z)), vec3(heel.x + 0.08f, 0.15f, 1.0f)});
  PoseStage stage(lib);
  stage.set_ground(&stair);
  stage.update(s, 0.0f);
  for (int f = 1; f <= 45; ++f) {
    s.frame = f % lib.graph.segments[idle].num_frames();
    stage.update(s, 1.0f / 30.0f);
  }
  const std::span<const vec3> shown = stage.shown(), animated = stage.animated();
  ASSERT_EQ(stage.contact() & (kLeftHeel | kLeftBall), kLeftBall) << "the ball held, the hanging heel not on the ground";
  const auto b = static_cast<size_t>(foot_ball_joint(0)), h = static_cast<size_t>(foot_heel_joint(0));
  EXPECT_NEAR(shown[b].y - animated[b].y, 0.15f, 0.005f) << "the ball on the step";
  EXPECT_GT(shown[h].y - animated[h].y, 0.10f) << "the heel hangs over the floor";
  EXPECT_NEAR(glm::length(shown[b] - shown[h]), glm::length(animated[b] - animated[h]), 1e-3f);
}

// The other way round: the heel on a step, the ball past its edge over the floor 15 cm below
// (as a foot stepping down off a step lands). The ball pitches down as far as a foot does and
// hangs: it is not counted on the ground, whatever the clip plants (it was: 13.7 cm off the
// ground and 163 cm/s of skate in one frame of 30 terrain seeds); the heel is held. (Any planted
// part shown more than 2 cm over the ground under it hangs, as the heel above does.)
TEST(PoseStage, ABallPastAStepEdgeHangsAndOnlyTheHeelIsPlanted) {
  const MotionLibrary& lib = library();
  const int idle = lib.graph.find_segment("idle");
  ASSERT_GE(idle, 0);
  PlaybackState s{idle, 0, Placement{}, -1};
  PoseStage flat(lib);
  const std::span<const vec3> played = flat.update(s, 0.0f);
  const vec3 heel = played[static_cast<size_t>(foot_heel_joint(0))], ball = played[static_cast<size_t>(foot_ball_joint(0))];
  ASSERT_GT(ball.z - heel.z, 0.05f);  // the ball ahead of the heel
  ASSERT_EQ(flat.contact() & (kLeftHeel | kLeftBall), kLeftHeel | kLeftBall) << "the clip plants both";
  Terrain step;  // under the left heel only, ending between the heel and the ball
  step.steps.push_back({"step", vec3(heel.x - 0.08f, 0.0f, -1.0f), vec3(heel.x + 0.08f, 0.15f, 0.5f * (heel.z + ball.z))});
  PoseStage stage(lib);
  stage.set_ground(&step);
  stage.update(s, 0.0f);
  for (int f = 1; f <= 45; ++f) {
    s.frame = f % lib.graph.segments[idle].num_frames();
    stage.update(s, 1.0f / 30.0f);
  }
  const std::span<const vec3> shown = stage.shown(), animated = stage.animated();
  const auto b = static_cast<size_t>(foot_ball_joint(0)), h = static_cast<size_t>(foot_heel_joint(0));
  EXPECT_EQ(stage.contact() & (kLeftHeel | kLeftBall), kLeftHeel) << "the heel held, the ball not";
  EXPECT_NEAR(shown[h].y - animated[h].y, 0.15f, 0.005f) << "the heel on the step";
  EXPECT_GT(shown[b].y - animated[b].y, 0.05f) << "the ball hangs over the floor";
  EXPECT_NEAR(glm::length(shown[b] - shown[h]), glm::length(animated[b] - animated[h]), 1e-3f);
}

// A step up found two frames before a swinging foot lands (as when steering turns the landing
// onto a step at the last moment: the stage sees only the ground under the landing change) is
// climbed at the bounded acceleration and landed late: the foot's height never accelerates by
// more than 40 mm/frame^2 (an 18 cm climb in the 2 frames left needs 180, over the library's pop
// threshold), and the foot is not counted on the ground until it is within 1 cm of it; then it
// is planted on the step. (Before, it jumped 9 cm in a frame: a knee at 157 mm/frame^2.)
void expect_a_late_step_up_climbed_and_landed_late(const MotionLibrary& lib) {
  // The first segment that lands a foot after a swing of at least 4 frames within itself, 3
  // frames before its end at least (a walk step lands on its successor's first frame): which
  // segment, foot and frame.
  int walk = -1, foot = -1, landing = -1;
  for (int g = 0; g < static_cast<int>(lib.graph.segments.size()) && walk < 0; ++g) {
    const Segment& candidate = lib.graph.segments[static_cast<size_t>(g)];
    for (int k = 0; k < 2 && walk < 0; ++k) {
      const uint8_t bits = foot_heel_bit(k) | foot_ball_bit(k);
      int swing = 0;
      for (int f = 0; f < candidate.num_frames() && walk < 0; ++f) {
        const bool down = lib.foot_contact_at(candidate.clip, candidate.first_frame + f) & bits;
        if (down && swing >= 4 && f >= 4 && f + 3 < candidate.num_frames()) walk = g, foot = k, landing = f;
        swing = down ? 0 : swing + 1;
      }
    }
  }
  ASSERT_GE(walk, 0) << "a segment lands a foot within itself";
  const Segment& seg = lib.graph.segments[static_cast<size_t>(walk)];
  const auto ankle = static_cast<size_t>(foot_heel_joint(foot));
  const uint8_t bits = foot_heel_bit(foot) | foot_ball_bit(foot);
  Terrain flat;  // the floor; and an 18 cm step under the whole landing foot, found late
  Terrain stepped;
  PoseStage probe(lib);
  PlaybackState s{walk, landing, Placement{}, -1};
  const vec3 lands_at = probe.update(s, 0.0f)[ankle];
  stepped.steps.push_back(
      {"step", vec3(lands_at.x - 0.08f, 0.0f, lands_at.z - 0.15f), vec3(lands_at.x + 0.08f, 0.18f, lands_at.z + 0.4f)});
  PoseStage stage(lib);
  stage.set_ground(&flat);
  s.frame = 0;
  stage.update(s, 0.0f);
  float lift[3] = {0.0f, 0.0f, 0.0f};  // the foot's height over its clip's, the last three frames
  bool landed = false;
  for (int f = 1; f < seg.num_frames(); ++f) {
    if (f == landing - 2) stage.set_ground(&stepped);
    s.frame = f;
    stage.update(s, 1.0f / 30.0f);
    lift[0] = lift[1], lift[1] = lift[2], lift[2] = stage.shown()[ankle].y - stage.animated()[ankle].y;
    if (f >= landing - 1) {
      SCOPED_TRACE(f);
      EXPECT_LT(std::abs(lift[2] - 2.0f * lift[1] + lift[0]), 0.045f) << "the climb's acceleration bounded";
      const bool planted = (stage.contact() & bits) != 0;
      if (planted) {
        EXPECT_NEAR(lift[2], 0.18f, 0.011f) << "counted on the ground only once on the step";
      }
      if (f == landing) {
        EXPECT_FALSE(planted) << "the clip plants it now: it is still climbing";
      }
      landed = landed || planted;
    }
  }
  EXPECT_TRUE(landed) << "planted on the step before the segment ends";
  EXPECT_NEAR(lift[2], 0.18f, 0.011f);
}

TEST(PoseStage, AStepUpFoundLateIsClimbedAtTheBoundedRateAndLandedLate) {
  expect_a_late_step_up_climbed_and_landed_late(library());
}

// The same on capture the team did not make (the Bandai walk in inches under a dummy root).
TEST(PoseStage, OnACaptureOfAnotherUnitAndRootAStepUpFoundLateIsLandedLate) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  expect_a_late_step_up_climbed_and_landed_late(lib);
}

// The ground is read where a locked foot is shown: the body drifts 5 cm forwards (less than a
// lock lets go at), so the clip's left ball moves over a step's edge while the lock keeps the
// foot on the floor. The ball stays on the floor, not pitched up towards the step it is not on.
TEST(PoseStage, ALockedFootReadsTheGroundWhereItIsHeld) {
  const MotionLibrary& lib = library();
  const int idle = lib.graph.find_segment("idle");
  ASSERT_GE(idle, 0);
  PlaybackState s{idle, 0, Placement{}, -1};
  PoseStage flat(lib);
  const std::span<const vec3> played = flat.update(s, 0.0f);
  const auto b = static_cast<size_t>(foot_ball_joint(0)), h = static_cast<size_t>(foot_heel_joint(0));
  const vec3 ball = played[b];
  Terrain edge;  // just ahead of the left ball, under the left foot only
  edge.steps.push_back({"edge", vec3(ball.x - 0.1f, 0.0f, ball.z + 0.02f), vec3(ball.x + 0.1f, 0.15f, ball.z + 1.0f)});
  PoseStage stage(lib);
  stage.set_ground(&edge);
  stage.update(s, 0.0f);
  for (int f = 1; f <= 10; ++f) {
    s.frame = f;
    s.segment_start.pos_m.y = 0.005f * static_cast<float>(f);  // 5 cm in all
    stage.update(s, 1.0f / 30.0f);
  }
  ASSERT_EQ(stage.contact() & (kLeftHeel | kLeftBall), kLeftHeel | kLeftBall);
  const std::span<const vec3> shown = stage.shown(), animated = stage.animated();
  ASSERT_GT(animated[b].z, ball.z + 0.03f) << "the clip's ball is over the step now";
  EXPECT_LT(shown[b].z, ball.z + 0.01f) << "the lock holds the foot where it was";
  EXPECT_NEAR(shown[b].y, animated[b].y, 0.005f) << "the ball on the floor it is held on";
  EXPECT_NEAR(shown[h].y, animated[h].y, 0.005f);
}

// The capture's first walking segment that goes forward 0.3 m or more.
int forward_walk(const MotionLibrary& lib) {
  for (int s = 0; s < lib.graph.num_segments(); ++s)
    if ((lib.graph.segments[s].tags & kTagLocomotion) && lib.segment_motion[static_cast<size_t>(s)].end.pos_m.y > 0.3f)
      return s;
  return -1;
}

// Plays `segments` segments from `first` through the stage, each followed by its most forward
// successor (open loop, heading 0: towards +Z), calling `frame` after every shown frame.
void walk_forward(const MotionLibrary& lib, PoseStage& stage, int first, int segments,
                  const std::function<void()>& frame) {
  PlaybackState st{first, 0, Placement{}, -1};
  stage.update(st, 0.0f);
  for (int step = 0; step < segments; ++step) {
    for (int f = step == 0 ? 1 : 0; f < lib.graph.segments[st.segment].num_frames(); ++f) {
      st.frame = f;
      stage.update(st, 1.0f / 30.0f);
      frame();
    }
    int next = -1;
    float forward = 0.0f;
    const auto successors = lib.graph.successors(st.segment);
    for (size_t i = 0; i < successors.size(); ++i) {
      const float y = lib.segment_motion[static_cast<size_t>(successors[i].to)].end.pos_m.y;
      if (next < 0 || y > forward) next = lib.graph.first_transition[st.segment] + static_cast<int>(i), forward = y;
    }
    ASSERT_GE(next, 0);
    st.frame = lib.graph.segments[st.segment].num_frames();
    playback_take(lib, st, next);
  }
}

// Foot locking on capture the team did not make (the Bandai locomotion takes), played with the
// root turning 2 deg a frame (steering) from a segment where a foot's hold rolls from one part to
// the other (heel to ball, or ball to heel: the capture lifts the ball before the heel in
// places): the held part (its ball when the ball is planted, else its heel, as the motion-quality
// bench measures) does not slide from one planted frame to the next, on the roll's frame too.
// (The newly held part was held from where the clip had moved it that frame: up to 1.2 cm, 36
// cm/s on the maze.)
TEST(PoseStage, OnCaptureTheHoldRollsFromPartToPartWithoutSliding) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionSource source;
  source.motions_dir = test::mocap_dir() / "locomotion";
  MotionLibrary lib;
  std::string error;
  ASSERT_TRUE(motion_library_from_folder(source, lib, nullptr, error)) << error;
  // A segment with a roll: one of its feet planted on two frames running, its ball on one only.
  const auto rolls_in = [&lib](int s) {
    const Segment& seg = lib.graph.segments[s];
    for (int f = seg.first_frame + 1; f < seg.end_frame; ++f)
      for (int foot = 0; foot < 2; ++foot) {
        const uint8_t bits = foot_ball_bit(foot) | foot_heel_bit(foot);
        const uint8_t a = lib.foot_contact_at(seg.clip, f - 1), b = lib.foot_contact_at(seg.clip, f);
        if ((a & bits) && (b & bits) && ((a ^ b) & foot_ball_bit(foot))) return true;
      }
    return false;
  };
  int first = -1;
  for (int s = 0; s < lib.graph.num_segments() && first < 0; ++s)
    if ((lib.graph.segments[s].tags & kTagLocomotion) && rolls_in(s) && !lib.graph.successors(s).empty()) first = s;
  ASSERT_GE(first, 0) << "no roll in the capture's locomotion";
  PoseStage stage(lib);
  PlaybackState st{first, 0, Placement{}, -1};
  stage.update(st, 0.0f);
  uint8_t before = stage.contact();
  std::vector<vec3> last(stage.shown().begin(), stage.shown().end());
  float worst = 0.0f;
  int rolls = 0, held = 0;
  for (int frame = 1; frame <= 90; ++frame) {
    const int frames = lib.graph.segments[st.segment].num_frames();
    if (++st.frame >= frames) {  // on to the first successor, played as the tree would
      st.frame = frames;
      if (lib.graph.successors(st.segment).empty()) break;
      playback_take(lib, st, lib.graph.first_transition[st.segment]);
    }
    st.segment_start = playback_turned_start(lib, st, 0.035f);
    stage.update(st, 1.0f / 30.0f);
    const uint8_t now = stage.contact();
    for (int foot = 0; foot < 2; ++foot) {
      const bool ball = now & foot_ball_bit(foot), heel = now & foot_heel_bit(foot);
      const uint8_t bit = ball ? foot_ball_bit(foot) : foot_heel_bit(foot);
      if ((!ball && !heel) || !(before & bit)) continue;  // not planted, or planted this frame
      const auto j = static_cast<size_t>(ball ? foot_ball_joint(foot) : foot_heel_joint(foot));
      rolls += ball != static_cast<bool>(before & foot_ball_bit(foot));
      ++held;
      worst = std::max(worst, glm::length(ground(stage.shown()[j]) - ground(last[j])));
    }
    before = now;
    last.assign(stage.shown().begin(), stage.shown().end());
  }
  EXPECT_GT(held, 20);
  EXPECT_GT(rolls, 0) << "the hold rolled from one part to the other";
  EXPECT_LT(worst, 0.002f) << "2 mm a frame, 6 cm/s";
}

// Ground adaptation on capture the team did not make (the Bandai walk in inches under a dummy
// root): walked up a 20 % slope, its planted parts stand on the ground under them, where the
// played ones sink into it by up to the slope's rise along the stride.
TEST(PoseStage, OnACaptureOfAnotherUnitAndRootFeetStandOnASlope) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  const int walking = forward_walk(lib);
  ASSERT_GE(walking, 0);
  Terrain slope;  // rising 0.2 m per metre towards +Z, the way heading 0 walks
  slope.height_field = {vec2(-4.0f), 0.02f, 400, 400, {}};
  for (int iz = 0; iz < 400; ++iz)
    for (int ix = 0; ix < 400; ++ix) slope.height_field.heights_m.push_back(0.2f * (-4.0f + 0.02f * (iz + 0.5f)));
  PoseStage stage(lib);
  stage.set_ground(&slope);
  float shown_worst = 0.0f, played_worst = 0.0f;
  int planted_frames = 0;
  walk_forward(lib, stage, walking, 6, [&] {  // 2-3 m uphill
    if (!(stage.contact() & (kLeftHeel | kLeftBall | kRightHeel | kRightBall))) return;
    ++planted_frames;
    shown_worst = std::max(shown_worst, planted_ground_error(stage.shown(), stage.animated(), stage.contact(), slope));
    played_worst =
        std::max(played_worst, planted_ground_error(stage.animated(), stage.animated(), stage.contact(), slope));
  });
  EXPECT_GT(planted_frames, 10);
  EXPECT_GT(played_worst, 0.2f) << "the clip's own feet sink into the slope (58 cm at 3 m)";
  EXPECT_LT(shown_worst, 0.02f) << "the shown ones stand on it (1.2 cm at worst)";
}

// The same capture up a flight of stairs (12 cm risers, 30 cm treads: a level nobody tuned the
// stage for, whose edges the walk's strides cross anywhere): every frame, the part a planted foot
// rests on (its ball when the ball is planted, else its heel, as the motion-quality bench
// measures) is within 2 cm of the ground under it. A swinging foot goes to the height of the
// tread it will land on, a part landing on or creeping over an edge is put on the tread it stands
// on, and a ball held behind the body at push-off lifts the heel instead of being dragged.
TEST(PoseStage, OnACaptureOfAnotherUnitAndRootFeetLandOnStairTreads) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("", lib));
  const int walking = forward_walk(lib);
  ASSERT_GE(walking, 0);
  Terrain stairs;  // from z = 0.5 m on, each tread a block on the one before
  for (int i = 0; i < 12; ++i)
    stairs.steps.push_back({"tread", vec3(-5.0f, 0.0f, 0.5f + 0.3f * static_cast<float>(i)),
                            vec3(5.0f, 0.12f * static_cast<float>(i + 1), 20.0f)});
  PoseStage stage(lib);
  stage.set_ground(&stairs);
  float shown_worst = 0.0f, played_worst = 0.0f, highest = 0.0f;
  int planted_frames = 0;
  walk_forward(lib, stage, walking, 8, [&] {
    for (int foot = 0; foot < 2; ++foot) {
      const uint8_t contact = stage.contact();
      if (!(contact & (foot_ball_bit(foot) | foot_heel_bit(foot)))) continue;
      const auto part = static_cast<size_t>(contact & foot_ball_bit(foot) ? foot_ball_joint(foot) : foot_heel_joint(foot));
      float g = 0.0f, played_g = 0.0f;
      ASSERT_TRUE(terrain_height_at(stairs, ground(stage.shown()[part]), g));
      ASSERT_TRUE(terrain_height_at(stairs, ground(stage.animated()[part]), played_g));
      ++planted_frames;
      highest = std::max(highest, g);
      shown_worst = std::max(shown_worst, std::abs(stage.shown()[part].y - (g + stage.animated()[part].y)));
      played_worst = std::max(played_worst, played_g);
    }
  });
  EXPECT_GT(planted_frames, 40);
  EXPECT_GT(highest, 0.5f) << "the walk climbs several treads";
  EXPECT_GT(played_worst, 0.5f) << "the clip's own feet stay on its flat floor, inside the stairs";
  EXPECT_LT(shown_worst, 0.02f);
}

// Not only our own clips: a captured walk, rescaled to inches, under a dummy root and with its
// rotation channels reordered, imported with no hint. Its feet are found planted, and while the
// root steers (2 deg a frame) the shown planted parts stay put where the played ones slide.
TEST(PoseStage, OnACaptureOfAnotherUnitRootAndChannelOrderPlantedFeetStayPut) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_walk_library("XYZ", lib));
  ASSERT_EQ(lib.foot_contact.size(), lib.root_track.size());
  int walking = -1;
  for (int s = 0; s < lib.graph.num_segments() && walking < 0; ++s)
    if ((lib.graph.segments[s].tags & kTagLocomotion) && lib.segment_motion[static_cast<size_t>(s)].end.pos_m.y > 0.3f)
      walking = s;
  ASSERT_GE(walking, 0);
  PoseStage stage(lib);
  PlaybackState st{walking, 0, Placement{}, -1};
  const std::span<const vec3> first = stage.update(st, 0.0f);
  std::vector<vec3> before(first.begin(), first.end());
  std::vector<vec3> played_before(stage.animated().begin(), stage.animated().end());
  uint8_t contact_before = stage.contact();
  int planted_pairs = 0;
  float shown_sum = 0.0f, played_sum = 0.0f;
  for (int f = 1; f < lib.graph.segments[walking].num_frames(); ++f) {
    st.segment_start = playback_turned_start(lib, st, 0.035f);
    st.frame = f;
    const std::span<const vec3> shown = stage.update(st, 1.0f / 30.0f);
    for (int foot = 0; foot < 2; ++foot) {
      // The part held: the ball when it is planted, else the heel (as the stage and the bench).
      const uint8_t bit = (stage.contact() & foot_ball_bit(foot)) ? foot_ball_bit(foot) : foot_heel_bit(foot);
      if (!(contact_before & bit) || !(stage.contact() & bit)) continue;
      const auto j = static_cast<size_t>(bit == foot_ball_bit(foot) ? foot_ball_joint(foot) : foot_heel_joint(foot));
      ++planted_pairs;
      shown_sum += glm::length(shown[j] - before[j]);
      played_sum += glm::length(stage.animated()[j] - played_before[j]);
    }
    before.assign(shown.begin(), shown.end());
    played_before.assign(stage.animated().begin(), stage.animated().end());
    contact_before = stage.contact();
  }
  ASSERT_GT(planted_pairs, 5) << "the capture's feet should be found planted";
  EXPECT_GT(played_sum / static_cast<float>(planted_pairs), 0.002f) << "played feet slide under steering";
  EXPECT_LT(shown_sum, 0.2f * played_sum) << "shown planted parts stay (nearly) put";
}

}  // namespace
}  // namespace foresight
