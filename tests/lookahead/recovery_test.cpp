// Steering mode never stays wedged (issue 17, item 2): a standing avatar turns on the spot to a
// heading it can move on from, a wedged one backs off and tries again, a crouching one falls
// back to crouching, and a key held into a dead end is left alone. The scripted player plans its
// route again when it has lost sight of it. docs/LOOKAHEAD.md "Recovering".
#include "library/pose_check.hpp"
#include "lookahead/lookahead_avatar.hpp"
#include "scripted/recording_generator.hpp"
#include "scripted/replay.hpp"
#include "lookahead/scene_path.hpp"
#include "scripted/scripted_player.hpp"
#include "lookahead_fixture.hpp"
#include "world/collision_check.hpp"

#include <gtest/gtest.h>

namespace foresight {
namespace {

using test::default_library;
using test::loaded_scene;

constexpr float kLabSteer_rad_per_s = 9.4247780f;  // 540 deg/s, the lab's responsive controller

MotionTreeConfig steering() {
  MotionTreeConfig c;
  c.steer_rad_per_s = kLabSteer_rad_per_s;
  return c;
}

/// A key held so that the world direction is `world_dir` (camera yaw 0: camera "right" is -X).
ControlInput holding(vec2 world_dir) {
  ControlInput in;
  in.camera_dir = glm::normalize(vec2(-world_dir.x, world_dir.y));
  return in;
}

struct Held {
  int colliding_frames = 0;
  float furthest_z = -1e9f;
  int steered_standing = 0;  ///< Frames a standing loop was turned on the spot.
};

Held hold(LookaheadAvatar& avatar, const MotionLibrary& lib, const CollisionWorld& world, const ControlInput& in,
          int frames) {
  Held h;
  PoseCheckScratch scratch;
  for (int f = 0; f < frames; ++f) {
    avatar.set_input(in);
    avatar.grow(GrowBudget::expansions(200));
    const bool standing = (lib.graph.segments[avatar.playback().segment].tags & kTagIdle) != 0;
    const AvatarStepResult r = avatar.step();
    h.steered_standing += r.steered && standing;
    h.colliding_frames += shown_pose_collides(lib, world, avatar.playback(), scratch);
    h.furthest_z = std::max(h.furthest_z, avatar.root().pos_m.y);
  }
  return h;
}

// Where the responsive controller used to stand for the rest of the run (docs/LAB.md, beams seed
// 5): in the 1.0 m corridor's mouth, 14 cm off its centre line, 0.45 m before the first beam,
// facing 11 deg into the west wall with that key held. Nothing forward fits there: neither a
// crouch (too close to the beam) nor a crouch-walk (facing the wall), but the corridor has room
// for the body: it backs off to come in again.
TEST(Recovery, WedgedWithRoomAheadItBacksOff) {
  const auto& lib = default_library();
  const auto& beams = loaded_scene("beams");
  const Placement wedged{vec2(2.86f, 4.90f), radians(-11.0f)};
  const int idle = find_fallback_segment(lib);
  ASSERT_TRUE(segment_feasible(beams.world, lib.segment_shapes[idle], wedged));
  for (const Transition& t : lib.graph.successors(idle)) {
    if (lib.graph.segments[t.to].tags & kTagCrouch) {
      EXPECT_FALSE(segment_feasible(beams.world, lib.segment_shapes[t.to], wedged))
          << lib.graph.segments[t.to].name << " fits: the test no longer starts wedged";
    }
  }
  LookaheadAvatar avatar(lib, beams.world, steering(), idle, wedged);
  const ControlInput key = holding(vec2(-0.2f, 0.98f));
  Held h = hold(avatar, lib, beams.world, key, 2 * 30);
  EXPECT_EQ(avatar.recoveries(), 1) << "wedged for 1.5 s: one recovery";
  h = hold(avatar, lib, beams.world, key, 3 * 30);
  EXPECT_GT(glm::length(avatar.root().pos_m - wedged.pos_m), LookaheadAvatar::kBackOff_m - 0.1f);
  EXPECT_EQ(h.colliding_frames, 0);
}

// Standing with nothing else to do (no budget: the tree never grows), the avatar turns on the
// spot to face the key, at 180 deg/s, and stops there.
TEST(Recovery, StandingItTurnsOnTheSpotToFaceTheKey) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  const Placement start{vec2(0.0f, -5.0f), 0.0f};
  LookaheadAvatar avatar(lib, arena.world, steering(), find_fallback_segment(lib), start);
  int steered = 0;
  const ControlInput key = holding(vec2(std::sin(radians(30.0f)), std::cos(radians(30.0f))));
  for (int f = 0; f < 30; ++f) {
    avatar.set_input(key);
    avatar.grow(GrowBudget::expansions(0));
    steered += avatar.step().steered;
  }
  EXPECT_NEAR(degrees(avatar.root().heading_rad), 30.0f, 1.5f);
  EXPECT_LT(glm::length(avatar.root().pos_m - start.pos_m), 0.01f) << "on the spot";
  EXPECT_GE(steered, 5) << "30 deg at 180 deg/s is 5 frames or more";
  EXPECT_LE(steered, 7) << "and then it stops turning";
}

// A key held into the maze's outer wall (1 m behind the spawn) is the player's choice: no
// recovery, the avatar stays where it is.
TEST(Recovery, AKeyHeldIntoADeadEndIsThePlayersChoice) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  const SpawnPoint& spawn = maze.scene.spawns.front();
  ReplayConfig config;
  config.tree = steering();
  config.max_seconds = 20;
  config.stop_at_goal = false;
  ReplayRun run(lib, maze.world, Placement{spawn.pos_m, spawn.heading_rad}, vec2(100.0f), 0.5f, config);
  ASSERT_TRUE(run.ok()) << run.error();
  ControlInput in;
  in.camera_dir = vec2(0.0f, -1.0f);
  in.camera_yaw_rad = spawn.heading_rad;  // backwards from the spawn: the wall
  while (!run.done()) run.frame(in);
  const ReplayResult r = run.finish();
  EXPECT_EQ(r.recoveries, 0);
  EXPECT_GE(r.stalls, 3) << "held against the wall for most of 20 s";
  EXPECT_LT(glm::length(r.path.back() - spawn.pos_m), 1.0f);
  EXPECT_EQ(r.colliding_frames, 0);
}

