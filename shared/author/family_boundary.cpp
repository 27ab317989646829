#include "author/family_boundary.hpp"

#include "author/rig.hpp"

#include <cassert>

namespace foresight::author {

FootPlant neutral_plant(const GaitFamily& f, int side, const Placement& root, float land_s,
                        float cycle_offset) {
  const float s = f.stance_fraction, c = f.cycle_s, d = f.stride_m;
  const float sign = side_sign(side);
  FootPlant p;
  const float ahead = d * (s * 0.5f + cycle_offset) + f.foot_forward_m;
  p.ankle_xz_m = root.apply(vec2(sign * f.step_width_m, ahead));
  p.yaw_rad = root.heading_rad + sign * f.toe_out_rad;
  p.land_s = land_s;
  p.lift_s = land_s + s * c;
  p.heel_off_s = p.lift_s - f.heel_off_fraction * c;
  p.lift_pitch_rad = f.style.lift_pitch_rad;
  return p;
}

FootPlant rear_plant(const GaitFamily& f, const Placement& root, float t) {
  assert(f.moving);
  return neutral_plant(f, 1 - f.lead_side, root, t - 0.5f * f.cycle_s, -0.5f);
}

FootKey boundary_key(const GaitFamily& f, int side, const Placement& root, float t,
                     const FootGeometry& g) {
  if (!f.moving) {
    FootPlant p;
    p.ankle_xz_m = root.apply(f.stand_ankle_m[side]);
    p.yaw_rad = root.heading_rad + f.stand_yaw_rad[side];
    p.lift_pitch_rad = f.style.lift_pitch_rad;
    return plant_key(p);
  }
  if (side == f.lead_side) return plant_key(neutral_plant(f, side, root, t, 0.0f));
  const FootPlant before = rear_plant(f, root, t);
  if (before.lift_s >= t) return plant_key(before);
  // Running: the foot is mid-air at the boundary, on its way to the next plant.
  const FootPlant next = neutral_plant(f, side, root, t + 0.5f * f.cycle_s, 0.5f);
  const float u = (t - before.lift_s) / (next.land_s - before.lift_s);
  return via_key(via_between(before, next, t, u, g, f.style.swing.ease_exponent));
}

Placement pinned_end(const GaitFamily& to, int side, const FootPlant& planted, float turn_rad,
                     const FootGeometry& g) {
  Placement end;
  if (!to.moving) {
    // Flat on its spot: the foot's yaw fixes the heading, its ankle the position.
    end.heading_rad = planted.yaw_rad - to.stand_yaw_rad[side];
    end.pos_m = planted.ankle_xz_m - rotate_ground(to.stand_ankle_m[side], end.heading_rad);
    return end;
  }
  end.heading_rad = turn_rad;
  const FootPlant rear = rear_plant(to, end, 0.0f);  // placed as if the end were at the origin
  if (rear.lift_s >= 0.0f) {
    // Still on the floor at the end boundary, heel up: the ball of the foot has not moved.
    end.pos_m = planted.ball_xz(g) - rear.ball_xz(g);
  } else {
    end.pos_m = planted.ankle_xz_m - rear.ankle_xz_m;
  }
  return end;
}

}  // namespace foresight::author
