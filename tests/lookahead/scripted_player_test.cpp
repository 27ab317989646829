// The scripted player on its own (what a bot sees: positions in, keys out): planning and its
// errors, the first key after the reaction delay, stopping at the goal, the wiggle when the avatar
// is stuck, and that the recording generator built on it still makes the shipped recordings.
#include "scripted/recording.hpp"
#include "scripted/recording_generator.hpp"
#include "lookahead/scene_path.hpp"
#include "scripted/scripted_player.hpp"
#include "lookahead_fixture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace foresight {
namespace {

using test::default_library;
using test::loaded_scene;

constexpr double kDt = 1.0 / 30.0;

float angle_deg(vec2 a, vec2 b) {
  return degrees(std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)));
}

Placement maze_spawn() {
  const SpawnPoint& s = loaded_scene("maze").scene.spawns[0];
  return {s.pos_m, s.heading_rad};
}

vec2 maze_goal() { return loaded_scene("maze").scene.goals[0].pos_m; }

ScriptedPlayer planned_in_maze(const ScriptedPlayerConfig& config) {
  const auto& maze = loaded_scene("maze");
  ScriptedPlayer player;
  std::string error;
  EXPECT_TRUE(player.plan(default_library(), maze.scene, maze.world, maze_spawn(), maze_goal(),
                          config, error))
      << error;
  return player;
}

TEST(ScriptedPlayer, PlansFromTheSpawnToTheGoal) {
  ScriptedPlayerConfig config;
  const ScriptedPlayer player = planned_in_maze(config);
  ASSERT_TRUE(player.planned());
  ASSERT_GE(player.route().size(), 3u);  // the maze has corners
  EXPECT_EQ(player.route().front(), maze_spawn().pos_m);
  EXPECT_EQ(player.route().back(), maze_goal());
  EXPECT_EQ(player.route_length_m(), route_length_m(player.route()));
  EXPECT_GT(player.route_length_m(), 40.0f);
  EXPECT_EQ(player.route_body_height_m(), lowest_moving_body_m(default_library()));
}

TEST(ScriptedPlayer, FirstKeyFollowsTheFirstLegAfterTheReactionDelay) {
  const auto& maze = loaded_scene("maze");
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE(seed);
    ScriptedPlayerConfig config;
    config.seed = seed;
    ScriptedPlayer player = planned_in_maze(config);
    const vec2 leg = player.route()[1] - player.route()[0];
    const HumanModel& h = config.human;
    double first_key_t = -1;
    ControlInput first;
    for (int k = 0; k * kDt <= 1.0 && first_key_t < 0; ++k) {
      const double t = k * kDt;
      const ControlInput in = player.frame(t, maze_spawn().pos_m);  // the avatar stays at the spawn
      // The camera whose region covers the spawn.
      EXPECT_EQ(player.camera_pos_m(), maze.scene.cameras[0].position_m);
      if (in.camera_dir != vec2(0.0f)) first_key_t = t, first = in;
    }
    ASSERT_GE(first_key_t, 0.0) << "no key within 1 s";
    EXPECT_GE(first_key_t, h.reaction_min_s);
    EXPECT_LE(first_key_t, h.reaction_max_s + kDt);
    EXPECT_TRUE(control_input_valid(first));
    EXPECT_NEAR(glm::length(first.camera_dir), 1.0f, 1e-6f);  // an arrow key, not a stick
    EXPECT_FALSE(first.crouch);
    EXPECT_LE(angle_deg(control_world_direction(first), leg), 45.0f);
  }
}

TEST(ScriptedPlayer, ReleasesTheKeysAtTheGoal) {
  ScriptedPlayerConfig config;
  ScriptedPlayer player = planned_in_maze(config);
  const std::vector<vec2> route = player.route();
  // The avatar walks the route at 1.2 m/s (the player tracks it leg by leg), then stands at the
  // goal; any hesitation, tap or wiggle under way has ended 3 s later.
  double t = 0;
  bool pressed_on_the_way = false;
  for (size_t i = 0; i + 1 < route.size(); ++i) {
    const float len = glm::length(route[i + 1] - route[i]);
    const int steps = std::max(1, static_cast<int>(std::ceil(len / (1.2f * kDt))));
    for (int s = 0; s < steps; ++s, t += kDt) {
      const float f = static_cast<float>(s) / static_cast<float>(steps);
      const vec2 pos = route[i] + (route[i + 1] - route[i]) * f;
      pressed_on_the_way |= player.frame(t, pos).camera_dir != vec2(0.0f);
    }
  }
  EXPECT_TRUE(pressed_on_the_way);
  for (const double until = t + 3.0; t < until; t += kDt) player.frame(t, maze_goal());
  for (int k = 0; k < 30; ++k, t += kDt) {
    const ControlInput in = player.frame(t, maze_goal());
    EXPECT_EQ(in.camera_dir, vec2(0.0f)) << "t = " << t;
    EXPECT_TRUE(control_input_valid(in));
  }
}

