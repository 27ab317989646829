// Scene loading and validation: every failure gives false and an error naming the JSON field.
#include "support/test_paths.hpp"
#include "world/scene_load.hpp"
#include "world_test_util.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <functional>

namespace foresight {
namespace {

using nlohmann::json;

json minimal_scene() {
  return json::parse(R"({
    "name": "t",
    "bounds": {"min": [0, 0], "max": [10, 10]},
    "boxes": [{"kind": "wall", "name": "w", "min": [4, 0.5, 4], "max": [5, 2, 5]}],
    "spawns": [{"name": "s", "pos": [1, 1], "heading_deg": 90}]
  })");
}

/// Parses `j` as "t.json"; expects failure with an error containing `expected`.
void expect_error(const json& j, const std::string& expected) {
  Scene scene;
  scene.name = "untouched";
  std::string error;
  EXPECT_FALSE(scene_parse(j.dump(), "t.json", scene, error)) << j.dump();
  EXPECT_NE(error.find(expected), std::string::npos) << "error: " << error
                                                     << "\nexpected to contain: " << expected;
  EXPECT_EQ(error.rfind("t.json: ", 0), 0u) << error;
  EXPECT_EQ(scene.name, "untouched") << "a failed parse must leave the scene alone";
}

void expect_error_text(const std::string& text, const std::string& expected) {
  Scene scene;
  std::string error;
  EXPECT_FALSE(scene_parse(text, "t.json", scene, error));
  EXPECT_NE(error.find(expected), std::string::npos) << "error: " << error
                                                     << "\nexpected to contain: " << expected;
}

json with(std::function<void(json&)> edit) {
  json j = minimal_scene();
  edit(j);
  return j;
}

TEST(SceneLoad, MinimalSceneParses) {
  Scene scene;
  std::string error;
  ASSERT_TRUE(scene_parse(minimal_scene().dump(), "t.json", scene, error)) << error;
  EXPECT_EQ(scene.name, "t");
  ASSERT_EQ(scene.boxes.size(), 1u);
  EXPECT_EQ(scene.boxes[0].kind, BoxKind::kWall);
  EXPECT_EQ(scene.boxes[0].max_m, vec3(5, 2, 5));
  ASSERT_EQ(scene.spawns.size(), 1u);
  EXPECT_FLOAT_EQ(scene.spawns[0].heading_rad, kPi / 2);
  EXPECT_TRUE(scene.terrain.height_field.empty());
  EXPECT_EQ(scene.terrain.floor_y_m, 0.0f);
}

TEST(SceneLoad, FullFeatureSceneParses) {
  json j = with([](json& s) {
    s["format"] = "foresight-scene";
    s["version"] = 1;
    s["_comment"] = "keys starting with an underscore are notes";
    s["terrain"] = json::parse(R"({"floor_y": 0.1,
      "height_field": {"origin": [0, 0], "cell": 0.5, "count": [3, 2],
                       "heights": [0, 0.1, null, 0.2, 0.3, 0.4]},
      "steps": [{"name": "st", "min": [6, 0, 6], "max": [7, 0.2, 7]}]})");
    s["goals"] = json::parse(R"([{"pos": [8, 8]}, {"name": "g", "pos": [2, 8], "radius": 1}])");
    s["cameras"] = json::parse(R"([{"name": "c", "position": [0, 5, 0], "target": [5, 0, 5],
      "fov_y_deg": 60, "region": {"min": [0, 0], "max": [10, 10]}}])");
    s["npcs"] = json::parse(R"([{"kind": "guard", "pos": [9, 9], "heading_deg": -90}])");
  });
  Scene scene;
  std::string error;
  ASSERT_TRUE(scene_parse(j.dump(), "t.json", scene, error)) << error;
  const HeightField& f = scene.terrain.height_field;
  EXPECT_EQ(f.count_x, 3);
  EXPECT_EQ(f.count_z, 2);
  EXPECT_TRUE(std::isnan(f.heights_m[2]));
  EXPECT_FLOAT_EQ(f.heights_m[5], 0.4f);
  EXPECT_FLOAT_EQ(scene.terrain.floor_y_m, 0.1f);
  EXPECT_EQ(scene.terrain.steps.size(), 1u);
  EXPECT_FLOAT_EQ(scene.goals[0].radius_m, 0.5f);
  EXPECT_FLOAT_EQ(scene.goals[1].radius_m, 1.0f);
  EXPECT_NEAR(scene.cameras[0].fov_y_rad, radians(60.0f), 1e-6f);
  EXPECT_EQ(scene.npcs[0].kind, "guard");
  EXPECT_NEAR(scene.npcs[0].heading_rad, -kPi / 2, 1e-6f);
}

