// Recordings: the file format (round trip, every kind of broken input), sample-and-hold, the
// authoring route planner, the shipped recordings and the generator's determinism.
#include "scripted/recording.hpp"
#include "scripted/recording_generator.hpp"
#include "lookahead/scene_path.hpp"
#include "lookahead_fixture.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace foresight {
namespace {

using test::default_library;
using test::loaded_scene;


std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Recording sample_recording() {
  Recording r;
  r.scene = "maze";
  r.name = "odd \"values\"";
  r.start_pos_m = vec2(1.25f, 1.3f);
  r.start_heading_rad = 1.2345678f;
  r.goal_pos_m = vec2(18.75f, 16.25f);
  r.goal_radius_m = 0.6f;
  r.library_hash = 0x0123456789abcdefull;
  ControlInput a;
  a.camera_yaw_rad = radians(45.0f);
  r.samples.push_back({0.0, a, vec3(-2.2f, 9.0f, -2.2f)});
  ControlInput b = a;
  b.camera_dir = vec2(0.6f, -0.8f);
  b.camera_yaw_rad = -2.9876543f;
  b.crouch = true;
  r.samples.push_back({1.0 / 3.0, b, vec3(22.2f, 9.0f, 22.2f)});
  ControlInput c = b;
  c.camera_dir = vec2(0.70710677f, 0.70710677f);
  c.camera_yaw_rad = 3.1415925f;
  c.crouch = false;
  r.samples.push_back({2.5, c, vec3(0.1f, 0.2f, 0.3f)});
  return r;
}

void expect_same(const Recording& a, const Recording& b) {
  EXPECT_EQ(a.scene, b.scene);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.start_pos_m, b.start_pos_m);
  EXPECT_EQ(a.start_heading_rad, b.start_heading_rad);
  EXPECT_EQ(a.goal_pos_m, b.goal_pos_m);
  EXPECT_EQ(a.goal_radius_m, b.goal_radius_m);
  EXPECT_EQ(a.library_hash, b.library_hash);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(a.samples[i].t_s, b.samples[i].t_s);
    EXPECT_EQ(a.samples[i].input.camera_dir, b.samples[i].input.camera_dir);
    EXPECT_EQ(a.samples[i].input.camera_yaw_rad, b.samples[i].input.camera_yaw_rad);
    EXPECT_EQ(a.samples[i].input.crouch, b.samples[i].input.crouch);
    EXPECT_EQ(a.samples[i].camera_pos_m, b.samples[i].camera_pos_m);
  }
}

TEST(Recording, WriteThenParseGivesTheSameRecordingExactly) {
  const Recording r = sample_recording();
  const std::string text = recording_write(r);
  Recording back;
  std::string error;
  ASSERT_TRUE(recording_parse(text, "t.json", back, error)) << error << "\n" << text;
  expect_same(r, back);
  EXPECT_EQ(recording_write(back), text);  // writing is deterministic and stable
  EXPECT_DOUBLE_EQ(back.duration_s(), 2.5);
  EXPECT_NE(text.find("\"camera_yaw_deg\":45,"), std::string::npos) << text;  // short numbers

  const auto dir = test::scratch_dir();
  ASSERT_TRUE(recording_save(dir / "r.json", r, error)) << error;
  Recording loaded;
  ASSERT_TRUE(recording_load(dir / "r.json", loaded, error)) << error;
  expect_same(r, loaded);
  EXPECT_FALSE(std::filesystem::exists(dir / "r.json.tmp"));
}

// A valid file with one sample line replaced, or the header edited.
std::string with_samples(const std::string& samples, const std::string& header_extra = "",
                         const std::string& version = "1", const std::string& format = "foresight-recording") {
  return "{\"format\": \"" + format + "\", \"version\": " + version + header_extra +
         ", \"scene\": \"maze\", \"start\": {\"pos\": [1, 2], \"heading_deg\": 90},"
         " \"goal\": {\"pos\": [3, 4]}, \"samples\": [" + samples + "]}";
}
const std::string kS0 = R"({"t": 0, "dir": [0, 1], "camera_yaw_deg": 45})";