// A crouching avatar with nothing feasible ahead (no budget: the tree never grows) falls back to
// crouching, not to the standing idle (a pop, and standing up under a beam).
TEST(Recovery, ACrouchingAvatarFallsBackToCrouching) {
  const auto& lib = default_library();
  const auto& arena = loaded_scene("arena");
  const int crouch_idle = find_fallback_segment(lib, true);
  ASSERT_GE(crouch_idle, 0);
  EXPECT_TRUE(lib.graph.segments[crouch_idle].tags & kTagCrouch);
  int crouch_walk = -1;
  for (int s = 0; s < lib.graph.num_segments() && crouch_walk < 0; ++s) {
    const uint32_t tags = lib.graph.segments[s].tags;
    if ((tags & kTagCrouch) && (tags & kTagLocomotion) && !(tags & kTagIdle)) crouch_walk = s;
  }
  ASSERT_GE(crouch_walk, 0);
  LookaheadAvatar avatar(lib, arena.world, MotionTreeConfig{}, crouch_walk, Placement{vec2(0, -5), 0.0f});
  ControlInput go;
  go.camera_dir = vec2(0, 1);
  for (int f = 0; f < 2 * lib.graph.segments[crouch_walk].num_frames(); ++f) {
    avatar.set_input(go);
    avatar.grow(GrowBudget::expansions(0));
    avatar.step();
  }
  EXPECT_GT(avatar.fallbacks(), 0);
  EXPECT_EQ(avatar.playback().segment, crouch_idle) << lib.graph.segments[avatar.playback().segment].name;
}

