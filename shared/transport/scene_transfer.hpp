#pragma once
// The scene travels with the session (docs/PROTOCOL.md, "Scenes"): the Accept names the server's
// scene and carries the hash and size of its file; a client whose own file under that name (or
// the one it was given) has another hash fetches the server's, part by part, over the sealed
// session. A name clash can then never show or check the wrong scene, and a scene given to the
// server by path plays on clients that never had the file.
#include "foresight_generated.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace foresight::protocol {

/// Bytes of the scene file per ScenePart (a sealed part stays well under kMaxDatagramBytes).
inline constexpr uint32_t kScenePartBytes = 1000;
/// Largest scene a client fetches (the scene loader's own cap is larger; a bigger one must be
/// installed on the client).
inline constexpr uint32_t kMaxFetchedSceneBytes = 4u << 20;

/// XXH3-64 of a scene file's bytes: what Accept.scene_hash carries.
uint64_t scene_file_hash(std::string_view bytes);

/// The scene file a client would use for the server's scene without fetching it: `own_path`
/// (--scene) when given, else data/scenes/<scene_name>.json; `text` empty when there is none.
/// True when its bytes hash to `server_hash` (the Accept's): it is the server's scene.
bool own_scene_file_matches(const std::string& own_path, const std::string& scene_name, uint64_t server_hash,
                            std::string& text);

/// The client's copy of the server's scene file, assembled from ScenePart messages in order.
class SceneDownload {
 public:
  /// Expects a file of `total` bytes hashing to `hash` (from the Accept); forgets any parts.
  void start(uint64_t hash, uint32_t total);
  /// Appends a part that continues the bytes received so far; other parts (another hash, an
  /// offset already had or beyond, too long) are ignored: false.
  bool add(const wire::ScenePart& part);
  bool started() const { return total_ > 0; }
  bool complete() const { return started() && bytes_.size() == total_; }
  /// Complete and hashing to the Accept's hash.
  bool verified() const { return complete() && scene_file_hash(bytes_) == hash_; }
  uint32_t next_offset() const { return static_cast<uint32_t>(bytes_.size()); }
  const std::string& bytes() const { return bytes_; }
  uint64_t hash() const { return hash_; }

 private:
  uint64_t hash_ = 0;
  uint32_t total_ = 0;
  std::string bytes_;
};

}  // namespace foresight::protocol