TEST(SceneLoad, BoxMinNotBelowMaxNamesTheAxis) {
  expect_error(with([](json& s) { s["boxes"][0]["max"][1] = 0.2; }),
               "t.json: boxes[0].max: max.y (0.2) must be > min.y (0.5)");
  expect_error(with([](json& s) { s["boxes"][0]["max"][0] = 4; }),
               "boxes[0].max: max.x (4) must be > min.x (4)");
  expect_error(with([](json& s) { s["boxes"][0]["max"][2] = 3; }),
               "boxes[0].max: max.z (3) must be > min.z (4)");
}

TEST(SceneLoad, WrongTypesNameTheField) {
  expect_error(with([](json& s) { s["boxes"][0]["min"] = "abc"; }),
               "boxes[0].min: expected an array of 3 numbers [x, y, z], got a string (\"abc\")");
  expect_error(with([](json& s) { s["boxes"][0]["min"] = {1, 2}; }),
               "boxes[0].min: expected an array of 3 numbers");
  expect_error(with([](json& s) { s["boxes"][0]["min"][1] = true; }),
               "boxes[0].min[1]: expected a number, got a boolean (true)");
  expect_error(with([](json& s) { s["name"] = 7; }), "name: expected a string, got a number (7)");
  expect_error(with([](json& s) { s["boxes"] = json::object(); }),
               "boxes: expected an array, got an object");
  expect_error(with([](json& s) { s["spawns"][0]["heading_deg"] = "north"; }),
               "spawns[0].heading_deg: expected a number, got a string");
  expect_error(with([](json& s) { s["bounds"] = {0, 0, 10, 10}; }),
               "bounds: expected an object, got an array of 4");
  expect_error_text("[1, 2]", "t.json: (root): expected a JSON object, got an array of 2");
}

TEST(SceneLoad, MissingFieldsNameTheField) {
  expect_error(with([](json& s) { s.erase("name"); }), "t.json: name: missing required field");
  expect_error(with([](json& s) { s.erase("bounds"); }), "bounds: missing required field");
  expect_error(with([](json& s) { s.erase("spawns"); }), "spawns: missing required field");
  expect_error(with([](json& s) { s["boxes"][0].erase("kind"); }),
               "boxes[0].kind: missing required field");
  expect_error(with([](json& s) { s["spawns"][0].erase("pos"); }),
               "spawns[0].pos: missing required field");
  expect_error(with([](json& s) { s["spawns"] = json::array(); }),
               "spawns: needs at least one spawn point");
  expect_error(with([](json& s) { s["npcs"] = json::parse(R"([{"pos": [1, 2], "heading_deg": 0}])"); }),
               "npcs[0].kind: missing required field");
}

TEST(SceneLoad, UnknownFieldsAndKindsAreErrors) {
  expect_error(with([](json& s) { s["boxes"][0]["colour"] = "red"; }),
               "boxes[0]: unknown field \"colour\"");
  expect_error(with([](json& s) { s["spwans"] = json::array(); }),
               "(root): unknown field \"spwans\"");
  expect_error(with([](json& s) { s["boxes"][0]["kind"] = "wal"; }),
               "boxes[0].kind: unknown kind \"wal\" (expected one of: wall, obstacle, beam, table, "
               "doorway-lintel, shelf, prop)");
  expect_error(with([](json& s) { s["format"] = "other"; }), "format: expected \"foresight-scene\"");
  expect_error(with([](json& s) { s["version"] = 2; }), "version: 2 is out of range [1, 1]");
}

TEST(SceneLoad, HugeAndNonFiniteNumbersAreRejected) {
  expect_error(with([](json& s) { s["boxes"][0]["min"][0] = 1e300; }),
               "boxes[0].min[0]: 1e+300 is out of range [-100000, 100000]");
  expect_error(with([](json& s) { s["spawns"][0]["pos"][1] = -2e5; }),
               "spawns[0].pos[1]: -200000 is out of range");
  // JSON has no NaN or infinity; an overflowing literal is the closest a file can get.
  std::string text = minimal_scene().dump();
  const std::string from = "[4,0.5,4]";
  ASSERT_NE(text.find(from), std::string::npos) << text;
  text.replace(text.find(from), from.size(), "[1e400,0.5,4]");
  Scene scene;
  std::string error;
  EXPECT_FALSE(scene_parse(text, "t.json", scene, error));
  EXPECT_EQ(error.rfind("t.json: invalid JSON at line 1, column ", 0), 0u) << error;
  EXPECT_NE(error.find("number overflow parsing '1e400'"), std::string::npos) << error;
}