TEST(Recording, AMinimalFileParsesWithDefaults) {
  Recording r;
  std::string error;
  ASSERT_TRUE(recording_parse(with_samples(kS0 + ", " + R"({"_note": "x", "t": 1.5, "dir": [1, 0], "camera_yaw_deg": -45, "crouch": true})"),
                              "m.json", r, error))
      << error;
  EXPECT_EQ(r.scene, "maze");
  EXPECT_EQ(r.name, "");
  EXPECT_EQ(r.start_pos_m, vec2(1, 2));
  EXPECT_FLOAT_EQ(r.start_heading_rad, kPi / 2);
  EXPECT_FLOAT_EQ(r.goal_radius_m, 0.75f);
  ASSERT_EQ(r.samples.size(), 2u);
  EXPECT_EQ(r.samples[0].camera_pos_m, vec3(0.0f));
  EXPECT_FALSE(r.samples[0].input.crouch);
  EXPECT_TRUE(r.samples[1].input.crouch);
  EXPECT_FLOAT_EQ(r.samples[1].input.camera_yaw_rad, -kPi / 4);
}

struct BadCase {
  const char* what;
  std::string text;
  std::vector<std::string> expect;  // substrings of the error
};

TEST(Recording, BrokenInputIsRefusedWithThePathAndTheReason) {
  const std::string s1 = R"({"t": 1, "dir": [1, 0], "camera_yaw_deg": 45})";
  const std::vector<BadCase> cases = {
      {"NaN literal", with_samples(R"({"t": NaN, "dir": [0, 1], "camera_yaw_deg": 45})"),
       {"bad.json: invalid JSON at line 1, column"}},
      {"inf literal", with_samples(R"({"t": 0, "dir": [0, 1], "camera_yaw_deg": Infinity})"),
       {"invalid JSON at line 1"}},
      {"too large for a double", with_samples(kS0 + R"(, {"t": 1e400, "dir": [0, 1], "camera_yaw_deg": 45})"),
       {"invalid JSON at line 1, column", "1e400", "not a finite number"}},
      {"too large for a float", with_samples(R"({"t": 0, "dir": [0, 1], "camera_yaw_deg": 45, "camera_pos": [1e39, 0, 0]})"),
       {"samples[0].camera_pos: component 0: 1e+39 is out of range"}},
      {"too large a time", with_samples(kS0 + R"(, {"t": 1e300, "dir": [0, 1], "camera_yaw_deg": 45})"),
       {"samples[1].t: 1e+300 is out of range"}},
      {"unsorted", with_samples(kS0 + ", " + R"({"t": 2, "dir": [1, 0], "camera_yaw_deg": 45}, )" + s1),
       {"samples[2].t: 1 is before the previous sample's t (2)"}},
      {"duplicate t", with_samples(kS0 + ", " + s1 + ", " + s1), {"samples[2].t: 1 repeats the previous sample's t (1)"}},
      {"first not at 0", with_samples(s1), {"samples[0].t: the first sample must be at t = 0"}},
      {"negative t", with_samples(R"({"t": -1, "dir": [0, 1], "camera_yaw_deg": 45})"), {"samples[0].t: -1 is out of range"}},
      {"unknown sample field", with_samples(kS0 + R"(, {"t": 1, "dir": [0, 1], "camera_yaw_deg": 45, "colour": 1, "size": 2})"),
       {"samples[1]: unknown fields \"colour\", \"size\" (allowed: t, dir, camera_yaw_deg, camera_pos, crouch)"}},
      {"unknown top-level field", with_samples(kS0, ", \"extra\": 1"), {"bad.json: unknown field \"extra\""}},
      {"unknown start field", "{\"format\": \"foresight-recording\", \"version\": 1, \"scene\": \"maze\", \"start\": {\"pos\": [1, 2], \"heading_deg\": 90, \"speed\": 1}, \"goal\": {\"pos\": [3, 4]}, \"samples\": [" + kS0 + "]}",
       {"start: unknown field \"speed\""}},
      {"|dir| > 1", with_samples(R"({"t": 0, "dir": [1, 1], "camera_yaw_deg": 45})"), {"samples[0].dir: length 1.41", "more than 1"}},
      {"dir too short", with_samples(R"({"t": 0, "dir": [1], "camera_yaw_deg": 45})"),
       {"samples[0].dir: expected an array of 2 numbers [x, y], got an array of 1"}},
      {"wrong version", with_samples(kS0, "", "2"), {"version: unsupported version 2 (this build reads version 1)"}},
      {"version not an integer", with_samples(kS0, "", "\"1\""), {"version: expected an integer, got a string"}},
      {"wrong format", with_samples(kS0, "", "1", "foresight-scene"), {"format: expected \"foresight-recording\", got \"foresight-scene\""}},
      {"missing field", with_samples(R"({"t": 0, "dir": [0, 1]})"), {"samples[0].camera_yaw_deg: missing required field"}},
      {"missing goal", "{\"format\": \"foresight-recording\", \"version\": 1, \"scene\": \"maze\", \"start\": {\"pos\": [1, 2], \"heading_deg\": 90}, \"samples\": [" + kS0 + "]}",
       {"goal: missing required field"}},
      {"missing format", "{\"version\": 1}", {"format: missing required field"}},
      {"wrong type", with_samples(R"({"t": "0", "dir": [0, 1], "camera_yaw_deg": 45})"),
       {"samples[0].t: expected a number, got a string (\"0\")"}},
      {"crouch not a boolean", with_samples(R"({"t": 0, "dir": [0, 1], "camera_yaw_deg": 45, "crouch": 1})"),
       {"samples[0].crouch: expected true or false, got a number (1)"}},
      {"sample not an object", with_samples(kS0 + ", 3"), {"samples[1]: expected an object, got a number (3)"}},
      {"samples not an array", with_samples("").replace(with_samples("").find("\"samples\": []"), 13, "\"samples\": {}"),
       {"samples: expected an array, got an object"}},
      {"no samples", with_samples(""), {"samples: needs at least one sample"}},
      {"root not an object", "[1, 2]", {"bad.json: expected an object, got an array of 2"}},
      {"empty text", "", {"bad.json: invalid JSON at line 1, column 1"}},
      {"truncated", with_samples(kS0 + ", " + s1).substr(0, 150), {"bad.json: invalid JSON at line 1, column"}},
      {"bad library hash", with_samples(kS0, ", \"library_hash\": \"12g4\""),
       {"library_hash: expected 1 to 16 hexadecimal digits, got \"12g4\""}},
      {"empty scene", with_samples(kS0).replace(with_samples(kS0).find("\"maze\""), 6, "\"\""), {"scene: must not be empty"}},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.what);
    Recording r = sample_recording();
    std::string error;
    EXPECT_FALSE(recording_parse(c.text, "bad.json", r, error)) << c.text;
    for (const std::string& e : c.expect) EXPECT_NE(error.find(e), std::string::npos) << "error: " << error;
    EXPECT_EQ(recording_write(r), recording_write(sample_recording()));  // output untouched
  }
}

