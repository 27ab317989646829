#include "author/default_library.hpp"
#include "graph_build/declared_graph.hpp"
#include "library_build/library_compile.hpp"
#include "library_build/library_source.hpp"

#include <cstdio>
#include <cstdlib>

namespace foresight {

MotionLibrary motion_library_default() {
  author::DefaultLibrarySpec spec = author::build_default_library();
  MotionLibrarySource lib;
  lib.name = "default";
  lib.skeleton = std::move(spec.skeleton);
  for (author::AuthoredClip& c : spec.clips) {
    lib.clips.push_back(std::move(c.clip));
    lib.clip_tags.push_back(c.tags);
  }
  std::vector<DeclaredTransition> declared;
  for (const author::DeclaredTransition& t : spec.transitions)
    declared.push_back({t.from, t.to, t.blend_frames});
  std::string error;
  // The default library is project code: a failure here is a programming error, caught by tests.
  MotionLibrary compiled;
  if (!graph_from_declared(lib.clips, lib.clip_tags, declared, lib.graph, error) ||
      !motion_library_compile(std::move(lib), compiled, error)) {
    std::fprintf(stderr, "default motion library is broken: %s\n", error.c_str());
    std::abort();
  }
  return compiled;
}

}  // namespace foresight
