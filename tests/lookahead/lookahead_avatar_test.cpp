#include "lookahead/lookahead_avatar.hpp"

#include "anim/fk.hpp"
#include "library/playback.hpp"
#include "library/pose_check.hpp"
#include "library/pose_stage.hpp"
#include "library/steerability.hpp"
#include "scripted/recording_generator.hpp"
#include "scripted/replay.hpp"
#include "scripted/response_meter.hpp"
#include "lookahead/scene_path.hpp"
#include "lookahead_fixture.hpp"
#include "library/foreign_capture.hpp"
#include "support/shown_motion.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace foresight {
namespace {

using test::default_library;
using test::loaded_scene;

struct RunStats {
  int colliding_frames = 0;
  vec2 displacement{0.0f};
};

RunStats run(LookaheadAvatar& avatar, const MotionLibrary& lib, const CollisionWorld& world,
             const ControlInput& input, int frames, int64_t expansions_per_frame) {
  RunStats stats;
  PoseCheckScratch scratch;
  const vec2 start = avatar.root().pos_m;
  for (int f = 0; f < frames; ++f) {
    avatar.set_input(input);
    avatar.grow(GrowBudget::expansions(expansions_per_frame));
    avatar.step();
    stats.colliding_frames += shown_pose_collides(lib, world, avatar.playback(), scratch);
  }
  stats.displacement = avatar.root().pos_m - start;
  return stats;
}

TEST(ControlInput, CameraSpaceBecomesWorldAndAvatarDirections) {
  ControlInput in;
  in.camera_dir = vec2(0, 1);  // "up": along the camera's view
  in.camera_yaw_rad = 0.0f;    // camera looks along +Z
  EXPECT_NEAR(glm::length(control_world_direction(in) - vec2(0, 1)), 0.0f, 1e-6f);
  in.camera_dir = vec2(1, 0);  // "right": the camera's right is -X when it looks along +Z
  EXPECT_NEAR(glm::length(control_world_direction(in) - vec2(-1, 0)), 0.0f, 1e-6f);
  in.camera_dir = vec2(0, 1);
  in.camera_yaw_rad = kPi / 2;  // camera looks along +X
  EXPECT_NEAR(glm::length(control_world_direction(in) - vec2(1, 0)), 0.0f, 1e-6f);
  // An avatar facing +X sees that as straight ahead (+Z in its own frame).
  EXPECT_NEAR(glm::length(control_avatar_direction(in, kPi / 2) - vec2(0, 1)), 0.0f, 1e-6f);
  EXPECT_EQ(control_world_direction(ControlInput{}), vec2(0.0f));
}

TEST(LookaheadAvatar, FollowsASteadyCommandInTheOpen) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  LookaheadAvatar avatar(lib, arena.world, MotionTreeConfig{}, test::idle_segment(lib),
                         Placement{vec2(0, -5), 0.0f});
  ControlInput in;
  in.camera_dir = vec2(0, 1);  // camera yaw 0: walk towards +Z
  const RunStats s = run(avatar, lib, arena.world, in, 10 * 30, 300);
  EXPECT_EQ(s.colliding_frames, 0);
  EXPECT_GT(s.displacement.y, 5.0f);
  EXPECT_LT(std::abs(s.displacement.x), 0.5f * s.displacement.y);
}

TEST(LookaheadAvatar, HoldingCrouchMakesItCrouchWhereverItCan) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  for (bool crouch : {false, true}) {
    for (vec2 dir : {vec2(0, 1), vec2(0, 0)}) {  // walking, and standing still
      LookaheadAvatar avatar(lib, arena.world, MotionTreeConfig{}, test::idle_segment(lib),
                             Placement{vec2(0, -5), 0.0f});
      ControlInput in;
      in.camera_dir = dir;
      in.crouch = crouch;
      run(avatar, lib, arena.world, in, 4 * 30, 300);  // settle into it
      int crouched_frames = 0;
      for (int f = 0; f < 60; ++f) {
        run(avatar, lib, arena.world, in, 1, 300);
        crouched_frames += (lib.graph.segments[static_cast<size_t>(avatar.playback().segment)].tags & kTagCrouch) != 0;
      }
      if (crouch)
        EXPECT_EQ(crouched_frames, 60) << "moving: " << (dir != vec2(0.0f));
      else
        EXPECT_EQ(crouched_frames, 0) << "moving: " << (dir != vec2(0.0f));
    }
  }
}

TEST(LookaheadAvatar, SteeringIntoAWallNeverEntersIt) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  const SpawnPoint& spawn = maze.scene.spawns.front();
  for (Strategy strategy : {Strategy::kBreadthFirst, Strategy::kCommand, Strategy::kCommandNoResort,
                            Strategy::kStatistic, Strategy::kHybrid}) {
    MotionTreeConfig config;
    config.strategy = strategy;
    LookaheadAvatar avatar(lib, maze.world, config, test::idle_segment(lib),
                           {spawn.pos_m, spawn.heading_rad});
    ControlInput into_wall;
    into_wall.camera_dir = vec2(0, 1);
    into_wall.camera_yaw_rad = kPi;  // towards -Z: the outer wall 1.25 m away
    const RunStats s = run(avatar, lib, maze.world, into_wall, 20 * 30, 200);
    EXPECT_EQ(s.colliding_frames, 0) << strategy_name(strategy);
  }
}

// Root steering (MotionTreeConfig::steer_rad_per_s): after a right-angle change of command while
// walking, the steered avatar moves within 30 deg of the new direction sooner than the paper's
// controller, which must wait for the playing step to end.
TEST(LookaheadAvatar, RootSteeringFollowsARightAngleTurnSooner) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  const auto frames_to_follow = [&](float steer_deg_per_s, int walk_frames) {
    MotionTreeConfig config;
    config.steer_rad_per_s = radians(steer_deg_per_s);
    LookaheadAvatar avatar(lib, arena.world, config, test::idle_segment(lib), Placement{vec2(0, -6), 0.0f});
    ControlInput ahead;
    ahead.camera_dir = vec2(0, 1);  // +Z
    run(avatar, lib, arena.world, ahead, walk_frames, 300);
    ControlInput left = ahead;
    left.camera_dir = vec2(-1, 0);  // the camera's left: +X (camera yaw 0)
    vec2 before = avatar.root().pos_m;
    for (int f = 1; f <= 60; ++f) {
      EXPECT_EQ(run(avatar, lib, arena.world, left, 1, 300).colliding_frames, 0);
      const vec2 now = avatar.root().pos_m, v = now - before;
      before = now;
      if (glm::length(v) > 0.2f / 30.0f && v.x > 0.0f && std::abs(std::atan2(v.y, v.x)) < radians(30.0f)) return f;
    }
    return 61;
  };
  int paper = 0, steered = 0;
  for (int walk = 60; walk < 75; walk += 3) {  // the change comes at different points of a step
    paper += frames_to_follow(0.0f, walk);
    steered += frames_to_follow(540.0f, walk);
  }
  std::printf("frames to follow a right angle, 5 changes: paper %d, steered %d\n", paper, steered);
  EXPECT_LT(steered, paper * 3 / 4) << "steered " << steered << " frames in all, the paper's controller " << paper;
}