TEST(Recording, MissingUnreadableAndTruncatedFilesGiveClearErrors) {
  Recording r;
  std::string error;
  const auto dir = test::scratch_dir();
  EXPECT_FALSE(recording_load(dir / "absent.json", r, error));
  EXPECT_NE(error.find("absent.json: no such file"), std::string::npos) << error;
  EXPECT_FALSE(recording_load(dir, r, error));
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;

  const std::string text = recording_write(sample_recording());
  {
    std::ofstream out(dir / "cut.json", std::ios::binary);
    out << text.substr(0, text.size() / 2);
  }
  EXPECT_FALSE(recording_load(dir / "cut.json", r, error));
  EXPECT_NE(error.find("cut.json: invalid JSON at line"), std::string::npos) << error;
  EXPECT_FALSE(recording_save(dir / "no-such-folder" / "x.json", sample_recording(), error));
  EXPECT_NE(error.find("cannot open for writing"), std::string::npos) << error;
}

TEST(Recording, InputIsSampledAndHeld) {
  const Recording r = sample_recording();  // samples at 0, 1/3, 2.5
  EXPECT_EQ(recording_input_at(r, -0.1).camera_dir, vec2(0.0f));  // before the first: stop
  EXPECT_EQ(recording_input_at(r, -0.1).camera_yaw_rad, 0.0f);
  EXPECT_EQ(recording_input_at(r, 0.0).camera_yaw_rad, r.samples[0].input.camera_yaw_rad);
  EXPECT_EQ(recording_input_at(r, 0.3).camera_dir, vec2(0.0f));
  EXPECT_EQ(recording_input_at(r, 1.0 / 3.0).camera_dir, vec2(0.6f, -0.8f));  // at its time exactly
  EXPECT_TRUE(recording_input_at(r, 2.4999).crouch);
  EXPECT_EQ(recording_input_at(r, 2.5).camera_dir, r.samples[2].input.camera_dir);
  EXPECT_EQ(recording_input_at(r, 1e9).camera_dir, r.samples[2].input.camera_dir);  // held after the end
  EXPECT_EQ(recording_input_at(Recording{}, 1.0).camera_dir, vec2(0.0f));
}

// ------------------------------------------------------------------- scene_route

void expect_route_valid(const CollisionWorld& world, const std::vector<vec2>& route, vec2 from, vec2 to,
                        float clearance, float height) {
  ASSERT_GE(route.size(), 2u);
  EXPECT_EQ(route.front(), from);
  EXPECT_EQ(route.back(), to);
  // Inner legs are clear for the planned body; the legs joining start and goal to the grid are
  // clear for a thin one.
  for (size_t i = 1; i < route.size(); ++i) {
    const bool inner = i > 1 && i + 1 < route.size();
    EXPECT_TRUE(scene_segment_clear(world, route[i - 1], route[i], inner ? clearance : 0.05f, height))
        << "leg " << i;
  }
}

