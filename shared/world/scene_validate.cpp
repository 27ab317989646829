// Semantic checks of a Scene (scene_load.hpp: scene_validate). The parser has already checked
// types and per-field ranges with precise JSON paths; these checks need the whole scene (a spawn
// inside a box, a camera looking at nothing) and also guard scenes built in code.
#include "io/json_reader.hpp"
#include "world/scene_load.hpp"
#include "world/terrain.hpp"

#include <cmath>
#include <exception>

namespace foresight {
namespace {

using json_io::Reader;

bool finite(vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string point_text(vec2 p) {
  return "(" + Reader::fmt(p.x) + ", " + Reader::fmt(p.y) + ")";
}

std::string box_text(const Scene& scene, std::size_t i) {
  const SceneBox& b = scene.boxes[i];
  std::string s = "boxes[" + std::to_string(i) + "]";
  if (!b.name.empty()) s += " \"" + b.name + "\"";
  return s + " (" + std::string(box_kind_name(b.kind)) + ")";
}

bool check_count(Reader& r, std::string_view path, std::size_t n, std::size_t max) {
  if (n <= max) return true;
  return r.fail(path, "has " + std::to_string(n) + " entries, more than the " +
                          std::to_string(max) + " allowed");
}

bool check_extent(Reader& r, const std::string& path, vec3 min, vec3 max) {
  if (!finite(min) || !finite(max)) return r.fail(path, "has a non-finite coordinate");
  return r.check_min_less_max(path + ".max", min, max);
}

/// A spawn-like point must be in the bounds, on ground, and not inside a box a standing avatar
/// would overlap there.
bool check_standing_point(Reader& r, const Scene& scene, const std::string& path, vec2 p) {
  const std::string pos_path = path + ".pos";
  if (!finite(p)) return r.fail(pos_path, "has a non-finite coordinate");
  if (!scene.bounds.contains(p))
    return r.fail(pos_path, point_text(p) + " is outside the bounds " +
                                point_text(scene.bounds.min_m) + " - " +
                                point_text(scene.bounds.max_m));
  float ground_y = 0.0f;
  if (!terrain_height_at(scene.terrain, p, ground_y))
    return r.fail(pos_path, point_text(p) + " has no ground (a height-field hole)");
  for (std::size_t i = 0; i < scene.boxes.size(); ++i) {
    const SceneBox& b = scene.boxes[i];
    if (b.ground_rect().contains(p) && b.min_m.y < ground_y + kSpawnClearance_m &&
        b.max_m.y > ground_y)
      return r.fail(pos_path, point_text(p) + " is inside " + box_text(scene, i));
  }
  return true;
}

bool validate(Reader& r, const Scene& scene) {
  if (scene.name.empty()) return r.fail("name", "must not be empty");

  const GroundRect& bounds = scene.bounds;
  if (!finite(bounds.min_m) || !finite(bounds.max_m))
    return r.fail("bounds", "has a non-finite coordinate");
  if (!r.check_min_less_max("bounds.max", bounds.min_m, bounds.max_m)) return false;
  const vec2 size = bounds.size_m();
  if (size.x > kMaxSceneExtent_m || size.y > kMaxSceneExtent_m)
    return r.fail("bounds", "size " + Reader::fmt(size.x) + " x " + Reader::fmt(size.y) +
                                " m exceeds " + Reader::fmt(kMaxSceneExtent_m) + " m");

  if (!check_count(r, "boxes", scene.boxes.size(), kMaxSceneBoxes) ||
      !check_count(r, "terrain.steps", scene.terrain.steps.size(), kMaxSceneSteps) ||
      !check_count(r, "spawns", scene.spawns.size(), kMaxScenePoints) ||
      !check_count(r, "goals", scene.goals.size(), kMaxScenePoints) ||
      !check_count(r, "cameras", scene.cameras.size(), kMaxSceneCameras) ||
      !check_count(r, "npcs", scene.npcs.size(), kMaxScenePoints))
    return false;

  for (std::size_t i = 0; i < scene.boxes.size(); ++i)
    if (!check_extent(r, "boxes[" + std::to_string(i) + "]", scene.boxes[i].min_m,
                      scene.boxes[i].max_m))
      return false;

  const Terrain& terrain = scene.terrain;
  if (!std::isfinite(terrain.floor_y_m)) return r.fail("terrain.floor_y", "is not finite");
  const HeightField& field = terrain.height_field;
  if (field.count_x != 0 || field.count_z != 0 || !field.heights_m.empty()) {
    const std::string fp = "terrain.height_field";
    if (field.count_x < 1 || field.count_z < 1 || field.count_x > kMaxHeightFieldCount ||
        field.count_z > kMaxHeightFieldCount)
      return r.fail(fp + ".count", "counts must be in [1, " +
                                       std::to_string(kMaxHeightFieldCount) + "]");
    if (!(field.cell_m > 0.0f) || !std::isfinite(field.cell_m))
      return r.fail(fp + ".cell", "must be a positive finite size");
    if (!finite(field.origin_m)) return r.fail(fp + ".origin", "has a non-finite coordinate");
    if (field.heights_m.size() != static_cast<std::size_t>(field.count_x) * field.count_z)
      return r.fail(fp + ".heights", "has " + std::to_string(field.heights_m.size()) +
                                         " values, expected count[0] * count[1]");
    for (float h : field.heights_m)
      if (std::isinf(h)) return r.fail(fp + ".heights", "has an infinite height");
  }
  for (std::size_t i = 0; i < terrain.steps.size(); ++i)
    if (!check_extent(r, "terrain.steps[" + std::to_string(i) + "]", terrain.steps[i].min_m,
                      terrain.steps[i].max_m))
      return false;

  if (scene.spawns.empty()) return r.fail("spawns", "needs at least one spawn point");
  for (std::size_t i = 0; i < scene.spawns.size(); ++i)
    if (!check_standing_point(r, scene, "spawns[" + std::to_string(i) + "]", scene.spawns[i].pos_m))
      return false;
  for (std::size_t i = 0; i < scene.goals.size(); ++i)
    if (!check_standing_point(r, scene, "goals[" + std::to_string(i) + "]", scene.goals[i].pos_m))
      return false;
  for (std::size_t i = 0; i < scene.npcs.size(); ++i)
    if (!check_standing_point(r, scene, "npcs[" + std::to_string(i) + "]", scene.npcs[i].pos_m))
      return false;

  for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
    const SceneCamera& cam = scene.cameras[i];
    const std::string cp = "cameras[" + std::to_string(i) + "]";
    if (!finite(cam.position_m) || !finite(cam.target_m) || !finite(cam.region.min_m) ||
        !finite(cam.region.max_m))
      return r.fail(cp, "has a non-finite coordinate");
    if (!(cam.fov_y_rad > 0.0f && cam.fov_y_rad < kPi))
      return r.fail(cp + ".fov_y_deg", "must be in (0, 180) degrees");
    if (!(glm::length(cam.target_m - cam.position_m) >= 1e-3f))
      return r.fail(cp + ".target", "must differ from position (no view direction)");
    if (!r.check_min_less_max(cp + ".region.max", cam.region.min_m, cam.region.max_m))
      return false;
    if (!cam.region.intersects(bounds))
      return r.fail(cp + ".region", "does not overlap the scene bounds");
  }
  return true;
}

}  // namespace

bool scene_validate(const Scene& scene, std::string_view source_name, std::string& error) {
  try {
    Reader reader(source_name);
    if (validate(reader, scene)) return true;
    error = reader.error();
  } catch (const std::exception& e) {  // Allocation failure while formatting a message.
    error = std::string(source_name) + ": " + e.what();
  }
  return false;
}

}  // namespace foresight
