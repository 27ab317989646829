#pragma once
// The bodies the fighter benchmarks adapt strikes between: the default library (its strikes and
// their skeleton), the default morphology's limb model (the strikes' source) and the five fighter
// morphologies with theirs. Built once per run.
#include "anim/author/default_library.hpp"
#include "fighter/morphology.hpp"
#include "fighter/strike_adaptation.hpp"

#include <string>
#include <vector>

namespace foresight::bench {

struct FighterCast {
  author::DefaultLibrarySpec library = author::build_default_library();
  Morphology source = default_morphology();
  LimbModel source_model;
  std::vector<Morphology> morphs = default_morphologies();
  std::vector<LimbModel> models;
  std::string error;  ///< Non-empty when a limb model could not be built.

  FighterCast() {
    models.resize(morphs.size());
    bool ok = limb_model_for_morphology(source, source_model, error);
    for (size_t i = 0; ok && i < morphs.size(); ++i) ok = limb_model_for_morphology(morphs[i], models[i], error);
  }
};

}  // namespace foresight::bench