TEST(SceneRoute, FindsRoutesThroughTheMazeAndTheObstacles) {
  const auto& maze = loaded_scene("maze");
  std::vector<vec2> route;
  const vec2 start = maze.scene.spawns[0].pos_m, goal = maze.scene.goals[0].pos_m;
  ASSERT_TRUE(scene_route(maze.world, start, goal, 0.5f, route));
  expect_route_valid(maze.world, route, start, goal, 0.5f, kStandingHeight_m);
  // 23 cells of 2.5 m along the corridors; corners cut.
  EXPECT_GT(route_length_m(route), 40.0f);
  EXPECT_LT(route_length_m(route), 60.0f);

  // Obstacles: crouch-high, the short way passes under the beam at x = 5 in the first corridor;
  // standing, the long way round.
  const auto& obstacles = loaded_scene("obstacles");
  const vec2 o_start = obstacles.scene.spawns[0].pos_m, o_goal = obstacles.scene.goals[0].pos_m;
  const float crouch = lowest_moving_body_m(default_library());
  EXPECT_LT(crouch, 1.25f);  // the beam's bottom
  std::vector<vec2> low, high;
  // (Standing, the long way leads past the crate through a 0.9 m gap: a thin walker.)
  ASSERT_TRUE(scene_route(obstacles.world, o_start, o_goal, 0.4f, crouch, low));
  ASSERT_TRUE(scene_route(obstacles.world, o_start, o_goal, 0.3f, kStandingHeight_m, high));
  expect_route_valid(obstacles.world, low, o_start, o_goal, 0.4f, crouch);
  expect_route_valid(obstacles.world, high, o_start, o_goal, 0.3f, kStandingHeight_m);
  bool under_beam = false;
  for (size_t i = 1; i < low.size(); ++i)
    under_beam |= (low[i - 1].x - 5.0f) * (low[i].x - 5.0f) <= 0.0f && std::max(low[i - 1].y, low[i].y) < 2.5f;
  EXPECT_TRUE(under_beam);
  EXPECT_GT(route_length_m(high), route_length_m(low) + 10.0f);
}

TEST(SceneRoute, NoRouteWhenTheGoalIsWalledIn) {
  Scene scene;
  scene.name = "walled";
  scene.bounds = {vec2(-10.0f), vec2(10.0f)};
  scene.spawns.push_back({"s", vec2(-8, -8), 0.0f});
  // A closed 3 x 3 m room around (5, 5), walls 0.2 m thick.
  const auto wall = [&](vec2 lo, vec2 hi) { scene.boxes.push_back({"", BoxKind::kWall, from_ground(lo, 0), from_ground(hi, 2.5f)}); };
  wall({3.4f, 3.4f}, {6.6f, 3.6f});
  wall({3.4f, 6.4f}, {6.6f, 6.6f});
  wall({3.4f, 3.4f}, {3.6f, 6.6f});
  wall({6.4f, 3.4f}, {6.6f, 6.6f});
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(collision_world_build(scene, world, error)) << error;
  std::vector<vec2> route{vec2(1.0f)};
  EXPECT_FALSE(scene_route(world, vec2(-8, -8), vec2(5, 5), 0.4f, route));
  EXPECT_TRUE(route.empty());
  EXPECT_FALSE(scene_route(world, vec2(-8, -8), vec2(3.5f, 5.0f), 0.4f, route));  // inside a wall
  // With a doorway the room is reachable.
  scene.boxes.pop_back();
  wall({6.4f, 3.4f}, {6.6f, 4.2f});
  wall({6.4f, 5.8f}, {6.6f, 6.6f});
  ASSERT_TRUE(collision_world_build(scene, world, error)) << error;
  EXPECT_TRUE(scene_route(world, vec2(-8, -8), vec2(5, 5), 0.4f, route));
  EXPECT_FALSE(scene_route(world, vec2(-8, -8), vec2(NAN, 5), 0.4f, route));
}

// ------------------------------------------------------------------- shipped recordings

const char* const kShipped[] = {"maze_train", "maze_eval", "obstacles_train", "obstacles_eval"};