// Open ground 400 m across with nothing on it: room for a capture's dash to turn anywhere (the
// arena's walls refuse a dash's turns near them, which is the walls', not the steering's, say).
const CollisionWorld& open_field() {
  static const CollisionWorld world = [] {
    Scene scene;
    scene.bounds = GroundRect{vec2(-200.0f), vec2(200.0f)};
    CollisionWorld w;
    std::string error;
    if (!collision_world_build(scene, w, error)) ADD_FAILURE() << error;
    return w;
  }();
  return world;
}

// Steering runs after the frame has advanced; it turns the motion about where the root stood on
// the frame before, so the step of the very frame the key turns already goes the new way. (Turned
// about where the root stands after the step, the step stayed the old way: a frame of latency on
// every response.) Walked along +Z on open ground, then the key turned to +X at different points of
// a step.
void expect_steering_turns_the_step_of_the_frame_the_key_turns(const MotionLibrary& lib) {
  const CollisionWorld& world = open_field();
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  int steered = 0;
  for (int walk = 60; walk < 90; walk += 2) {
    LookaheadAvatar avatar(lib, world, config, find_spawn_segment(lib), Placement{vec2(0, -6), 0.0f});
    ControlInput ahead;
    ahead.camera_dir = vec2(0, 1);  // +Z
    run(avatar, lib, world, ahead, walk - 1, 300);
    const vec2 earlier = avatar.root().pos_m;
    run(avatar, lib, world, ahead, 1, 300);
    const vec2 before = avatar.root().pos_m;
    ControlInput left = ahead;
    left.camera_dir = vec2(-1, 0);  // the camera's left: +X (camera yaw 0)
    avatar.set_input(left);
    avatar.grow(GrowBudget::expansions(300));
    const int segment = avatar.playback().segment;
    const AvatarStepResult r = avatar.step();
    if (!r.steered || avatar.playback().segment != segment) continue;  // a segment's end decides instead
    // The turn a frame may make: the full rate, or less where the clip frames leave less room
    // (the pop budget, SteeringAddsNoPopToAFrameWithRoomForIt: a capture's toe strikes, its
    // dash, which turns 3 deg a frame).
    const Segment& seg = lib.graph.segments[static_cast<size_t>(segment)];
    const int at = seg.first_frame + avatar.playback().frame;
    const float allowed = std::min(config.steer_rad_per_s / 30.0f, lib.steer_limit_at(seg.clip, at));
    ++steered;
    // This frame's step against the frame's before (the stride's sway turns it a degree or two).
    const vec2 step = avatar.root().pos_m - before, last = before - earlier;
    ASSERT_GT(glm::length(last), 0.005f) << "walk " << walk;
    const float turned = wrap_angle(std::atan2(step.x, step.y) - std::atan2(last.x, last.y));  // +X: +90 deg
    EXPECT_GT(turned, 0.5f * allowed) << "walk " << walk << ": this frame's step turned " << degrees(turned)
                                      << " deg; the key turned 90 deg and steering may turn " << degrees(allowed);
  }
  EXPECT_GE(steered, 5);
}

// A turning clip's body faces 15-20 deg ahead of its path: steering that stopped once the body
// faced the key left the path some 30 deg off it for a few more frames. Whenever a moving avatar
// is left unsteered with a key held, the way its root goes over the next frames is within 25 deg
// of the key (kWayOff_rad), wherever in a step the key turns and by however much.
void expect_steering_leaves_the_path_on_the_key(const MotionLibrary& lib) {
  const CollisionWorld& world = open_field();
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  int unsteered = 0, off = 0;
  for (const float key_deg : {45.0f, 90.0f, 135.0f, -45.0f, -90.0f, -135.0f})
    for (int walk = 60; walk < 80; walk += 4) {
      LookaheadAvatar avatar(lib, world, config, find_spawn_segment(lib), Placement{vec2(0, -6), 0.0f});
      ControlInput in;
      in.camera_dir = vec2(0, 1);  // +Z
      run(avatar, lib, world, in, walk, 300);
      const float key = radians(key_deg);
      in.camera_dir = vec2(-std::sin(key), std::cos(key));  // camera yaw 0: the world direction (sin, cos)
      for (int f = 0; f < 30; ++f) {
        avatar.set_input(in);
        avatar.grow(GrowBudget::expansions(300));
        const AvatarStepResult r = avatar.step();
        const Segment& seg = lib.graph.segments[static_cast<size_t>(avatar.playback().segment)];
        if (r.steered || r.segment_changed || !(seg.tags & kTagLocomotion)) continue;
        const vec2 way = avatar.way_ahead();
        if (glm::length(way) < LookaheadAvatar::kSteerAheadMin_m) continue;
        ++unsteered;
        const float error = wrap_angle(key - std::atan2(way.x, way.y));
        if (std::abs(error) >= LookaheadAvatar::kWayOff_rad) {
          ++off;
          ADD_FAILURE() << "key " << key_deg << " deg after " << walk << " frames, frame " << f << ": " << seg.name
                        << " left unsteered going " << degrees(error) << " deg off the key";
        }
      }
    }
  EXPECT_GT(unsteered, 100);
  EXPECT_EQ(off, 0);
}

TEST(LookaheadAvatar, SteeringTurnsTheStepOfTheFrameTheKeyTurns) {
  expect_steering_turns_the_step_of_the_frame_the_key_turns(default_library());
}

TEST(LookaheadAvatar, SteeringLeavesThePathOnTheKeyNotOnlyTheBody) {
  expect_steering_leaves_the_path_on_the_key(default_library());
}

