#include "anim/author/default_skeleton.hpp"

namespace foresight::author {

Skeleton default_skeleton() {
  // Placeholder until the authoring code lands: a pelvis only.
  Skeleton s;
  s.joint_names = {"Hips"};
  s.parents = {kNoParent};
  s.rest_offsets_m = {vec3(0, 0.95f, 0)};
  s.is_end_site = {false};
  return s;
}

}  // namespace foresight::author