TEST(SceneLoad, AbsurdSizesAreCapped) {
  expect_error(with([](json& s) { s["bounds"]["max"] = {5000, 10}; }),
               "bounds: size 5000 x 10 m exceeds 2000 m");
  expect_error(with([](json& s) {
                 s["terrain"] = json::parse(R"({"height_field": {"origin": [0, 0], "cell": 0.1,
                   "count": [5000, 1], "heights": []}})");
               }),
               "terrain.height_field.count[0]: 5000 is out of range [1, 4096]");
  expect_error(with([](json& s) {
                 s["terrain"] = json::parse(R"({"height_field": {"origin": [0, 0], "cell": 1,
                   "count": [4096, 4096], "heights": []}})");
               }),
               "terrain.height_field.count: field extent 4096 x 4096 m exceeds 2000 m");
  expect_error(with([](json& s) { s["goals"] = json::parse(R"([{"pos": [1, 1], "radius": -1}])"); }),
               "goals[0].radius: -1 is out of range");
}

TEST(SceneLoad, TooManyBoxesIsAnErrorBeforeReadingThem) {
  std::string text = R"({"name": "t", "bounds": {"min": [0, 0], "max": [10, 10]},
    "spawns": [{"pos": [1, 1], "heading_deg": 0}], "boxes": [)";
  const std::string one = R"({"kind":"wall","min":[5,0,5],"max":[6,1,6]},)";
  text.reserve(text.size() + one.size() * (kMaxSceneBoxes + 1));
  for (std::size_t i = 0; i <= kMaxSceneBoxes; ++i) text += one;
  text.back() = ']';
  text += "}";
  expect_error_text(text, "t.json: boxes: has 100001 entries, more than the 100000 allowed");
}

TEST(SceneLoad, HeightFieldErrorsNameTheField) {
  const auto field = [](const std::string& body) {
    return with([&](json& s) { s["terrain"] = json::parse(R"({"height_field": )" + body + "}"); });
  };
  expect_error(field(R"({"origin": [0, 0], "cell": 1, "count": [2, 2], "heights": [0, 0, 0, 0, 0]})"),
               "terrain.height_field.heights: has 5 values, expected count[0] * count[1] = 2 * 2 = 4");
  expect_error(field(R"({"origin": [0, 0], "cell": 1, "count": [2, 2], "heights": [0, 0, "x", 0]})"),
               "terrain.height_field.heights[2]: expected a number or null (a hole), got a string");
  expect_error(field(R"({"origin": [0, 0], "cell": 1, "count": [2.5, 2], "heights": []})"),
               "terrain.height_field.count[0]: expected an integer, got a number (2.5)");
  expect_error(field(R"({"origin": [0, 0], "cell": 0, "count": [1, 1], "heights": [0]})"),
               "terrain.height_field.cell: 0 is out of range [0.01, 100]");
  expect_error(field(R"({"origin": [0, 0], "cell": 1, "count": [1, 1]})"),
               "terrain.height_field.heights: missing required field");
  expect_error(with([](json& s) {
                 s["terrain"] = json::parse(R"({"steps": [{"min": [1, 0.3, 1], "max": [2, 0.1, 2]}]})");
               }),
               "terrain.steps[0].max: max.y (0.1) must be > min.y (0.3)");
}

TEST(SceneLoad, CameraErrorsNameTheField) {
  const auto camera = [](const std::string& body) {
    return with([&](json& s) { s["cameras"] = json::array({json::parse(body)}); });
  };
  expect_error(camera(R"({"position": [0, 5, 0], "target": [5, 0, 5], "fov_y_deg": 60,
                          "region": {"min": [3, 0], "max": [3, 10]}})"),
               "cameras[0].region.max: max.x (3) must be > min.x (3)");
  expect_error(camera(R"({"position": [0, 5, 0], "target": [5, 0, 5], "fov_y_deg": 0,
                          "region": {"min": [0, 0], "max": [3, 10]}})"),
               "cameras[0].fov_y_deg: 0 is out of range [1, 179]");
  expect_error(camera(R"({"position": [1, 5, 1], "target": [1, 5, 1], "fov_y_deg": 60,
                          "region": {"min": [0, 0], "max": [3, 10]}})"),
               "cameras[0].target: must differ from position");
  expect_error(camera(R"({"position": [0, 5, 0], "target": [5, 0, 5], "fov_y_deg": 60,
                          "region": {"min": [20, 20], "max": [30, 30]}})"),
               "cameras[0].region: does not overlap the scene bounds");
  expect_error(camera(R"({"position": [0, 5, 0], "target": [5, 0, 5], "fov_y_deg": 60})"),
               "cameras[0].region: missing required field");
}