// The same on capture the team did not make: every Bandai locomotion take in inches under a dummy
// root, compiled with no unit hint (its own starts, stops, dashes and derived bends). Checked by
// hand before the pop budget: the first part failed with the old pivot (the step turned 0 deg);
// now the keys there fall in the capture's dash, which the budget turns 3 deg a frame, so the
// built-in test above is the one that guards the pivot. The second part holds on this capture
// with the heading rule alone too (its turns keep their paths under their bodies).
TEST(LookaheadAvatar, OnAForeignCaptureSteeringAnswersOnTheFrameAndKeepsThePathOnTheKey) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  expect_steering_turns_the_step_of_the_frame_the_key_turns(lib);
  expect_steering_leaves_the_path_on_the_key(lib);
}

// A segment going sideways (a side step: its way 45-135 deg off its facing) is steered at a third
// of the rate: aiming its way at the key turns its body as far, and side steps spun round at
// 540 deg/s were most of the built-in library's pops (docs/MOTION_QUALITY.md). A forward walk
// still turns at the full rate. Each locomotion segment with a way (LookaheadAvatar::way_ahead)
// is spawned on open ground with the key 90 deg off that way; its first steered frame's turn is
// compared with 18 deg (6 deg sideways). Returns how many sideways segments were seen.
int expect_sideways_segments_steered_slower(const MotionLibrary& lib) {
  const CollisionWorld& world = open_field();
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  const float full = radians(540.0f) / 30.0f;
  int sideways = 0, forward = 0;
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const Segment& seg = lib.graph.segments[static_cast<size_t>(s)];
    if (!(seg.tags & kTagLocomotion) || seg.num_frames() < 8 || std::abs(lib.clips[seg.clip].fps - 30.0f) > 0.1f) continue;
    LookaheadAvatar avatar(lib, world, config, s, Placement{vec2(0.0f), 0.0f});
    const vec2 way = avatar.way_ahead();
    if (glm::length(way) < 0.05f) continue;
    const float off = std::abs(wrap_angle(std::atan2(way.x, way.y) - avatar.root().heading_rad));
    const bool is_sideways = off > radians(50.0f) && off < radians(130.0f);
    if (!is_sideways && off > radians(20.0f)) continue;  // neither clearly: left to the rule's edges
    const float key = std::atan2(way.x, way.y) + radians(90.0f);
    ControlInput in;
    in.camera_dir = vec2(-std::sin(key), std::cos(key));  // camera yaw 0: the world direction (sin, cos)
    avatar.set_input(in);
    avatar.grow(GrowBudget::expansions(300));
    const float before = avatar.playback().segment_start.heading_rad;
    const AvatarStepResult r = avatar.step();
    if (!r.steered || avatar.playback().segment != s) continue;
    const float turned = std::abs(wrap_angle(avatar.playback().segment_start.heading_rad - before));
    // Where the clip frames leave steering less room than that, the pop budget decides (below).
    const float room = lib.steer_limit_at(seg.clip, seg.first_frame + 1);
    if (room < (is_sideways ? full * LookaheadAvatar::kSidewaysSteerShare : full)) continue;
    if (is_sideways) {
      ++sideways;
      EXPECT_LT(turned, 0.5f * full) << seg.name << " goes " << degrees(off) << " deg off its facing";
      EXPECT_NEAR(turned, full * LookaheadAvatar::kSidewaysSteerShare, 1e-3f) << seg.name;
    } else {
      ++forward;
      EXPECT_NEAR(turned, full, 1e-3f) << seg.name;
    }
  }
  EXPECT_GT(forward, 3);
  return sideways;
}

TEST(LookaheadAvatar, ASideStepIsSteeredSlowerThanAWalk) {
  EXPECT_GE(expect_sideways_segments_steered_slower(default_library()), 2) << "side_step_left, side_step_right";
}

// The Bandai walk in inches under a dummy root (test::make_foreign), its body turned 90 deg on
// its path (a crab walk: it goes sideways), played `slower` times slower (upsampled at the same
// frame rate), beside the walk as captured: a library of both.
void foreign_crab_walk_library(int slower, MotionLibrary& lib) {
  BvhDocument walk;
  std::string error;
  ASSERT_TRUE(bvh_load(test::mocap_dir() / "locomotion" / "bandai_dataset-1_walk_normal_001.bvh", walk, error)) << error;
  BvhDocument crab = walk;
  const int hips = test::joint_named(crab, "Hips");
  ASSERT_GE(hips, 0);
  test::turn_body_on_its_path(crab, hips, 90.0);
  if (slower > 1) {
    const double frame_time_s = crab.frame_time_s;
    test::upsample(crab, slower);
    crab.frame_time_s = frame_time_s;  // more frames at the same rate: slower
  }
  const auto dir = test::scratch_dir();
  for (auto [take, name] : {std::pair{&walk, "walk.bvh"}, std::pair{&crab, "crab_walk.bvh"}}) {
    test::make_foreign(*take);
    ASSERT_TRUE(bvh_save(dir / name, *take, error)) << error;
  }
  MotionSource source;
  source.motions_dir = dir;
  ASSERT_TRUE(motion_library_from_folder(source, lib, nullptr, error)) << error;
}

// The same on capture the team did not make: the Bandai crab walk beside the walk as captured.
TEST(LookaheadAvatar, OnAForeignCaptureASidewaysWalkIsSteeredSlowerThanAWalk) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(foreign_crab_walk_library(1, lib));
  EXPECT_GE(expect_sideways_segments_steered_slower(lib), 1);
}

// A sideways move that sets off slowly (the built-in side step shifts its weight first: 4 cm in
// its first 4 frames) is still a sideways move on those frames (LookaheadAvatar::way_ahead takes
// it to where the segment ends). The same on a capture the team did not make: the Bandai crab
// walk above taken 4 times slower (0.3 m/s; the walk as captured beside it), so that its pieces
// move under 5 cm in their first 4 frames; they are found going sideways and steered at the third
// of the rate.
TEST(LookaheadAvatar, OnASlowForeignSidewaysWalkTheFirstFramesAreSteeredAsSideways) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(foreign_crab_walk_library(4, lib));
  int slow_starts = 0;
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const Segment& seg = lib.graph.segments[static_cast<size_t>(s)];
    if (!(seg.tags & kTagLocomotion) || seg.num_frames() <= LookaheadAvatar::kSteerAheadFrames) continue;
    const vec2 first_frames = motion_library_root_at(lib, s, LookaheadAvatar::kSteerAheadFrames, Placement{}).pos_m -
                              motion_library_root_at(lib, s, 0, Placement{}).pos_m;
    slow_starts += glm::length(first_frames) < LookaheadAvatar::kSteerAheadMin_m;
  }
  EXPECT_GT(slow_starts, 3) << "the slowed take must set off slowly, or the test shows nothing";
  EXPECT_GE(expect_sideways_segments_steered_slower(lib), 3);
}