TEST(ScriptedPlayer, WigglesWhenTheAvatarMakesNoProgress) {
  ScriptedPlayerConfig config;
  config.human.hesitations_per_min = 0;  // only the wiggle moves the keys off the route
  config.human.wrong_taps_per_min = 0;
  ScriptedPlayer player = planned_in_maze(config);
  const vec2 leg = player.route()[1] - player.route()[0];
  double pressed_t = -1, wiggle_t = -1, wiggle_end_t = -1;
  for (int k = 0; k * kDt < 10.0 && wiggle_end_t < 0; ++k) {
    const double t = k * kDt;
    const vec2 dir = control_world_direction(player.frame(t, maze_spawn().pos_m));
    if (dir == vec2(0.0f)) continue;
    const float off = angle_deg(dir, leg);
    if (pressed_t < 0) pressed_t = t;
    if (wiggle_t < 0 && off > 22.5f + 1.0f) {
      wiggle_t = t;
      EXPECT_TRUE(std::abs(off - 45.0f) < 1.0f || std::abs(off - 90.0f) < 1.0f) << off;
    }
    if (wiggle_t >= 0 && off < 22.5f) wiggle_end_t = t;
  }
  ASSERT_GE(pressed_t, 0.0);
  ASSERT_GE(wiggle_t, 0.0) << "no wiggle in 10 s at a standstill";
  // Not moved 0.3 m for stuck_after_s while pressing: the first frame past that.
  EXPECT_GE(wiggle_t, pressed_t + config.human.stuck_after_s - 1e-9);
  EXPECT_LE(wiggle_t, pressed_t + config.human.stuck_after_s + kDt + 1e-9);
  // Back on the wanted key after wiggle_s (and the reaction delay).
  ASSERT_GE(wiggle_end_t, 0.0);
  EXPECT_GE(wiggle_end_t, wiggle_t + config.human.wiggle_s - 1e-9);
  EXPECT_LE(wiggle_end_t, wiggle_t + config.human.wiggle_s + config.human.reaction_max_s + 2 * kDt);
}

TEST(ScriptedPlayer, RefusesUnreachableGoalsAndNonFiniteArguments) {
  const auto& maze = loaded_scene("maze");
  const auto& lib = default_library();
  ScriptedPlayer player;
  std::string error;
  // (2.5, 2.5) is inside the wall between the first two rows of cells.
  EXPECT_FALSE(player.plan(lib, maze.scene, maze.world, maze_spawn(), vec2(2.5f, 2.5f), {}, error));
  EXPECT_FALSE(player.planned());
  EXPECT_TRUE(player.route().empty());
  EXPECT_NE(error.find("no route: the goal (2.50, 2.50) is not free"), std::string::npos) << error;
  const Placement in_wall{vec2(2.5f, 2.5f), 0.0f};
  EXPECT_FALSE(player.plan(lib, maze.scene, maze.world, in_wall, maze_goal(), {}, error));
  EXPECT_NE(error.find("no route: the start (2.50, 2.50) is not free"), std::string::npos) << error;
  // No corridor is 3 m wide: the route is planned for the library's own walker instead.
  ScriptedPlayerConfig wide;
  wide.route_clearance_m = 1.5f;
  ASSERT_TRUE(player.plan(lib, maze.scene, maze.world, maze_spawn(), maze_goal(), wide, error)) << error;
  EXPECT_FLOAT_EQ(player.route_clearance_used_m(), moving_body_clearance_m(lib));
  EXPECT_LT(moving_body_clearance_m(lib), 0.4f) << "a walker fits a 0.8 m gap";
  // Two rooms joined by a 0.5 m slit, narrower than any walker: no route, and it says why.
  Scene slit;
  slit.name = "slit";
  slit.bounds = {{0.0f, 0.0f}, {6.0f, 6.0f}};
  slit.boxes.push_back({"left", BoxKind::kWall, {0.0f, 0.0f, 2.9f}, {2.75f, 2.5f, 3.1f}});
  slit.boxes.push_back({"right", BoxKind::kWall, {3.25f, 0.0f, 2.9f}, {6.0f, 2.5f, 3.1f}});
  slit.spawns.push_back({"start", {3.0f, 1.0f}, 0.0f});
  CollisionWorld slit_world;
  ASSERT_TRUE(collision_world_build(slit, slit_world, error)) << error;
  EXPECT_FALSE(player.plan(lib, slit, slit_world, Placement{vec2(3.0f, 1.0f), 0.0f}, vec2(3.0f, 5.0f), {}, error));
  EXPECT_NE(error.find("no route from (3.00, 1.00) to (3.00, 5.00) for a body of radius"), std::string::npos) << error;
  EXPECT_NE(error.find("the library's walkers are"), std::string::npos) << error;

  const Placement nan_start{vec2(NAN, 1.25f), 0.0f};
  EXPECT_FALSE(player.plan(lib, maze.scene, maze.world, nan_start, maze_goal(), {}, error));
  EXPECT_NE(error.find("must be finite"), std::string::npos) << error;
  EXPECT_FALSE(player.plan(lib, maze.scene, maze.world, maze_spawn(), vec2(18.75f, INFINITY), {}, error));
  EXPECT_NE(error.find("must be finite"), std::string::npos) << error;
  ScriptedPlayerConfig bad;
  bad.frame_interval_s = 0;
  EXPECT_FALSE(player.plan(lib, maze.scene, maze.world, maze_spawn(), maze_goal(), bad, error));
  EXPECT_NE(error.find("frame_interval_s"), std::string::npos) << error;
  bad = {};
  bad.human.stuck_after_s = NAN;
  EXPECT_FALSE(player.plan(lib, maze.scene, maze.world, maze_spawn(), maze_goal(), bad, error));
  EXPECT_NE(error.find("stuck_after_s"), std::string::npos) << error;

  // Unplanned, or fed a position it cannot use: keys up.
  EXPECT_EQ(player.frame(0.0, maze_spawn().pos_m).camera_dir, vec2(0.0f));
  ASSERT_TRUE(player.plan(lib, maze.scene, maze.world, maze_spawn(), maze_goal(), {}, error)) << error;
  EXPECT_EQ(player.frame(0.0, vec2(NAN, 0.0f)).camera_dir, vec2(0.0f));
}

