#include "world/data_paths.hpp"

#include <cstdlib>

namespace foresight {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("FORESIGHT_DATA"); env && *env) return env;
  return FORESIGHT_DATA_DIR;
}

std::filesystem::path scene_path(std::string_view name_or_path) {
  const bool is_path = name_or_path.find('/') != std::string_view::npos ||
                       (name_or_path.size() > 5 && name_or_path.substr(name_or_path.size() - 5) == ".json");
  if (is_path) return std::filesystem::path(name_or_path);
  return data_dir() / "scenes" / (std::string(name_or_path) + ".json");
}

}  // namespace foresight
