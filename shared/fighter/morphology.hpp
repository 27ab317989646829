#pragma once
// Fighter morphologies: the default skeleton with its bone groups scaled, so that one strike clip
// can be shown (and adapted) on characters whose height AND proportions differ (paper 3.5, Fig. 7:
// "not only the global size but also the proportions between the body segments are different").
//
// Bone groups (every bone offset in a group is multiplied by the group's factor, so bone
// directions never change and the default skeleton's joint frames stay valid):
//   legs       thigh, shin, and the foot (ankle -> ball -> toe tip, so the ankle and ball heights
//              above the floor scale with the legs)
//   arms       upper arm, forearm, hand
//   spine      pelvis -> spine -> chest -> neck, and the clavicle's rise
//   neck_head  neck -> head -> head top
//   width      clavicle -> shoulder joint and pelvis -> hip joint (shoulder and hip breadth)
// The pelvis rest height is recomputed so that the rest pose stands with its soles on the floor.
//
// The five shipped morphologies (height = head top in the rest pose; default skeleton 1.75 m):
//   | name        | legs | arms | spine | neck_head | width | height | what                          |
//   |-------------|------|------|-------|-----------|-------|--------|-------------------------------|
//   | stocky      | 0.76 | 0.92 | 1.05  | 1.00      | 1.30  | 1.57 m | short legs, broad, long trunk |
//   | tall        | 1.22 | 1.08 | 1.05  | 1.00      | 0.95  | 1.97 m | long-legged, slim             |
//   | long_arms   | 1.00 | 1.30 | 1.00  | 1.00      | 1.05  | 1.75 m | default height, long reach    |
//   | child       | 0.62 | 0.62 | 0.66  | 0.95      | 0.72  | 1.20 m | big head, short limbs         |
//   | heavy_torso | 0.90 | 0.95 | 1.25  | 1.05      | 1.30  | 1.81 m | long heavy torso, short legs  |
// (Heights as computed by make_morphology; morphology_test.cpp checks they differ by > 5 cm.)
#include "anim/skeleton.hpp"
#include "fighter/fighter_rig.hpp"

#include <array>
#include <string>
#include <vector>

namespace foresight {

struct MorphologyScales {
  float legs = 1.0f;
  float arms = 1.0f;
  float spine = 1.0f;
  float neck_head = 1.0f;
  float width = 1.0f;
};

struct MorphologySpec {
  const char* name;
  MorphologyScales scales;
};

inline constexpr int kNumMorphologies = 5;
/// The table above, in its order.
const std::array<MorphologySpec, kNumMorphologies>& morphology_specs();

struct Morphology {
  std::string name;
  MorphologyScales scales;
  Skeleton skeleton;   ///< The default skeleton, scaled; same joints, names and frames.
  FighterRig rig;
  float height_m = 0.0f;         ///< Head top above the floor in the rest pose.
  float ankle_height_m = 0.0f;   ///< Ankle above the floor with the foot flat.
  float ball_height_m = 0.0f;    ///< Ball of the foot (ToeBase) above the floor.
};

/// Scales the default skeleton's bone groups. Deterministic. Factors must be > 0.
Skeleton scale_default_skeleton(const MorphologyScales& scales);
/// One morphology (skeleton, rig, heights). Asserts the rig is found (it always is: same names).
Morphology make_morphology(const MorphologySpec& spec);
/// The five morphologies of morphology_specs(), in order.
std::vector<Morphology> default_morphologies();
/// The unscaled default skeleton as a Morphology named "default" (the library's own character).
Morphology default_morphology();

}  // namespace foresight
