#include "author/step_spec.hpp"

#include "author/family_boundary.hpp"

#include <cassert>
#include <cmath>

namespace foresight::author {

int stepping_side(FamilyId from, FamilyId to) {
  const GaitFamily& fa = gait_family(from);
  const GaitFamily& fb = gait_family(to);
  return fb.moving ? fb.lead_side : 1 - fa.lead_side;
}

LocomotionSpec step_spec(const std::string& name, uint32_t tags, FamilyId from, FamilyId to,
                         float duration_s, float turn_rad, float start_speed_mps,
                         float end_speed_mps, const FootGeometry& g, StepTiming timing) {
  const GaitFamily& fa = gait_family(from);
  const GaitFamily& fb = gait_family(to);
  assert(fa.moving || fb.moving);
  const int stepping = stepping_side(from, to);
  const int stance = 1 - stepping;
  assert(!fa.moving || fa.lead_side == stance);
  const float T = duration_s;

  LocomotionSpec spec;
  spec.name = name;
  spec.tags = tags;
  spec.duration_s = T;
  spec.start_family = from;
  spec.end_family = to;
  // Between moving families the style blends over the whole step (zero slope at both ends, so a
  // chain of steps changes style smoothly); starts and stops settle a little before the end.
  spec.style_blend_begin_s = 0.0f;
  spec.style_blend_end_s = fa.moving && fb.moving ? T : 0.85f * T;

  // The stance foot: its start plant, kept to the end.
  FootKey stance_key = boundary_key(fa, stance, Placement{}, 0.0f, g);
  FootPlant& planted = stance_key.plant;
  const Placement end = pinned_end(fb, stance, planted, turn_rad, g);
  if (start_speed_mps < 0.0f) {
    // Steady: the arc through both placements, walked at an even pace.
    const float half = 0.5f * std::abs(end.heading_rad);
    const float chord = glm::length(end.pos_m);
    start_speed_mps = end_speed_mps = (half > 1e-4f ? chord * half / std::sin(half) : chord) / T;
  }
  spec.path = RootPath(T, end, start_speed_mps, end_speed_mps);
  if (!fb.moving) {
    planted.heel_off_s = planted.lift_s = kOpenFutureS;
    spec.feet[stance] = {stance_key};
  } else {
    // It becomes the end family's rear foot: its heel rolls and it lifts on that family's clock.
    const FootPlant rear = rear_plant(fb, end, T);
    planted.heel_off_s = rear.heel_off_s;
    planted.lift_s = rear.lift_s;
    planted.lift_pitch_rad = rear.lift_pitch_rad;
    const FootKey end_key = boundary_key(fb, stance, end, T, g);
    if (end_key.is_via) {
      spec.feet[stance] = {stance_key, end_key};  // Runs: in the air at the end.
    } else {
      // Walks: still on its ball at the end, turned to the end family's yaw.
      planted.pivot_rad = wrap_angle(rear.yaw_rad - planted.yaw_rad);
      planted.pivot_end_s = T;
      spec.feet[stance] = {stance_key};
    }
  }

  // The stepping foot: from its start state to its end footprint.
  FootKey first = boundary_key(fa, stepping, Placement{}, 0.0f, g);
  FootKey last = boundary_key(fb, stepping, end, T, g);
  if (!fa.moving) {
    first.plant.heel_off_s = timing.heel_off_s;
    first.plant.lift_s = timing.lift_s;
    first.plant.lift_pitch_rad = style_at(spec, timing.lift_s).lift_pitch_rad;
  }
  if (!fb.moving)
    last.plant.land_s = timing.land_s >= 0.0f ? timing.land_s : T - fb.style.weight_accept_s;
  spec.feet[stepping] = {first, last};
  return spec;
}

}  // namespace foresight::author
