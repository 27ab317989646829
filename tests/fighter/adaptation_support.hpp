#pragma once
// Shared by the adaptation tests: the default library's strikes, the morphologies and their models.
#include "anim/author/default_library.hpp"
#include "fighter/morphology.hpp"
#include "fighter/strike_adaptation.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace foresight::test {

struct FighterCast {
  author::DefaultLibrarySpec library = author::build_default_library();
  Morphology source = default_morphology();
  LimbModel source_model;
  std::vector<Morphology> morphs = default_morphologies();
  std::vector<LimbModel> models;

  FighterCast() {
    std::string error;
    EXPECT_TRUE(limb_model_for_morphology(source, source_model, error)) << error;
    models.resize(morphs.size());
    for (size_t i = 0; i < morphs.size(); ++i) EXPECT_TRUE(limb_model_for_morphology(morphs[i], models[i], error)) << error;
  }
  const author::AuthoredClip* strike(const std::string& name) const {
    for (const author::AuthoredClip& c : library.clips)
      if (c.clip.name == name && c.strike) return &c;
    return nullptr;
  }
  LimbCharacter source_character() const { return {&library.skeleton, &source_model}; }
  LimbCharacter fighter(size_t i) const { return {&morphs[i].skeleton, &models[i]}; }
  /// A request for a default strike, from its first frame to its last.
  StrikeRequest request(const author::AuthoredClip& c, const Placement& alignment, vec3 target) const {
    StrikeRequest r;
    r.source = source_character();
    r.clip = &c.clip;
    r.start_frame = 0;
    r.hit_frame = c.strike->hit_frame;
    r.kick = c.strike->kind == "kick";
    r.side = c.strike->side == "left" ? kFighterLeft : kFighterRight;
    r.alignment = alignment;
    r.target_m = target;
    return r;
  }
};

inline bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace foresight::test