// Steering turns the playing motion about the root, which adds about 2 x rate x speed to every
// moving joint's acceleration: a dash (4.5 m/s) spun at 540 deg/s gained 95 mm/frame^2, the
// capture's own pop threshold 146. So each frame turns only as fast as its clip frames' own
// accelerations leave room under the threshold (MotionLibrary::steer_limit_rad). Every locomotion
// segment is played on open ground with the key held 90 deg off its way; on every frame whose
// clip frames have a fair share of room (own acceleration under 70 % of the threshold), the
// shown pose's (the pose stage eases the turn's start) largest joint acceleration stays under
// the threshold. Returns the frames checked.
int expect_steering_adds_no_pop(const MotionLibrary& lib) {
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  int checked = 0, steered = 0;
  for (int s = 0; s < lib.graph.num_segments(); ++s) {
    const Segment& seg = lib.graph.segments[static_cast<size_t>(s)];
    if (!(seg.tags & kTagLocomotion) || seg.num_frames() < 4) continue;
    LookaheadAvatar avatar(lib, open_field(), config, s, Placement{vec2(0.0f), 0.0f});
    const vec2 way = avatar.way_ahead();
    const float key = (glm::length(way) > 0.05f ? std::atan2(way.x, way.y) : 0.0f) + radians(90.0f);
    ControlInput in;
    in.camera_dir = vec2(-std::sin(key), std::cos(key));  // camera yaw 0: the world direction (sin, cos)
    PoseStage stage(lib);
    std::vector<std::vector<vec3>> shown_poses;
    std::vector<int> frames;
    for (;;) {
      const std::span<const vec3> shown = stage.update(avatar.playback(), shown_poses.empty() ? 0.0f : 1.0f / 30.0f);
      shown_poses.emplace_back(shown.begin(), shown.end());
      frames.push_back(seg.first_frame + avatar.playback().frame);
      avatar.set_input(in);
      avatar.grow(GrowBudget::expansions(100));
      const AvatarStepResult r = avatar.step();
      if (r.segment_changed || avatar.playback().segment != s) break;
      steered += r.steered;
    }
    for (size_t k = 1; k + 1 < shown_poses.size(); ++k) {
      float own = 0.0f;
      for (size_t i = k - 1; i <= k + 1; ++i) own = std::max(own, lib.frame_acceleration_at(seg.clip, frames[i]));
      if (own > 0.7f * lib.pop_threshold_m) continue;
      const float largest = test::largest_joint_acceleration(shown_poses[k - 1], shown_poses[k], shown_poses[k + 1]);
      EXPECT_LE(largest, lib.pop_threshold_m) << seg.name << " frame " << frames[k] - seg.first_frame << ": own "
                                              << own * 1000.0f << " mm/frame^2";
      ++checked;
    }
  }
  EXPECT_GT(steered, checked / 4) << "the segments must be steered";
  return checked;
}

TEST(LookaheadAvatar, SteeringAddsNoPopToAFrameWithRoomForIt) {
  EXPECT_GT(expect_steering_adds_no_pop(default_library()), 300);
}

// The same on the Bandai capture in inches under a dummy root: its runs and dashes are fast.
TEST(LookaheadAvatar, OnAForeignCaptureSteeringAddsNoPopToAFrameWithRoomForIt) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  EXPECT_GT(expect_steering_adds_no_pop(lib), 300);
}

// A key pressed beside a standing avatar sets it off at once, its start steered round to the key,
// not after a whole turn on the spot (0.57 s for the built-in 90 deg one, 0.8 s for a capture's
// derived one): the lab's maze answered 21 of the 25 presses that came during one in over 250
// ms. On open ground, standing facing +Z, keys 90 and 135 deg to either side and straight back:
// no turn on the spot is played, and the press is answered (ResponseMeter, the lab's measure)
// within 0.6 s. (With the turns on the spot taken first: 733 ms built-in, 1 500 ms on the Bandai
// capture; without, 433 and 467.) Returns the slowest answer, ms.
double expect_a_key_beside_a_stand_sets_off_at_once(const MotionLibrary& lib) {
  const CollisionWorld& world = open_field();
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  double slowest = 0.0;
  for (const float key_deg : {90.0f, -90.0f, 135.0f, -135.0f, 180.0f}) {
    LookaheadAvatar avatar(lib, world, config, find_spawn_segment(lib), Placement{vec2(0.0f), 0.0f});
    const double dt = 1.0 / 30.0;
    ResponseMeter meter(dt);
    const float key = radians(key_deg);
    ControlInput press;
    press.camera_dir = vec2(-std::sin(key), std::cos(key));  // camera yaw 0: the world direction (sin, cos)
    double answered_ms = -1.0;
    for (int f = 0; f < 80 && answered_ms < 0.0; ++f) {  // 20 frames standing, then the key held
      const ControlInput in = f < 20 ? ControlInput{} : press;
      avatar.set_input(in);
      avatar.grow(GrowBudget::expansions(300));
      avatar.step();
      const Segment& seg = lib.graph.segments[static_cast<size_t>(avatar.playback().segment)];
      EXPECT_FALSE((seg.tags & kTagTurn) && !(seg.tags & kTagLocomotion)) << "key " << key_deg << " deg, frame " << f << ": " << seg.name;
      if (meter.frame(f * dt, control_world_direction(in), avatar.root().pos_m, avatar.playback().segment)) answered_ms = meter.last().ms;
    }
    EXPECT_GE(answered_ms, 0.0) << "key " << key_deg << " deg: not answered in 2 s";
    EXPECT_LE(answered_ms, 600.0) << "key " << key_deg << " deg";
    slowest = std::max(slowest, answered_ms);
  }
  return slowest;
}