TEST(ShippedRecordings, LoadAndStartAtTheirScenesSpawn) {
  for (const char* name : kShipped) {
    SCOPED_TRACE(name);
    Recording r;
    std::string error;
    ASSERT_TRUE(recording_load(data_dir() / "recordings" / (std::string(name) + ".json"), r, error)) << error;
    EXPECT_EQ(r.name, name);
    const auto& scene = loaded_scene(r.scene).scene;
    bool at_spawn = false, at_goal = false;
    for (const SpawnPoint& s : scene.spawns)
      at_spawn |= s.pos_m == r.start_pos_m && s.heading_rad == r.start_heading_rad;
    for (const GoalPoint& g : scene.goals) at_goal |= g.pos_m == r.goal_pos_m && g.radius_m == r.goal_radius_m;
    EXPECT_TRUE(at_spawn);
    EXPECT_TRUE(at_goal);
    EXPECT_GT(r.samples.size(), 5u);
    EXPECT_GT(r.duration_s(), 10.0);
    for (const CommandSample& s : r.samples) EXPECT_FALSE(s.input.crouch);  // the avatar decides
  }
}

TEST(RecordingGenerator, IsDeterministic) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  RecordingGeneratorConfig config;
  config.scene = "maze";
  config.name = "maze_train";
  config.seed = 7;
  config.replay.max_seconds = test::kSlowBuild ? 8.0 : 20.0;
  const auto dir = test::scratch_dir();
  std::string texts[2];
  for (int i = 0; i < 2; ++i) {
    GeneratedRecording g;
    std::string error;
    ASSERT_TRUE(recording_generate(lib, maze.scene, maze.world, config, g, error)) << error;
    const auto path = dir / ("run" + std::to_string(i) + ".json");
    ASSERT_TRUE(recording_save(path, g.recording, error)) << error;
    texts[i] = read_text(path);
    EXPECT_EQ(g.run.colliding_frames, 0);
    EXPECT_GE(g.route.size(), 2u);
    EXPECT_EQ(g.recording.samples.front().t_s, 0.0);
  }
  EXPECT_FALSE(texts[0].empty());
  EXPECT_EQ(texts[0], texts[1]);
  // Another seed, another player.
  config.seed = 8;
  GeneratedRecording other;
  std::string error;
  ASSERT_TRUE(recording_generate(lib, maze.scene, maze.world, config, other, error)) << error;
  EXPECT_NE(recording_write(other.recording), texts[0]);
}

TEST(RecordingGenerator, RefusesUnknownPointsAndUnreachableGoals) {
  const auto& lib = default_library();
  const auto& maze = loaded_scene("maze");
  RecordingGeneratorConfig config;
  GeneratedRecording g;
  std::string error;
  config.goal = "nowhere";
  EXPECT_FALSE(recording_generate(lib, maze.scene, maze.world, config, g, error));
  EXPECT_NE(error.find("no goal \"nowhere\" (goals: \"goal\", \"dead-end-sw\")"), std::string::npos) << error;
  config.goal.clear();
  config.spawn = "moon";
  EXPECT_FALSE(recording_generate(lib, maze.scene, maze.world, config, g, error));
  EXPECT_NE(error.find("no spawn \"moon\""), std::string::npos) << error;
  config.spawn.clear();
  config.goal = "goal";
  Scene walled = maze.scene;  // the goal's corridor closed off
  const GoalPoint& goal = walled.goals[0];
  walled.boxes.push_back({"plug", BoxKind::kWall, {goal.pos_m.x - 1.3f, 0.0f, goal.pos_m.y - 1.3f},
                          {goal.pos_m.x + 1.3f, 2.5f, goal.pos_m.y - 0.9f}});
  walled.boxes.push_back({"plug2", BoxKind::kWall, {goal.pos_m.x - 1.3f, 0.0f, goal.pos_m.y - 1.3f},
                          {goal.pos_m.x - 0.9f, 2.5f, goal.pos_m.y + 1.3f}});
  walled.boxes.push_back({"plug3", BoxKind::kWall, {goal.pos_m.x + 0.9f, 0.0f, goal.pos_m.y - 1.3f},
                          {goal.pos_m.x + 1.3f, 2.5f, goal.pos_m.y + 1.3f}});
  walled.boxes.push_back({"plug4", BoxKind::kWall, {goal.pos_m.x - 1.3f, 0.0f, goal.pos_m.y + 0.9f},
                          {goal.pos_m.x + 1.3f, 2.5f, goal.pos_m.y + 1.3f}});
  CollisionWorld walled_world;
  ASSERT_TRUE(collision_world_build(walled, walled_world, error)) << error;
  EXPECT_FALSE(recording_generate(lib, walled, walled_world, config, g, error));
  EXPECT_NE(error.find("no route"), std::string::npos) << error;
}

}  // namespace
}  // namespace foresight
