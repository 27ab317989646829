#pragma once
// The default cast the fighter's offline tools adapt strikes between (benchmarks, figures, tests):
// the default library (its strikes and their skeleton), the default morphology's limb model (the
// strikes' source) and the five fighter morphologies with theirs. Built in one go (allocates).
#include "author/default_library.hpp"
#include "fighter/morphology.hpp"
#include "fighter/strike_adaptation.hpp"

#include <string>
#include <vector>

namespace foresight {

struct FighterCast {
  author::DefaultLibrarySpec library = author::build_default_library();
  Morphology source = default_morphology();
  LimbModel source_model;
  std::vector<Morphology> morphs = default_morphologies();
  std::vector<LimbModel> models;
  std::string error;  ///< Non-empty when a limb model could not be built.

  FighterCast();
  /// The default library's strike clip called `name`, or nullptr.
  const author::AuthoredClip* strike(const std::string& name) const;
  LimbCharacter source_character() const { return {&library.skeleton, &source_model}; }
  LimbCharacter fighter(size_t i) const { return {&morphs[i].skeleton, &models[i]}; }
  /// A request for a default strike, from its first frame to its last.
  StrikeRequest request(const author::AuthoredClip& c, const Placement& alignment, vec3 target) const;
};

}  // namespace foresight