TEST(LookaheadAvatar, AKeyBesideAStandSetsItOffAtOnce) {
  std::printf("slowest answer: %.0f ms\n", expect_a_key_beside_a_stand_sets_off_at_once(default_library()));
}

TEST(LookaheadAvatar, OnAForeignCaptureAKeyBesideAStandSetsItOffAtOnce) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  std::printf("slowest answer: %.0f ms\n", expect_a_key_beside_a_stand_sets_off_at_once(lib));
}

TEST(LookaheadAvatar, RootSteeringNeverEntersAWall) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  const SpawnPoint& spawn = maze.scene.spawns.front();
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  LookaheadAvatar avatar(lib, maze.world, config, test::idle_segment(lib), {spawn.pos_m, spawn.heading_rad});
  // Commands that keep swinging round, towards walls and along them.
  int colliding = 0;
  for (int k = 0; k < 24; ++k) {
    ControlInput in;
    in.camera_dir = vec2(std::sin(1.7f * static_cast<float>(k)), std::cos(1.7f * static_cast<float>(k)));
    colliding += run(avatar, lib, maze.world, in, 20, 200).colliding_frames;
  }
  EXPECT_EQ(colliding, 0);
}

// Steering mode ends a stop early for a held command once only the weight is left to settle
// (the rest of the stop moves the root under 2 cm); the paper's controller waits for its end.
TEST(LookaheadAvatar, SteeringEndsAStopEarlyForANewCommand) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  // Walk, release the keys until a stop plays and only its settling is left, then press "left":
  // returns how many frames the stop had left and how many it played before the avatar moved on.
  const auto press_during_settling = [&](float steer_deg_per_s, int& left_at_press, int& played) {
    MotionTreeConfig config;
    config.steer_rad_per_s = radians(steer_deg_per_s);
    LookaheadAvatar avatar(lib, arena.world, config, test::idle_segment(lib), Placement{vec2(0, -6), 0.0f});
    ControlInput ahead;
    ahead.camera_dir = vec2(0, 1);
    run(avatar, lib, arena.world, ahead, 45, 300);
    const auto name = [&] { return lib.graph.segments[avatar.playback().segment].name; };
    for (int f = 0; f < 60 && name().find("_stop") == std::string::npos; ++f)
      run(avatar, lib, arena.world, ControlInput{}, 1, 300);
    ASSERT_NE(name().find("_stop"), std::string::npos) << name();
    const int stop = avatar.playback().segment;
    while (avatar.playback().segment == stop &&
           glm::length(playback_next_start(lib, avatar.playback()).pos_m - avatar.root().pos_m) >= 0.02f)
      run(avatar, lib, arena.world, ControlInput{}, 1, 300);
    ASSERT_EQ(avatar.playback().segment, stop) << "the stop ended before its settling";
    left_at_press = lib.graph.segments[stop].num_frames() - avatar.playback().frame;
    ControlInput left = ahead;
    left.camera_dir = vec2(-1, 0);
    for (played = 0; avatar.playback().segment == stop && played < 60; ++played)
      EXPECT_EQ(run(avatar, lib, arena.world, left, 1, 300).colliding_frames, 0);
    EXPECT_FALSE(lib.graph.segments[avatar.playback().segment].tags & kTagIdle) << name();  // it moves
  };
  int left = 0, played = 0;
  press_during_settling(0.0f, left, played);
  EXPECT_EQ(played, left) << "the paper's controller changes motion at the stop's end";
  press_during_settling(540.0f, left, played);
  EXPECT_GE(left, 2);
  EXPECT_LT(played, left) << "the steered avatar moves on before the stop's end";
}

// Ending early is for what goes nowhere: a stand-up stays in place on the ground while the body
// rises 42 cm, so it is not left half way for a held command (its head jumped 22 cm in one shown
// frame, a pop the pose stage could not hide); only its last few cm may be cut.
TEST(LookaheadAvatar, SteeringDoesNotLeaveAStandUpHalfWay) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  const int stand_up = lib.graph.find_segment("stand_up");
  ASSERT_GE(stand_up, 0);
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  LookaheadAvatar avatar(lib, arena.world, config, stand_up, Placement{vec2(0, -6), 0.0f});
  ControlInput ahead;
  ahead.camera_dir = vec2(0, 1);
  const Segment& seg = lib.graph.segments[stand_up];
  const Clip& clip = lib.clips[seg.clip];
  const auto pelvis_y = [&](int frame) { return clip.frame_pos(std::min(seg.first_frame + frame, clip.num_frames - 1))[0].y; };
  ASSERT_GT(pelvis_y(seg.num_frames()) - pelvis_y(0), 0.3f) << "the body rises";
  int last_frame = 0;
  for (int f = 0; f < 60 && avatar.playback().segment == stand_up; ++f) {
    last_frame = avatar.playback().frame;
    run(avatar, lib, arena.world, ahead, 1, 300);
  }
  ASSERT_NE(avatar.playback().segment, stand_up) << "it moves on";
  EXPECT_LT(pelvis_y(seg.num_frames()) - pelvis_y(last_frame), 0.05f)
      << "left at frame " << last_frame << " of " << seg.num_frames();
}

