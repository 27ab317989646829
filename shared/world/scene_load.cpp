#include "world/scene_load.hpp"

#include "io/text_file.hpp"

#include "io/json_reader.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <system_error>

namespace foresight {
namespace {

using nlohmann::json;
using json_io::Reader;

// Files larger than this are refused before reading: a 4096 x 4096 height field written with
// short numbers is ~100 MB, so this leaves room without letting a stray file exhaust memory.

constexpr double kMaxHeadingDeg = 36000.0;
constexpr double kMaxHeight_m = 10000.0;

bool read_box(Reader& r, const json& j, const std::string& path, SceneBox& box) {
  if (!r.require_object(j, path) ||
      !r.check_keys(j, path, {"name", "kind", "min", "max"}) ||
      !r.optional_string(j, path, "name", box.name))
    return false;
  std::string kind;
  if (!r.required_string(j, path, "kind", kind)) return false;
  if (!box_kind_from_name(kind, box.kind))
    return r.fail(Reader::child(path, "kind"), "unknown kind \"" + kind + "\" (expected one of: " +
                                                   std::string(box_kind_names()) + ")");
  return r.required_vec3(j, path, "min", kMaxSceneCoord_m, box.min_m) &&
         r.required_vec3(j, path, "max", kMaxSceneCoord_m, box.max_m) &&
         r.check_min_less_max(Reader::child(path, "max"), box.min_m, box.max_m);
}

bool read_step(Reader& r, const json& j, const std::string& path, StepBlock& step) {
  return r.require_object(j, path) && r.check_keys(j, path, {"name", "min", "max"}) &&
         r.optional_string(j, path, "name", step.name) &&
         r.required_vec3(j, path, "min", kMaxSceneCoord_m, step.min_m) &&
         r.required_vec3(j, path, "max", kMaxSceneCoord_m, step.max_m) &&
         r.check_min_less_max(Reader::child(path, "max"), step.min_m, step.max_m);
}

bool read_height_field(Reader& r, const json& j, const std::string& path, HeightField& field) {
  if (!r.require_object(j, path) ||
      !r.check_keys(j, path, {"origin", "cell", "count", "heights"}) ||
      !r.required_vec2(j, path, "origin", kMaxSceneCoord_m, field.origin_m) ||
      !r.required_number(j, path, "cell", 0.01, 100.0, field.cell_m))
    return false;
  const json* count = nullptr;
  if (!r.member(j, path, "count", true, count)) return false;
  const std::string count_path = Reader::child(path, "count");
  if (!count->is_array() || count->size() != 2)
    return r.fail(count_path, "expected an array of 2 integers [count_x, count_z], got " +
                                  json_describe(*count));
  int counts[2] = {0, 0};
  for (std::size_t i = 0; i < 2; ++i) {
    if (!r.integer((*count)[i], Reader::index(count_path, i), 1, kMaxHeightFieldCount, counts[i]))
      return false;
  }
  field.count_x = counts[0];
  field.count_z = counts[1];
  const float extent_x = static_cast<float>(field.count_x) * field.cell_m;
  const float extent_z = static_cast<float>(field.count_z) * field.cell_m;
  if (extent_x > kMaxSceneExtent_m || extent_z > kMaxSceneExtent_m)
    return r.fail(count_path, "field extent " + Reader::fmt(extent_x) + " x " +
                                  Reader::fmt(extent_z) + " m exceeds " +
                                  Reader::fmt(kMaxSceneExtent_m) + " m");

  const json* heights = nullptr;
  if (!r.member(j, path, "heights", true, heights)) return false;
  const std::string heights_path = Reader::child(path, "heights");
  if (!heights->is_array())
    return r.fail(heights_path, "expected an array of numbers or null, got " +
                                    json_describe(*heights));
  const std::size_t expected = static_cast<std::size_t>(field.count_x) * field.count_z;
  if (heights->size() != expected)
    return r.fail(heights_path, "has " + std::to_string(heights->size()) +
                                    " values, expected count[0] * count[1] = " +
                                    std::to_string(field.count_x) + " * " +
                                    std::to_string(field.count_z) + " = " +
                                    std::to_string(expected));
  field.heights_m.assign(expected, 0.0f);
  for (std::size_t i = 0; i < expected; ++i) {
    const json& h = (*heights)[i];
    if (h.is_null()) {
      field.heights_m[i] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    // The element path is built only on failure: this loop runs up to 16M times.
    if (!h.is_number())
      return r.fail(Reader::index(heights_path, i),
                    "expected a number or null (a hole), got " + json_describe(h));
    std::string reason;
    if (!Reader::number_in_range(h, -kMaxHeight_m, kMaxHeight_m, field.heights_m[i], reason))
      return r.fail(Reader::index(heights_path, i), reason);
  }
  return true;
}

bool read_terrain(Reader& r, const json& j, const std::string& path, Terrain& terrain) {
  if (!r.require_object(j, path) || !r.check_keys(j, path, {"floor_y", "height_field", "steps"}))
    return false;
  terrain.floor_y_m = 0.0f;
  if (!r.optional_number(j, path, "floor_y", -kMaxHeight_m, kMaxHeight_m, terrain.floor_y_m))
    return false;
  const json* field = nullptr;
  if (!r.member(j, path, "height_field", false, field)) return false;
  if (field != nullptr &&
      !read_height_field(r, *field, Reader::child(path, "height_field"), terrain.height_field))
    return false;
  return r.array_of(j, path, "steps", kMaxSceneSteps, terrain.steps, read_step);
}

bool read_spawn(Reader& r, const json& j, const std::string& path, SpawnPoint& spawn) {
  float heading_deg = 0.0f;
  if (!r.require_object(j, path) || !r.check_keys(j, path, {"name", "pos", "heading_deg"}) ||
      !r.optional_string(j, path, "name", spawn.name) ||
      !r.required_vec2(j, path, "pos", kMaxSceneCoord_m, spawn.pos_m) ||
      !r.required_number(j, path, "heading_deg", -kMaxHeadingDeg, kMaxHeadingDeg, heading_deg))
    return false;
  spawn.heading_rad = wrap_angle(radians(heading_deg));
  return true;
}

bool read_goal(Reader& r, const json& j, const std::string& path, GoalPoint& goal) {
  goal.radius_m = 0.5f;
  return r.require_object(j, path) && r.check_keys(j, path, {"name", "pos", "radius"}) &&
         r.optional_string(j, path, "name", goal.name) &&
         r.required_vec2(j, path, "pos", kMaxSceneCoord_m, goal.pos_m) &&
         r.optional_number(j, path, "radius", 0.01, 100.0, goal.radius_m);
}

bool read_rect(Reader& r, const json& j, const std::string& path, GroundRect& rect) {
  return r.require_object(j, path) && r.check_keys(j, path, {"min", "max"}) &&
         r.required_vec2(j, path, "min", kMaxSceneCoord_m, rect.min_m) &&
         r.required_vec2(j, path, "max", kMaxSceneCoord_m, rect.max_m) &&
         r.check_min_less_max(Reader::child(path, "max"), rect.min_m, rect.max_m);
}

bool read_camera(Reader& r, const json& j, const std::string& path, SceneCamera& camera) {
  float fov_deg = 0.0f;
  if (!r.require_object(j, path) ||
      !r.check_keys(j, path, {"name", "position", "target", "fov_y_deg", "region"}) ||
      !r.optional_string(j, path, "name", camera.name) ||
      !r.required_vec3(j, path, "position", kMaxSceneCoord_m, camera.position_m) ||
      !r.required_vec3(j, path, "target", kMaxSceneCoord_m, camera.target_m) ||
      !r.required_number(j, path, "fov_y_deg", 1.0, 179.0, fov_deg))
    return false;
  camera.fov_y_rad = radians(fov_deg);
  if (glm::length(camera.target_m - camera.position_m) < 1e-3f)
    return r.fail(Reader::child(path, "target"), "must differ from position (no view direction)");
  const json* region = nullptr;
  return r.member(j, path, "region", true, region) &&
         read_rect(r, *region, Reader::child(path, "region"), camera.region);
}

bool read_npc(Reader& r, const json& j, const std::string& path, NpcSpawn& npc) {
  float heading_deg = 0.0f;
  if (!r.require_object(j, path) ||
      !r.check_keys(j, path, {"name", "kind", "pos", "heading_deg"}) ||
      !r.optional_string(j, path, "name", npc.name) ||
      !r.required_string(j, path, "kind", npc.kind) ||
      !r.required_vec2(j, path, "pos", kMaxSceneCoord_m, npc.pos_m) ||
      !r.required_number(j, path, "heading_deg", -kMaxHeadingDeg, kMaxHeadingDeg, heading_deg))
    return false;
  if (npc.kind.empty()) return r.fail(Reader::child(path, "kind"), "must not be empty");
  npc.heading_rad = wrap_angle(radians(heading_deg));
  return true;
}

bool read_scene(Reader& r, const json& root, Scene& scene) {
  const std::string path;  // The root's path is empty; children are "name", "boxes[3]", ...
  if (!root.is_object())
    return r.fail("(root)", "expected a JSON object, got " + json_describe(root));
  if (!r.check_keys(root, "(root)",  // a path of its own: fail() drops an empty one
                    {"format", "version", "name", "bounds", "boxes", "terrain", "spawns", "goals",
                     "cameras", "npcs"}))
    return false;
  std::string format;
  if (!r.optional_string(root, path, "format", format)) return false;
  if (!format.empty() && format != "foresight-scene")
    return r.fail("format", "expected \"foresight-scene\", got \"" + format + "\"");
  float version = 1.0f;
  if (!r.optional_number(root, path, "version", 1.0, 1.0, version)) return false;

  if (!r.required_string(root, path, "name", scene.name)) return false;
  if (scene.name.empty()) return r.fail("name", "must not be empty");

  const json* bounds = nullptr;
  if (!r.member(root, path, "bounds", true, bounds) ||
      !read_rect(r, *bounds, "bounds", scene.bounds))
    return false;

  if (!r.array_of(root, path, "boxes", kMaxSceneBoxes, scene.boxes, read_box)) return false;
  const json* terrain = nullptr;
  if (!r.member(root, path, "terrain", false, terrain)) return false;
  if (terrain != nullptr && !read_terrain(r, *terrain, "terrain", scene.terrain)) return false;

  const json* spawns = nullptr;
  if (!r.member(root, path, "spawns", true, spawns)) return false;
  if (!r.array_of(root, path, "spawns", kMaxScenePoints, scene.spawns, read_spawn)) return false;
  if (scene.spawns.empty()) return r.fail("spawns", "needs at least one spawn point");
  return r.array_of(root, path, "goals", kMaxScenePoints, scene.goals, read_goal) &&
         r.array_of(root, path, "cameras", kMaxSceneCameras, scene.cameras, read_camera) &&
         r.array_of(root, path, "npcs", kMaxScenePoints, scene.npcs, read_npc);
}

bool parse_impl(std::string_view json_text, std::string_view source_name, Scene& scene,
                std::string& error) {
  json root;
  if (!json_io::parse(json_text, source_name, root, error)) return false;
  Scene parsed;
  Reader reader(source_name);
  if (!read_scene(reader, root, parsed)) {
    error = reader.error();
    return false;
  }
  if (!scene_validate(parsed, source_name, error)) return false;
  scene = std::move(parsed);
  return true;
}

}  // namespace

bool scene_parse(std::string_view json_text, std::string_view source_name, Scene& scene,
                 std::string& error) {
  return json_io::guarded(source_name, "scene", error, [&] {
    return parse_impl(json_text, source_name, scene, error);
  });
}

bool scene_load(const std::filesystem::path& path, Scene& scene, std::string& error) {
  std::string text;
  return text_file_read(path, kMaxSceneFileBytes, text, error) &&
         scene_parse(text, path.filename().string(), scene, error);
}

}  // namespace foresight
