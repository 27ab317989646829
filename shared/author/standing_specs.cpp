#include "author/standing_specs.hpp"

#include "author/family_boundary.hpp"

#include <array>
#include <cassert>
#include <utility>

namespace foresight::author {

LocomotionSpec standing_spec(const std::string& name, uint32_t tags, FamilyId family,
                             float duration_s, StandingMotion motion, const FootGeometry& g) {
  LocomotionSpec spec;
  spec.name = name;
  spec.tags = tags;
  spec.duration_s = duration_s;
  spec.start_family = spec.end_family = family;
  spec.path = RootPath(duration_s, Placement{}, 0.0f, 0.0f);
  for (int side = 0; side < 2; ++side)
    spec.feet[side] = {boundary_key(gait_family(family), side, Placement{}, 0.0f, g)};
  spec.standing = motion;
  return spec;
}

LocomotionSpec transition_spec(const std::string& name, uint32_t tags, FamilyId start,
                               FamilyId end_family, float duration_s, Placement end,
                               const FootGeometry& g) {
  LocomotionSpec spec;
  spec.name = name;
  spec.tags = tags;
  spec.duration_s = duration_s;
  spec.start_family = start;
  spec.end_family = end_family;
  spec.style_blend_begin_s = 0.0f;
  spec.style_blend_end_s = 0.85f * duration_s;
  spec.path = RootPath(duration_s, end, 0.0f, 0.0f);
  for (int side = 0; side < 2; ++side)
    spec.feet[side] = {boundary_key(gait_family(start), side, Placement{}, 0.0f, g),
                       boundary_key(gait_family(end_family), side, end, duration_s, g)};
  return spec;
}

void set_step(LocomotionSpec& spec, int side, float heel_off_s, float lift_s, float land_s) {
  FootTimeline& keys = spec.feet[side];
  FootPlant& first = keys.front().plant;
  if (lift_s >= 0.0f) {
    first.lift_s = lift_s;
    first.heel_off_s = heel_off_s;
    first.lift_pitch_rad = style_at(spec, lift_s).lift_pitch_rad;
  }
  keys.back().plant.land_s = land_s;
}

LocomotionSpec spot_turn_spec(const std::string& name, uint32_t tags, FamilyId family,
                              float duration_s, float turn_rad, std::span<const SpotStep> steps,
                              const FootGeometry& g) {
  const GaitFamily& f = gait_family(family);
  assert(!f.moving);
  LocomotionSpec spec = standing_spec(name, tags, family, duration_s, {}, g);
  // Not wrapped: a half turn to the left is +pi, to the right -pi.
  spec.path = RootPath(duration_s, Placement{vec2(0.0f), turn_rad}, 0.0f, 0.0f);
  // The body turns with the feet: its heading is keyed to the mean of the two feet's turn at
  // every touch-down (both legs twist about equally), still until the first lift-off.
  assert(!steps.empty() && steps.front().lift_s > 0.0f && steps.back().land_s < duration_s);
  KeyTrack<float> heading;
  heading.key(0.0f, 0.0f).key(steps.front().lift_s, 0.0f, true);
  std::array<float, 2> done{0.0f, 0.0f};
  for (size_t i = 0; i < steps.size(); ++i) {
    done[steps[i].side] = steps[i].turn_fraction;
    heading.key(steps[i].land_s, turn_rad * 0.5f * (done[0] + done[1]), i + 1 == steps.size());
  }
  heading.key(duration_s, turn_rad);
  spec.path.set_heading(std::move(heading));
  for (const SpotStep& s : steps) {
    FootTimeline& keys = spec.feet[s.side];
    FootPlant& from = keys.back().plant;
    from.heel_off_s = s.heel_off_s;
    from.lift_s = s.lift_s;
    const Placement turned{vec2(0.0f), s.turn_fraction * turn_rad};
    FootPlant to = boundary_key(f, s.side, turned, 0.0f, g).plant;
    to.land_s = s.land_s;
    keys.push_back(plant_key(to));
  }
  return spec;
}

}  // namespace foresight::author