// While a direction is held and the avatar walks, steering mode does not stop where a motion that
// keeps moving is feasible. In the maze's corridors, where the scripted player swings its keys by
// right angles at every corner, the paper's choice stops about five times a run (the tree sees a
// sharp turn as two wide turning steps); the steered avatar walks on. The generator's runs are
// replayed frame by frame from their recordings (a replay reproduces the run exactly). A stop
// counts when the held direction is ahead (within 90 degrees of the facing: reversing is a stop
// and a turn) and open: a body half a shoulder-width wide (0.35 m) clears 1.5 m straight ahead
// that way (stopping with the key pointing into a near wall is the right answer).
TEST(LookaheadAvatar, SteeringKeepsWalkingWhileACommandIsHeld) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  int stops = 0, segments = 0;
  for (uint64_t seed = 1; seed <= (test::kSlowBuild ? 1u : 3u); ++seed) {
    RecordingGeneratorConfig g;
    g.scene = "maze";
    g.name = "steered";
    g.seed = seed;
    g.replay.tree.steer_rad_per_s = radians(540.0f);
    g.replay.max_seconds = 120;
    GeneratedRecording out;
    std::string error;
    ASSERT_TRUE(recording_generate(lib, maze.scene, maze.world, g, out, error)) << error;
    const Recording& rec = out.recording;
    ReplayRun run(lib, maze.world, Placement{rec.start_pos_m, rec.start_heading_rad}, rec.goal_pos_m,
                  rec.goal_radius_m, g.replay);
    ASSERT_TRUE(run.ok()) << run.error();
    int previous = run.avatar().playback().segment;
    while (!run.done()) {
      const ControlInput in = recording_input_at(rec, run.time_s());
      run.frame(in);
      const int segment = run.avatar().playback().segment;
      if (segment == previous) continue;
      ++segments;
      const bool held = glm::length(control_world_direction(in)) > 0.0f;
      const std::string& name = lib.graph.segments[static_cast<size_t>(segment)].name;
      const vec2 at = run.avatar().playback().segment_start.pos_m;
      const vec2 held_dir = control_world_direction(in);
      const float facing = run.avatar().playback().segment_start.heading_rad;
      const bool ahead = held && glm::dot(glm::normalize(held_dir), vec2(std::sin(facing), std::cos(facing))) > 0.0f;
      if (ahead && name.find("_stop") != std::string::npos &&
          scene_segment_clear(maze.world, at, at + 1.5f * glm::normalize(held_dir), 0.35f, kStandingHeight_m)) {
        ++stops;
        ADD_FAILURE() << "seed " << seed << ": " << name << " at " << run.time_s() << " s, heading " << degrees(facing) << " deg, (" << at.x << ", "
                      << at.y << ") while the key held points the open way (" << held_dir.x << ", " << held_dir.y << ")";
      }
      previous = segment;
    }
    EXPECT_TRUE(run.result().reached_goal) << "seed " << seed;
  }
  EXPECT_GT(segments, 50);
  EXPECT_EQ(stops, 0);
}

// A steered avatar never corners itself: the scripted player, which holds keys into corners and
// zigzags through the maze, gets it to the goal without a colliding frame. Two of the runs are
// ones that ended standing in a corner for ever: obstacles seed 77 without the trap rule (a turn
// on the spot into a pocket where only standing fits), maze seed 195 with a rotation that only
// had to leave one segment's way on (a step steered so that only a stop into a corner followed).
// Obstacles seed 1 froze for 100 s on the last frame of slow_to_walk_l once steering also turned
// the path onto the key: both its successors were dead ends (nothing feasible after them, not
// even idle), which find_traps did not count as traps.
TEST(LookaheadAvatar, SteeringReachesTheGoalWithoutCorneringItself) {
  const auto& lib = default_library();
  struct Run {
    const char* scene;
    const char* spawn;
    const char* goal;
    uint64_t seed;
  };
  std::vector<Run> runs = {{"obstacles", "", "", 77}, {"maze", "centre", "dead-end-sw", 195}};
  if (!test::kSlowBuild)
    for (uint64_t seed = 1; seed <= 4; ++seed) runs.push_back({"obstacles", "", "", seed}), runs.push_back({"maze", "", "", seed});
  for (const Run& run : runs) {
    const auto& loaded = loaded_scene(run.scene);
    RecordingGeneratorConfig g;
    g.scene = run.scene;
    g.name = "steered";
    g.spawn = run.spawn;
    g.goal = run.goal;
    g.seed = run.seed;
    g.replay.tree.steer_rad_per_s = radians(540.0f);
    g.replay.max_seconds = 120;
    GeneratedRecording out;
    std::string error;
    ASSERT_TRUE(recording_generate(lib, loaded.scene, loaded.world, g, out, error)) << error;
    EXPECT_TRUE(out.reached_goal) << run.scene << " seed " << run.seed;
    EXPECT_EQ(out.run.colliding_frames, 0) << run.scene << " seed " << run.seed;
  }
}

TEST(LookaheadAvatar, WithNoBudgetItFallsBackToIdleAndNeverMoves) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  const SpawnPoint& spawn = maze.scene.spawns.front();
  LookaheadAvatar avatar(lib, maze.world, MotionTreeConfig{}, test::idle_segment(lib),
                         {spawn.pos_m, spawn.heading_rad});
  ASSERT_GE(avatar.fallback_segment(), 0);
  ControlInput go;
  go.camera_dir = vec2(0, 1);
  const RunStats s = run(avatar, lib, maze.world, go, 10 * 30, 0);
  EXPECT_EQ(s.colliding_frames, 0);
  EXPECT_GT(avatar.fallbacks(), 0);
  EXPECT_LT(glm::length(s.displacement), 0.05f);
  EXPECT_EQ(avatar.playback().segment, avatar.fallback_segment());
}

// A wall 4 m wide (x within 2 m of `x`) and 1 m thick across the Z axis, its face at `face_z` and
// the rest of it beyond, the way `way` (+1 or -1) points.
void add_wall_across_z(Scene& scene, const char* name, float x, float face_z, float way) {
  scene.boxes.push_back({name, BoxKind::kWall, {x - 2.0f, 0.0f, std::min(face_z, face_z + way)},
                         {x + 2.0f, 2.5f, std::max(face_z, face_z + way)}});
}

