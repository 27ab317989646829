// libFuzzer: any text through the scene loader (world/scene_load.hpp: JSON, every field checked,
// then the semantic checks) and, when it loads, the collision world built from it.
#include "world/collision_world.hpp"
#include "world/scene_load.hpp"

#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  foresight::Scene scene;
  std::string error;
  if (!foresight::scene_parse(text, "fuzz.json", scene, error)) return 0;
  if (!foresight::scene_validate(scene, "fuzz.json", error)) std::abort();  // parse promised it
  foresight::CollisionWorld world;
  foresight::collision_world_build(scene, world, error);
  return 0;
}