// Closed loop, the scripted player from the spawn to the goal. In the beam corridor the
// responsive controller missed 6 of 20 runs before (seeds 5 and 8 among the first ten: wedged at
// the corridor's mouth, docs/LAB.md) and took up to 240 s; in the pillar field it missed 8 of 20
// (seeds 1 and 8). Each reaches the goal now, without a colliding frame.
TEST(Recovery, TheResponsiveControllerReachesTheGoalsItMissedWhenWedged) {
  const auto& lib = default_library();
  struct Runs {
    const char* scene;
    int seeds;
    double max_seconds;
  };
  const int beam_seeds = test::kSlowBuild ? 3 : 10;
  for (const Runs runs : {Runs{"beams", beam_seeds, 60}, Runs{"pillars", test::kSlowBuild ? 1 : 3, 240}}) {
    const auto& s = loaded_scene(runs.scene);
    for (int seed = 1; seed <= runs.seeds; ++seed) {
      RecordingGeneratorConfig g;
      g.scene = runs.scene;
      g.seed = static_cast<uint64_t>(seed);
      g.replay.tree = steering();
      g.replay.max_seconds = runs.max_seconds;
      GeneratedRecording out;
      std::string error;
      ASSERT_TRUE(recording_generate(lib, s.scene, s.world, g, out, error)) << error;
      EXPECT_TRUE(out.reached_goal) << runs.scene << " seed " << seed;
      EXPECT_EQ(out.run.colliding_frames, 0) << runs.scene << " seed " << seed;
    }
  }
}

// The player finds its route behind a wall (the avatar went round another way): after
// kReplanAfter_s it plans again from where the avatar is.
TEST(ScriptedPlayerReplan, ALostPlayerPlansTheRouteAgainFromWhereTheAvatarIs) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  const SpawnPoint& spawn = maze.scene.spawns.front();
  ScriptedPlayer player;
  ScriptedPlayerConfig c;
  std::string error;
  ASSERT_TRUE(player.plan(lib, maze.scene, maze.world, {spawn.pos_m, spawn.heading_rad},
                          maze.scene.goals.front().pos_m, c, error))
      << error;
  // A free point of the maze from which no point of the first legs is in sight.
  const std::vector<vec2> first = player.route();
  vec2 lost{0.0f};
  bool found = false;
  for (float x = 1.25f; x < 20.0f && !found; x += 0.5f)
    for (float z = 1.25f; z < 20.0f && !found; z += 0.5f) {
      const vec2 p(x, z);
      if (!scene_segment_clear(maze.world, p, p, 0.35f, kStandingHeight_m)) continue;
      bool sees = false;
      for (size_t i = 0; i + 1 < first.size() && i < 3 && !sees; ++i)
        for (float u = 0.0f; u <= 1.0f && !sees; u += 0.05f)
          sees = scene_segment_clear(maze.world, p, first[i] + u * (first[i + 1] - first[i]), c.sight_clearance_m,
                                     player.route_body_height_m());
      if (!sees) lost = p, found = true;
    }
  ASSERT_TRUE(found);
  double t = 0.0;
  for (int f = 0; f < 30; ++f, t += c.frame_interval_s) player.frame(t, spawn.pos_m);
  EXPECT_EQ(player.replans(), 0);
  for (int f = 0; f < static_cast<int>(ScriptedPlayer::kReplanAfter_s * 30) + 2; ++f, t += c.frame_interval_s)
    player.frame(t, lost);
  EXPECT_EQ(player.replans(), 1);
  ASSERT_GE(player.route().size(), 2u);
  EXPECT_EQ(player.route().front(), lost);
  EXPECT_EQ(player.route().back(), first.back());
}

}  // namespace
}  // namespace foresight
