#include "world/scene.hpp"

#include <array>
#include <utility>

namespace foresight {
namespace {

constexpr std::array<std::pair<BoxKind, std::string_view>, 7> kBoxKindNames{{
    {BoxKind::kWall, "wall"},
    {BoxKind::kObstacle, "obstacle"},
    {BoxKind::kBeam, "beam"},
    {BoxKind::kTable, "table"},
    {BoxKind::kDoorwayLintel, "doorway-lintel"},
    {BoxKind::kShelf, "shelf"},
    {BoxKind::kProp, "prop"},
}};

}  // namespace

std::string_view box_kind_name(BoxKind kind) {
  for (const auto& [k, name] : kBoxKindNames)
    if (k == kind) return name;
  return "unknown";
}

bool box_kind_from_name(std::string_view name, BoxKind& kind) {
  for (const auto& [k, n] : kBoxKindNames) {
    if (n == name) {
      kind = k;
      return true;
    }
  }
  return false;
}

std::string_view box_kind_names() {
  return "wall, obstacle, beam, table, doorway-lintel, shelf, prop";
}

}  // namespace foresight
