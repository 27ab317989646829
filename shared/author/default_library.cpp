#include "author/default_library.hpp"

#include "author/default_skeleton.hpp"
#include "author/fight_moves.hpp"
#include "author/locomotion_clips.hpp"
#include "graph/motion_graph.hpp"

#include <cmath>

namespace foresight::author {
namespace {

// Grid the stored numbers are rounded to: 1e-5 m for positions, 1e-6 for quaternion components.
// Far below anything visible, and it makes the bytes independent of libm's last bits (except in
// the rare case a value falls exactly between two grid points).
constexpr double kPosGrid = 1e5;
constexpr double kRotGrid = 1e6;

float snap(float v, double grid) {
  return static_cast<float>(std::nearbyint(static_cast<double>(v) * grid) / grid);
}

void snap_clip(Clip& clip) {
  for (vec3& p : clip.local_pos_m)
    for (int i = 0; i < 3; ++i) p[i] = snap(p[i], kPosGrid);
  for (quat& q : clip.local_rot)
    for (int i = 0; i < 4; ++i) q[i] = snap(q[i], kRotGrid);
}

}  // namespace

DefaultLibrarySpec build_default_library() {
  DefaultLibrarySpec lib;
  lib.skeleton = default_skeleton();
  const Rig rig = rig_from_skeleton(lib.skeleton);
  const FootGeometry g = foot_geometry(rig);
  std::vector<ClipBoundaries> bounds;

  auto add_locomotion = [&](const LocomotionSpec& spec) {
    lib.clips.push_back({bake_locomotion(lib.skeleton, rig, spec), spec.tags, std::nullopt});
    bounds.push_back({spec.name, spec.start_family, spec.end_family, false});
  };
  for (const LocomotionSpec& spec : default_locomotion_specs(g)) add_locomotion(spec);
  add_locomotion(fight_stance_spec(g));
  add_locomotion(idle_to_stance_spec(g));
  add_locomotion(stance_to_idle_spec(g));

  for (const StrikeSpec& s : default_strikes()) {
    StrikeAnnotation a;
    a.hit_joint = s.kind == "kick" ? rig.leg[s.side].end : rig.arm[s.side].end;
    a.hit_frame = strike_hit_frame(s);
    a.kind = s.kind;
    a.side = s.side == kLeft ? "left" : "right";
    a.height = s.height;
    lib.clips.push_back({bake_strike(lib.skeleton, rig, g, s), kTagFight, a});
    bounds.push_back({s.name, FamilyId::kFight, FamilyId::kFight, true});
  }
  for (AuthoredClip& c : lib.clips) snap_clip(c.clip);
  lib.transitions = build_manifest(bounds);
  return lib;
}

}  // namespace foresight::author
