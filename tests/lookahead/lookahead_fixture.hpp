#pragma once
// The default library and the built-in scenes, loaded once per test binary.
#include "library_build/library_source.hpp"
#include "world/collision_world.hpp"
#include "world/data_paths.hpp"
#include "world/scene_load.hpp"

#include <gtest/gtest.h>

#include <map>

namespace foresight::test {

// Slow builds (sanitizers, Debug) get shorter replays so the suite stays fast there.
#if defined(__SANITIZE_ADDRESS__) || !defined(NDEBUG)
inline constexpr bool kSlowBuild = true;
#else
inline constexpr bool kSlowBuild = false;
#endif

inline const MotionLibrary& default_library() {
  static const MotionLibrary lib = motion_library_default();
  return lib;
}

struct LoadedScene {
  Scene scene;
  CollisionWorld world;
};

inline const LoadedScene& loaded_scene(const std::string& name) {
  static std::map<std::string, LoadedScene> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    LoadedScene s;
    std::string error;
    if (!scene_world_load(name, s.scene, s.world, error))
      ADD_FAILURE() << error;
    it = cache.emplace(name, std::move(s)).first;
  }
  return it->second;
}

/// The first idle segment (where avatars spawn).
inline int idle_segment(const MotionLibrary& lib) {
  for (int s = 0; s < lib.graph.num_segments(); ++s)
    if (lib.graph.segments[s].tags & kTagIdle) return s;
  return 0;
}

}  // namespace foresight::test
