#pragma once
// A scene: the static world avatars move in, as loaded from data/scenes/*.json (docs/SCENES.md).
//
// Units and axes follow math/types.hpp: metres, Y up, ground points (x, z) stored as vec2 {x, z},
// heading 0 faces +Z. Everything here is plain data; scene_load.hpp fills it and validates it,
// collision_world.hpp compiles it into the form the planner's hot loop reads.
#include "math/types.hpp"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace foresight {

/// Axis-aligned rectangle of the ground plane (closed): x in [min.x, max.x], z in [min.y, max.y].
struct GroundRect {
  vec2 min_m{0.0f};
  vec2 max_m{0.0f};

  bool contains(vec2 p) const {
    return p.x >= min_m.x && p.x <= max_m.x && p.y >= min_m.y && p.y <= max_m.y;
  }
  bool intersects(const GroundRect& o) const {
    return min_m.x <= o.max_m.x && o.min_m.x <= max_m.x && min_m.y <= o.max_m.y &&
           o.min_m.y <= max_m.y;
  }
  vec2 size_m() const { return max_m - min_m; }
};

/// What a box is, for rendering, bots and debugging. Collision treats every kind the same way:
/// only the box's extent matters (a table is simply a box whose bottom is above the floor).
enum class BoxKind : std::uint8_t {
  kWall,           ///< Full-height wall.
  kObstacle,       ///< Anything in the way (crate, barrier, pillar).
  kBeam,           ///< Overhead beam spanning a corridor; crouch under it if high enough.
  kTable,          ///< A table top: a slab above the floor.
  kDoorwayLintel,  ///< The wall above a (low) doorway opening.
  kShelf,          ///< Object at arm height, fixed to a wall.
  kProp,           ///< Decoration that still collides.
};

/// "wall", "obstacle", "beam", "table", "doorway-lintel", "shelf", "prop".
std::string_view box_kind_name(BoxKind kind);
/// Inverse of box_kind_name; false for an unknown name.
bool box_kind_from_name(std::string_view name, BoxKind& kind);
/// The accepted names, comma separated (for error messages and docs).
std::string_view box_kind_names();

struct SceneBox {
  std::string name;  ///< Optional (may be empty).
  BoxKind kind = BoxKind::kWall;
  vec3 min_m{0.0f};  ///< min < max on every axis (validated).
  vec3 max_m{0.0f};

  GroundRect ground_rect() const { return {ground(min_m), ground(max_m)}; }
};

/// Ground heights on a regular grid of cells. Cell (ix, iz) covers
/// x in [origin.x + ix * cell, origin.x + (ix + 1) * cell), z likewise, and has one constant height.
/// A NaN height is a hole: no ground there (a gap to stride over).
struct HeightField {
  vec2 origin_m{0.0f};  ///< Corner of cell (0, 0): the minimum x and z.
  float cell_m = 0.0f;
  int count_x = 0;
  int count_z = 0;
  std::vector<float> heights_m;  ///< Row-major: [iz * count_x + ix]; NaN = hole.

  bool empty() const { return count_x <= 0 || count_z <= 0; }
  GroundRect extent() const {
    return {origin_m, origin_m + vec2(static_cast<float>(count_x) * cell_m,
                                      static_cast<float>(count_z) * cell_m)};
  }
};

/// A block you stand on (a step, a platform): it raises the ground to its top wherever it is.
/// Not an obstacle for the body; the terrain rule (collision_world.hpp) decides what is too high.
struct StepBlock {
  std::string name;
  vec3 min_m{0.0f};
  vec3 max_m{0.0f};

  GroundRect ground_rect() const { return {ground(min_m), ground(max_m)}; }
};

/// The ground: the flat floor at floor_y_m everywhere in the bounds, replaced by the height
/// field where it covers (holes included), and raised to the top of any step block over a point.
struct Terrain {
  float floor_y_m = 0.0f;
  HeightField height_field;  ///< Empty when the scene has none.
  std::vector<StepBlock> steps;
};

struct SpawnPoint {
  std::string name;
  vec2 pos_m{0.0f};
  float heading_rad = 0.0f;
};

/// A destination for bots: reached within radius_m of pos_m.
struct GoalPoint {
  std::string name;
  vec2 pos_m{0.0f};
  float radius_m = 0.5f;
};

/// A designer-placed third-person camera: used while the avatar is inside `region`.
struct SceneCamera {
  std::string name;
  vec3 position_m{0.0f};
  vec3 target_m{0.0f};  ///< Look-at point.
  float fov_y_rad = 1.0f;  ///< Vertical field of view.
  GroundRect region;     ///< Ground-plane area this camera covers (non-empty).
};

struct NpcSpawn {
  std::string name;
  std::string kind;  ///< Free-form behaviour/appearance tag ("guard", "sparring-partner", ...).
  vec2 pos_m{0.0f};
  float heading_rad = 0.0f;
};

struct Scene {
  std::string name;
  GroundRect bounds;  ///< The world's ground extent; nothing stands outside it.
  std::vector<SceneBox> boxes;
  Terrain terrain;
  std::vector<SpawnPoint> spawns;  ///< At least one.
  std::vector<GoalPoint> goals;
  std::vector<SceneCamera> cameras;
  std::vector<NpcSpawn> npcs;
};

// Caps that keep a hostile or mistyped file from exhausting memory or time (validated on load).
inline constexpr std::size_t kMaxSceneBoxes = 100000;
inline constexpr std::size_t kMaxSceneSteps = 100000;
inline constexpr std::size_t kMaxScenePoints = 1024;  ///< Per list: spawns, goals, npcs.
inline constexpr std::size_t kMaxSceneCameras = 256;
inline constexpr int kMaxHeightFieldCount = 4096;  ///< Per axis.
inline constexpr float kMaxSceneCoord_m = 100000.0f;  ///< |coordinate| limit.
inline constexpr float kMaxSceneExtent_m = 2000.0f;   ///< Bounds size limit per axis.
/// A spawn/goal/NPC point is "inside a box" when the box overlaps the vertical segment from the
/// ground up to this height above it (a standing avatar).
inline constexpr float kSpawnClearance_m = 1.85f;

}  // namespace foresight
