#include "transport/scene_transfer.hpp"

#include "io/text_file.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <xxhash.h>

#include <filesystem>

namespace foresight::protocol {

uint64_t scene_file_hash(std::string_view bytes) { return XXH3_64bits(bytes.data(), bytes.size()); }

bool own_scene_file_matches(const std::string& own_path, const std::string& scene_name, uint64_t server_hash,
                            std::string& text) {
  text.clear();
  const std::filesystem::path path = own_path.empty() ? scene_path(scene_name) : std::filesystem::path(own_path);
  std::error_code ec;
  std::string error;
  if (!std::filesystem::exists(path, ec) || !text_file_read(path, kMaxSceneFileBytes, text, error)) {
    text.clear();
    return false;
  }
  return scene_file_hash(text) == server_hash;
}

void SceneDownload::start(uint64_t hash, uint32_t total) {
  hash_ = hash;
  total_ = total <= kMaxFetchedSceneBytes ? total : 0;
  bytes_.clear();
  bytes_.reserve(total_);
}

bool SceneDownload::add(const wire::ScenePart& part) {
  const auto* data = part.data();
  if (!started() || part.scene_hash() != hash_ || part.total() != total_ || data == nullptr ||
      part.offset() != bytes_.size() || data->size() > total_ - bytes_.size())
    return false;
  bytes_.append(reinterpret_cast<const char*>(data->data()), data->size());
  return true;
}

}  // namespace foresight::protocol