// A segment can end where not even idle fits (a capture's dash ends a hand's width from a box
// its narrower running body clears). The avatar used to hold that segment's last frame for ever;
// it now stands where idle fits nearest, back along its way. Here a wall's face is put 10 cm
// inside the standing body's reach, the way the segment travels, at its end, with no budget, so
// the segment has no child. The way is the travel's, not the facing's: a walk backwards backs
// into the wall, and searching behind its facing froze it there (a Bandai walk-back, 100 s).
void expect_stands_back_where_idle_does_not_fit(const MotionLibrary& lib, int walk) {
  ASSERT_GE(walk, 0);
  const Placement start{vec2(0.0f), 0.0f};  // facing +Z
  const Placement end = motion_library_root_at(lib, walk, lib.graph.segments[walk].num_frames(), start);
  const int idle = find_fallback_segment(lib);
  ASSERT_GE(idle, 0);
  const vec2 way = glm::normalize(end.pos_m - start.pos_m);
  ASSERT_GT(std::abs(way.y), 0.9f) << "a walk along +-Z";
  const vec2 way_local = rotate_ground(way, -end.heading_rad);  // in the standing body's frame
  float reach = 0.0f;  // the standing body's reach that way from its root
  for (const BodyVolume& v : lib.volumes(idle))
    reach = std::max(reach, glm::dot(v.center_m, way_local) + glm::length(v.half_axis_m) + v.radius_m);
  Scene scene;
  scene.bounds = GroundRect{vec2(-20.0f), vec2(20.0f)};
  const vec2 face = end.pos_m + way * (reach - 0.10f);
  add_wall_across_z(scene, "wall", face.x, face.y, way.y > 0.0f ? 1.0f : -1.0f);
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(collision_world_build(scene, world, error)) << error;
  ASSERT_FALSE(segment_feasible(world, lib.segment_shapes[idle], end)) << "idle must not fit where the walk ends";

  LookaheadAvatar placed(lib, world, MotionTreeConfig{}, walk, start);
  PoseCheckScratch scratch;
  int standing_frames = 0, colliding = 0;
  for (int f = 0; f < 3 * 30; ++f) {
    placed.step();
    if (placed.playback().segment != idle) continue;
    ++standing_frames;
    colliding += shown_pose_collides(lib, world, placed.playback(), scratch);
  }
  EXPECT_GT(standing_frames, 2 * 30) << "held segment " << lib.graph.segments[placed.playback().segment].name;
  EXPECT_EQ(colliding, 0);
  const vec2 moved = placed.root().pos_m - end.pos_m;
  EXPECT_LT(glm::length(moved), LookaheadAvatar::kStandSearch_m + 0.01f);
  EXPECT_LT(glm::dot(moved, way), 0.0f) << "it stands back along its way";
  EXPECT_NEAR(wrap_angle(placed.root().heading_rad - end.heading_rad), 0.0f, 0.01f);
}

TEST(LookaheadAvatar, WhereIdleDoesNotFitAtTheEndItStandsBackNotFrozenInTheLastPose) {
  const MotionLibrary& lib = default_library();
  expect_stands_back_where_idle_does_not_fit(lib, lib.graph.find_segment("walk_l"));
}

// The same on the Bandai capture in inches under a dummy root, whose idle is derived from it.
TEST(LookaheadAvatar, OnAForeignCaptureWhereIdleDoesNotFitItStandsBack) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  expect_stands_back_where_idle_does_not_fit(lib, walking_segment(lib));
}

// After a fallback the avatar is not turned (on the spot or steered) until the jump to its stand
// has been shown (the pose stage carries it over 0.2 s): turned at once, the offset that still
// shows the body where the walk ended swings with the turn (the pillar field: a toe into the
// pillar that ended the walk, cut back out in one frame, 179 mm/frame^2; the Bandai capture
// below: a backward walk's start steered on its first frame, 157 against its threshold of 146).
// A walk ends at the end of a dead end as narrow as its body, where nothing after it fits; the key
// then points back: the built-in stand turns on the spot, the capture's walks back; either only
// after 0.2 s, and nothing shown pops or enters a wall.
void expect_nothing_turns_after_a_fallback_until_its_jump_is_shown(const MotionLibrary& lib, int walk) {
  ASSERT_GE(walk, 0);
  const Placement start{vec2(0.0f), 0.0f};  // facing +Z
  const Placement end = motion_library_root_at(lib, walk, lib.graph.segments[walk].num_frames(), start);
  ASSERT_GT(std::abs(glm::normalize(end.pos_m - start.pos_m).y), 0.9f) << "a walk along +-Z";
  const float way = end.pos_m.y > 0.0f ? 1.0f : -1.0f;  // +Z or -Z (a backward walk)
  float ahead = -1e9f, side = 0.0f;  // how far the walk's body reaches along its way and sideways
  for (const BodyVolume& v : lib.volumes(walk)) {
    const float extent = glm::length(v.half_axis_m) + v.radius_m;
    ahead = std::max(ahead, way * v.center_m.y + extent);
    side = std::max(side, std::abs(v.center_m.x) + extent);
  }
  const float face = way * (ahead + 0.01f), half_width = side + 0.02f;
  Scene scene;
  scene.bounds = GroundRect{vec2(-20.0f), vec2(20.0f)};
  add_wall_across_z(scene, "end", 0.0f, face, way);
  const float z0 = std::min(face, 0.0f) - 3.0f, z1 = std::max(face, 0.0f) + 3.0f;
  scene.boxes.push_back({"left", BoxKind::kWall, {-2.5f, 0.0f, z0}, {-half_width, 2.5f, z1}});
  scene.boxes.push_back({"right", BoxKind::kWall, {half_width, 0.0f, z0}, {2.5f, 2.5f, z1}});
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(collision_world_build(scene, world, error)) << error;
  ASSERT_TRUE(segment_feasible(world, lib.segment_shapes[walk], start)) << "the walk fits the corridor";

  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  LookaheadAvatar avatar(lib, world, config, walk, start);
  PoseStage stage(lib, PoseStageConfig{});
  stage.set_obstacles(&world);
  ControlInput back;  // back the way it came (camera yaw 0: camera forward is the world's +Z)
  back.camera_dir = vec2(0.0f, -way);
  const float fps = lib.clips[lib.graph.segments[walk].clip].fps;
  int fallback_frame = -1, first_turned = -1, shown_colliding = 0;
  float largest_acceleration = 0.0f;
  std::vector<vec3> before, now, after;
  for (int f = 0; f < 120 && (first_turned < 0 || f < first_turned + 15); ++f) {
    avatar.set_input(fallback_frame >= 0 ? back : ControlInput{});
    avatar.grow(GrowBudget::expansions(300));
    const AvatarStepResult step = avatar.step();
    if (step.fallback && fallback_frame < 0) fallback_frame = f;
    if (fallback_frame >= 0 && f > fallback_frame && first_turned < 0 && step.steered) first_turned = f;
    const std::span<const vec3> shown = stage.update(avatar.playback(), f == 0 ? 0.0f : 1.0f / fps);
    shown_colliding += shown_joints_collide(lib, world, shown);
    before.swap(now), now.swap(after), after.assign(shown.begin(), shown.end());
    if (f >= 2) largest_acceleration = std::max(largest_acceleration, test::largest_joint_acceleration(before, now, after));
  }
  ASSERT_GE(fallback_frame, 0) << "the walk must end in a fallback";
  ASSERT_GE(first_turned, 0) << "it is turned to the key";
  std::printf("fallback at frame %d, first turned %d frames later; largest shown acceleration "
              "%.1f mm/frame^2 (pop threshold %.1f)\n", fallback_frame, first_turned - fallback_frame,
              1000.0f * largest_acceleration, 1000.0f * lib.pop_threshold_m);
  const int settle = static_cast<int>(std::lround(LookaheadAvatar::kFallbackSettle_s * fps));
  EXPECT_GE(first_turned - fallback_frame, settle);
  EXPECT_LE(first_turned - fallback_frame, settle + 4) << "and then it turns";
  EXPECT_LT(largest_acceleration, lib.pop_threshold_m) << "what is shown does not pop";
  EXPECT_EQ(shown_colliding, 0);
}