TEST(SceneLoad, SpawnsMustStandFree) {
  expect_error(with([](json& s) { s["spawns"][0]["pos"] = {4.5, 4.5}; }),
               "spawns[0].pos: (4.5, 4.5) is inside boxes[0] \"w\" (wall)");
  expect_error(with([](json& s) { s["spawns"][0]["pos"] = {11, 1}; }),
               "spawns[0].pos: (11, 1) is outside the bounds (0, 0) - (10, 10)");
  expect_error(with([](json& s) { s["goals"] = json::parse(R"([{"pos": [4, 4.2]}])"); }),
               "goals[0].pos: (4, 4.2) is inside boxes[0]");
  expect_error(with([](json& s) {
                 s["npcs"] = json::parse(R"([{"kind": "k", "pos": [4.9, 4.9], "heading_deg": 0}])");
               }),
               "npcs[0].pos: (4.9, 4.9) is inside boxes[0]");
  expect_error(with([](json& s) {
                 s["terrain"] = json::parse(R"({"height_field": {"origin": [0, 0], "cell": 2,
                   "count": [1, 1], "heights": [null]}})");
               }),
               "spawns[0].pos: (1, 1) has no ground (a height-field hole)");
  // Under a box whose bottom is above a standing avatar's head is fine.
  json high = with([](json& s) {
    s["boxes"][0]["min"][1] = 1.9;
    s["boxes"][0]["max"][1] = 2.2;
    s["spawns"][0]["pos"] = {4.5, 4.5};
  });
  Scene scene;
  std::string error;
  EXPECT_TRUE(scene_parse(high.dump(), "t.json", scene, error)) << error;
}

TEST(SceneLoad, InvalidJsonReportsLineAndColumn) {
  expect_error_text("{\n  \"name\": \"t\",\n  \"bounds\": {]\n}", "t.json: invalid JSON at line 3, column 14");
  expect_error_text("", "t.json: invalid JSON at line 1, column 1");
  expect_error_text("{\"name\": \"t\",}", "invalid JSON at line 1, column 14");
}

TEST(SceneLoad, DeeplyNestedJsonDoesNotCrash) {
  const std::size_t depth = 100000;
  expect_error_text(std::string(depth, '['), "invalid JSON");
  expect_error_text(std::string(depth, '[') + std::string(depth, ']'), "(root): expected a JSON object");
}

TEST(SceneLoad, TruncatedFileFails) {
  const std::filesystem::path dir = test::scratch_dir();
  std::ifstream in(test::scenes_dir() / "maze.json", std::ios::binary);
  const std::string full((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(full.size(), 100u);
  for (std::size_t cut : {full.size() / 2, full.size() - 3, std::size_t{1}}) {
    const std::filesystem::path path = dir / "maze_truncated.json";
    std::ofstream(path, std::ios::binary) << full.substr(0, cut);
    Scene scene;
    std::string error;
    EXPECT_FALSE(scene_load(path, scene, error));
    EXPECT_EQ(error.rfind("maze_truncated.json: invalid JSON at line ", 0), 0u) << error;
  }
}

TEST(SceneLoad, MissingFileAndDirectoryFail) {
  Scene scene;
  std::string error;
  EXPECT_FALSE(scene_load(test::scenes_dir() / "no_such_scene.json", scene, error));
  EXPECT_NE(error.find("no_such_scene.json: no such file"), std::string::npos) << error;
  EXPECT_FALSE(scene_load(test::scenes_dir(), scene, error));
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
}

TEST(SceneLoad, ValidateCatchesCodeBuiltScenes) {
  Scene scene;
  std::string error;
  EXPECT_FALSE(scene_validate(scene, "code", error));
  EXPECT_EQ(error, "code: name: must not be empty");
  scene.name = "c";
  scene.bounds = {{0, 0}, {10, 10}};
  EXPECT_FALSE(scene_validate(scene, "code", error));
  EXPECT_EQ(error, "code: spawns: needs at least one spawn point");
  scene.spawns.push_back({"s", {1, 1}, 0});
  EXPECT_TRUE(scene_validate(scene, "code", error)) << error;
  scene.boxes.push_back({"b", BoxKind::kWall, {1, 0, 1}, {1, 1, 2}});
  EXPECT_FALSE(scene_validate(scene, "code", error));
  EXPECT_EQ(error, "code: boxes[0].max: max.x (1) must be > min.x (1)");
}

}  // namespace
}  // namespace foresight
