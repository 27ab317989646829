#include "anim/author/locomotion_clips.hpp"

#include "graph/motion_graph.hpp"

#include <string>

namespace foresight::author {
namespace {

constexpr float frames_s(int frames) { return static_cast<float>(frames) / kFps; }

const GaitFamily& walk() { return gait_family(FamilyId::kWalk); }
const GaitFamily& run() { return gait_family(FamilyId::kRun); }
const GaitFamily& crouch() { return gait_family(FamilyId::kCrouchWalk); }

// Steady cycles of one family: straight or turning, at the family's stride.
LocomotionSpec steady(const std::string& name, uint32_t tags, const GaitFamily& f, int frames,
                      float turn_deg, const FootGeometry& g) {
  const float t = frames_s(frames);
  const float v = f.stride_m / t;
  return cycle_spec(name, tags, f.id, f.id, t, arc_end(f.stride_m, radians(turn_deg)), v, v, g);
}

void add_turns(std::vector<LocomotionSpec>& out, const std::string& prefix, uint32_t tags,
               const GaitFamily& f, int frames, float turn_deg, const FootGeometry& g) {
  const std::string deg = std::to_string(static_cast<int>(turn_deg));
  out.push_back(steady(prefix + "_turn_left_" + deg, tags | kTagTurn, f, frames, turn_deg, g));
  out.push_back(steady(prefix + "_turn_right_" + deg, tags | kTagTurn, f, frames, -turn_deg, g));
}

}  // namespace

std::vector<LocomotionSpec> default_locomotion_specs(const FootGeometry& g) {
  std::vector<LocomotionSpec> out;
  const FamilyId idle = FamilyId::kIdle, crouch_idle = FamilyId::kCrouchIdle;
  const uint32_t loco = kTagLocomotion, crouching = kTagLocomotion | kTagCrouch;

  // Standing.
  out.push_back(standing_spec("idle", kTagIdle, idle, frames_s(60), {0.012f, 0.025f, 0.0f, 2}, g));
  out.push_back(standing_spec("crouch_idle", kTagIdle | kTagCrouch, crouch_idle, frames_s(60),
                              {0.008f, 0.02f, 0.0f, 2}, g));

  // Walking: one cycle per clip (two steps), turns lay the footprints along an arc.
  out.push_back(steady("walk", loco, walk(), 30, 0.0f, g));
  {
    // Slow walk: same boundary stride, slower cadence (1.0 m/s).
    const float t = frames_s(42);
    out.push_back(cycle_spec("walk_slow", loco, FamilyId::kWalk, FamilyId::kWalk, t,
                             arc_end(walk().stride_m, 0.0f), 1.0f, 1.0f, g));
  }
  add_turns(out, "walk", loco, walk(), 30, 45.0f, g);
  add_turns(out, "walk", loco, walk(), 33, 90.0f, g);

  // Running (flight phase: the right foot is mid-air at the boundary).
  out.push_back(steady("run", loco | kTagRun, run(), 22, 0.0f, g));
  add_turns(out, "run", loco | kTagRun, run(), 22, 45.0f, g);

  // Crouch-walking.
  out.push_back(steady("crouch_walk", crouching, crouch(), 34, 0.0f, g));
  add_turns(out, "crouch_walk", crouching, crouch(), 34, 45.0f, g);

  // Walk <-> run: one cycle each, speeding up / slowing down.
  {
    CycleTiming up;
    up.left_lift = 0.5f;
    up.right_land = 0.52f;
    up.right_lift = 0.86f;
    out.push_back(cycle_spec("walk_to_run", loco | kTagRun, FamilyId::kWalk, FamilyId::kRun,
                             frames_s(24), arc_end(1.85f, 0.0f), walk().speed_mps(),
                             run().speed_mps(), g, up));
    CycleTiming down;
    down.left_lift = 0.377f;
    down.right_land = 0.5f;
    out.push_back(cycle_spec("run_to_walk", loco | kTagRun, FamilyId::kRun, FamilyId::kWalk,
                             frames_s(21), arc_end(1.5f, 0.0f), run().speed_mps(),
                             walk().speed_mps(), g, down));
  }
  // Walk <-> crouch-walk: one cycle each, sinking / rising while stepping.
  // Half-standing, so not kTagCrouch (that tag promises a low body in every frame).
  out.push_back(cycle_spec("walk_to_crouch_walk", loco, FamilyId::kWalk, FamilyId::kCrouchWalk,
                           frames_s(30), arc_end(1.05f, 0.0f), walk().speed_mps(),
                           crouch().speed_mps(), g));
  out.push_back(cycle_spec("crouch_walk_to_walk", loco, FamilyId::kCrouchWalk, FamilyId::kWalk,
                           frames_s(30), arc_end(1.05f, 0.0f), crouch().speed_mps(),
                           walk().speed_mps(), g));

  // Start / stop: idle <-> walk in two steps (right foot first when starting).
  {
    LocomotionSpec s = transition_spec("walk_start", loco, idle, FamilyId::kWalk, frames_s(36),
                                       arc_end(0.61f, 0.0f), 0.0f, walk().speed_mps(), g);
    set_step(s, kRight, 0.20f, 0.36f, 0.62f);
    set_step(s, kLeft, 0.55f, 0.78f, s.duration_s);
    out.push_back(s);
    LocomotionSpec e = transition_spec("walk_stop", loco, FamilyId::kWalk, idle, frames_s(36),
                                       arc_end(0.85f, 0.0f), walk().speed_mps(), 0.0f, g);
    set_step(e, kRight, -1.0f, -1.0f, 0.45f);
    set_step(e, kLeft, 0.50f, 0.65f, 0.95f);
    out.push_back(e);
  }
  // Crouch down / stand up: the feet stay, the body sinks or rises (in place: kTagIdle).
  {
    LocomotionSpec d = transition_spec("crouch_down", kTagIdle, idle, crouch_idle, frames_s(24),
                                       Placement{}, 0, 0, g);
    d.style_blend_end_s = d.duration_s;
    out.push_back(d);
    LocomotionSpec u = transition_spec("stand_up", kTagIdle, crouch_idle, idle, frames_s(24),
                                       Placement{}, 0, 0, g);
    u.style_blend_end_s = u.duration_s;
    out.push_back(u);
  }
  // Crouch-walk start / stop from the crouch idle.
  {
    LocomotionSpec s = transition_spec("crouch_walk_start", crouching, crouch_idle,
                                       FamilyId::kCrouchWalk, frames_s(39), arc_end(0.34f, 0.0f),
                                       0.0f, crouch().speed_mps(), g);
    set_step(s, kRight, 0.22f, 0.40f, 0.70f);
    set_step(s, kLeft, 0.65f, 0.85f, s.duration_s);
    out.push_back(s);
    LocomotionSpec e = transition_spec("crouch_walk_stop", crouching, FamilyId::kCrouchWalk,
                                       crouch_idle, frames_s(39), arc_end(0.45f, 0.0f),
                                       crouch().speed_mps(), 0.0f, g);
    set_step(e, kRight, -1.0f, -1.0f, 0.55f);
    set_step(e, kLeft, 0.60f, 0.75f, 1.05f);
    out.push_back(e);
  }
  // Side-steps from idle: the leading foot steps out, the other closes.
  for (int side = 0; side < 2; ++side) {
    const float m = side_sign(side);
    LocomotionSpec s = transition_spec(side == kLeft ? "side_step_left" : "side_step_right", loco,
                                       idle, idle, frames_s(33), {vec2(m * 0.30f, 0.0f), 0.0f}, 0,
                                       0, g);
    set_step(s, side, 0.04f, 0.20f, 0.45f);
    set_step(s, 1 - side, 0.50f, 0.66f, 0.85f);
    out.push_back(s);
  }
  return out;
}

}  // namespace foresight::author
