#include "fighter_build/fighter_cast.hpp"

namespace foresight {

FighterCast::FighterCast() {
  models.resize(morphs.size());
  bool ok = limb_model_for_morphology(source, source_model, error);
  for (size_t i = 0; ok && i < morphs.size(); ++i) ok = limb_model_for_morphology(morphs[i], models[i], error);
}

const author::AuthoredClip* FighterCast::strike(const std::string& name) const {
  for (const author::AuthoredClip& c : library.clips)
    if (c.clip.name == name && c.strike) return &c;
  return nullptr;
}

StrikeRequest FighterCast::request(const author::AuthoredClip& c, const Placement& alignment, vec3 target) const {
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

}  // namespace foresight