TEST(LookaheadAvatar, AfterAFallbackNothingTurnsUntilItsJumpIsShown) {
  const MotionLibrary& lib = default_library();
  expect_nothing_turns_after_a_fallback_until_its_jump_is_shown(lib, lib.graph.find_segment("walk_l"));
}

TEST(LookaheadAvatar, OnAForeignCaptureAfterAFallbackNothingTurnsUntilItsJumpIsShown) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  expect_nothing_turns_after_a_fallback_until_its_jump_is_shown(lib, walking_segment(lib));
}

// Steering ends a segment early (for a held command) only where what is left of it goes nowhere:
// the pose shown then is the segment's end pose in place of the frame it would have shown, so
// no joint of that frame may be more than the 2 cm the root may be from its end. A slow walk's
// last frame moved the root under 2 cm while its swinging toe moved 5-9 cm: the frame was
// skipped and the toe popped (the Bandai capture's pillar field, 1.5 pops a minute). Keys turn
// and are released in turn (stops that settle, starts, walks) in the open arena; every early end
// is checked on the played pose (before the pose stage), on both libraries.
void expect_early_ends_skip_no_limb(const MotionLibrary& lib) {
  const auto& arena = loaded_scene("arena");
  MotionTreeConfig config;
  config.steer_rad_per_s = radians(540.0f);
  LookaheadAvatar avatar(lib, arena.world, config, test::idle_segment(lib), Placement{vec2(0, 0), 0.0f});
  const size_t n = static_cast<size_t>(lib.num_joints());
  Pose pose;
  pose.resize(lib.num_joints());
  std::vector<vec3> replaced(n), shown(n);
  std::vector<quat> rot(n);
  const auto positions = [&](const PlaybackState& state, std::vector<vec3>& out) {
    playback_pose(lib, state, pose);
    fk_pose(lib.skeleton, pose.local_pos_m, pose.local_rot, out, rot);
  };
  int early_ends = 0;
  float largest_skip_m = 0.0f;
  for (int k = 0; k < 48; ++k) {
    // Round the compass by 135 deg a time, from wherever the avatar is towards the middle.
    ControlInput in;
    const float a = radians(135.0f * static_cast<float>(k));
    in.camera_dir = vec2(std::sin(a), std::cos(a));
    if (glm::length(avatar.root().pos_m) > 5.0f) in.camera_dir = glm::normalize(-avatar.root().pos_m) * vec2(-1, 1);
    for (int f = 0; f < 40; ++f) {
      const bool held = f < 25 || k % 3 == 0;  // a stop now and then, pressed again while it settles
      const PlaybackState before = avatar.playback();
      const int fallbacks = avatar.fallbacks();
      run(avatar, lib, arena.world, held ? in : ControlInput{}, 1, 300);
      const PlaybackState& now = avatar.playback();
      // A fallback jumps (the pose stage inertializes it): not an early end.
      if (now.segment == before.segment || avatar.fallbacks() != fallbacks ||
          before.frame + 1 >= lib.graph.segments[static_cast<size_t>(before.segment)].num_frames())
        continue;
      ++early_ends;
      PlaybackState instead = before;
      ++instead.frame;
      positions(instead, replaced);
      positions(now, shown);
      for (size_t j = 0; j < n; ++j) largest_skip_m = std::max(largest_skip_m, glm::length(shown[j] - replaced[j]));
    }
  }
  EXPECT_GT(early_ends, 5) << "the run never ended a segment early: nothing was tested";
  EXPECT_LT(largest_skip_m, 0.025f) << early_ends << " early ends";
}

TEST(LookaheadAvatar, AnEarlyEndSkipsNoLimbMotion) {
  expect_early_ends_skip_no_limb(default_library());
}

// The same on the Bandai capture in inches under a dummy root, whose slow walks skipped toes.
TEST(LookaheadAvatar, OnAForeignCaptureAnEarlyEndSkipsNoLimbMotion) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  expect_early_ends_skip_no_limb(lib);
}

// A backward walk of the Bandai capture (inches, dummy root): it backs into the wall.
TEST(LookaheadAvatar, OnAForeignCaptureABackwardWalkStandsBackTheWayItCame) {
  FORESIGHT_REQUIRE_MOCAP();
  MotionLibrary lib;
  ASSERT_NO_FATAL_FAILURE(test::foreign_locomotion_library(lib));
  int backward = -1;
  for (int s = 0; s < lib.graph.num_segments() && backward < 0; ++s) {
    const Segment& seg = lib.graph.segments[static_cast<size_t>(s)];
    const Placement end = motion_library_root_at(lib, s, seg.num_frames(), Placement{});
    if (seg.name.find("walk-back_normal") != std::string::npos && seg.name.find("derived") == std::string::npos &&
        end.pos_m.y < -0.3f && std::abs(end.pos_m.x) < 0.1f)
      backward = s;
  }
  expect_stands_back_where_idle_does_not_fit(lib, backward);
}

TEST(LookaheadAvatar, BrokenInputIsRefusedCountedAndMeansStop) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  LookaheadAvatar avatar(lib, arena.world, MotionTreeConfig{}, test::idle_segment(lib), Placement{});
  ControlInput bad;
  bad.camera_dir = vec2(std::numeric_limits<float>::quiet_NaN(), 1.0f);
  avatar.set_input(bad);
  bad.camera_dir = vec2(3.0f, 0.0f);  // longer than a unit vector
  avatar.set_input(bad);
  bad.camera_dir = vec2(0.0f, 1.0f);
  bad.camera_yaw_rad = std::numeric_limits<float>::infinity();
  avatar.set_input(bad);
  EXPECT_EQ(avatar.rejected_inputs(), 3);
  EXPECT_EQ(avatar.input().camera_dir, vec2(0.0f));
}

}  // namespace
}  // namespace foresight