// A fresh player fed the generator's avatar positions (what a bot would see) holds exactly the
// recorded inputs and cameras, frame by frame.
TEST(ScriptedPlayer, HoldsWhatTheGeneratorRecorded) {
  const auto& obstacles = loaded_scene("obstacles");
  RecordingGeneratorConfig config;
  config.scene = "obstacles";
  config.seed = 5;
  config.replay.max_seconds = test::kSlowBuild ? 6.0 : 20.0;
  GeneratedRecording g;
  std::string error;
  ASSERT_TRUE(
      recording_generate(default_library(), obstacles.scene, obstacles.world, config, g, error))
      << error;
  const Recording& rec = g.recording;
  ScriptedPlayer player;
  ASSERT_TRUE(player.plan(default_library(), obstacles.scene, obstacles.world,
                          Placement{rec.start_pos_m, rec.start_heading_rad}, rec.goal_pos_m,
                          config.player_config(), error))
      << error;
  EXPECT_EQ(player.route(), g.route);
  size_t sample = 0;
  for (size_t k = 0; k < g.run.path.size(); ++k) {
    const double t = static_cast<double>(k) * config.replay.frame_interval_s;
    const vec2 pos = k == 0 ? rec.start_pos_m : g.run.path[k - 1];
    const ControlInput in = player.frame(t, pos);
    while (sample + 1 < rec.samples.size() && rec.samples[sample + 1].t_s <= t) ++sample;
    ASSERT_EQ(in.camera_dir, rec.samples[sample].input.camera_dir) << "frame " << k;
    ASSERT_EQ(in.camera_yaw_rad, rec.samples[sample].input.camera_yaw_rad) << "frame " << k;
    ASSERT_EQ(player.camera_pos_m(), rec.samples[sample].camera_pos_m) << "frame " << k;
  }
}

// The generator, now on ScriptedPlayer, still writes the shipped files byte for byte (the four
// commands of docs/RECORDINGS.md). After a change of the default library they are regenerated.
TEST(ScriptedPlayer, TheGeneratorStillMakesTheShippedRecordings) {
  if (test::kSlowBuild) GTEST_SKIP() << "twelve full recordings: Release builds only";
  struct Shipped {
    const char* name;
    const char* scene;
    const char* spawn;
    const char* goal;
    uint64_t seed;
  };
  const Shipped shipped[] = {{"maze_train", "maze", "", "", 1},
                             {"maze_eval", "maze", "centre", "dead-end-sw", 2},
                             {"obstacles_train", "obstacles", "", "", 1},
                             {"obstacles_eval", "obstacles", "", "", 2},
                             {"doorways_train", "doorways", "", "", 1},
                             {"doorways_eval", "doorways", "", "", 2},
                             {"beams_train", "beams", "", "", 1},
                             {"beams_eval", "beams", "", "", 2},
                             {"pillars_train", "pillars", "", "", 1},
                             {"pillars_eval", "pillars", "", "", 3},
                             {"dead_end_train", "dead_end", "", "", 1},
                             {"dead_end_eval", "dead_end", "", "", 2}};
  for (const Shipped& s : shipped) {
    SCOPED_TRACE(s.name);
    const auto& scene = loaded_scene(s.scene);
    RecordingGeneratorConfig config;  // as foresight-record
    config.scene = s.scene;
    config.name = s.name;
    config.spawn = s.spawn;
    config.goal = s.goal;
    config.seed = s.seed;
    config.replay.max_seconds = 240;
    GeneratedRecording g;
    std::string error;
    ASSERT_TRUE(recording_generate(default_library(), scene.scene, scene.world, config, g, error)) << error;
    std::ifstream in(data_dir() / "recordings" / (std::string(s.name) + ".json"), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(recording_write(g.recording), text.str());
  }
}

}  // namespace
}  // namespace foresight
