#include "author/locomotion_clips.hpp"

#include "author/standing_specs.hpp"
#include "author/step_spec.hpp"
#include "graph/motion_graph.hpp"

#include <array>
#include <cmath>
#include <string>

namespace foresight::author {
namespace {

// Every steering clip is one step (about half a second) and every standing loop 0.4 s, so the
// controller, which can only change motion at clip boundaries, never waits long for one. Clip
// names end in the stepping foot: walk_l is a left step, from a right-foot strike to a left one.

constexpr float frames_s(int frames) { return static_cast<float>(frames) / kFps; }

const char* suffix(int side) { return side == kLeft ? "_l" : "_r"; }

// The gaits, by their left-strike family.
constexpr FamilyId kWalk = FamilyId::kWalkL;
constexpr FamilyId kSlow = FamilyId::kSlowL;
constexpr FamilyId kRun = FamilyId::kRunL;
constexpr FamilyId kCrouchWalk = FamilyId::kCrouchWalkL;

float speed_of(FamilyId gait) { return gait_family(gait).speed_mps(); }

struct Turn {
  const char* name;  // "22" is 22.5 deg: four steps make a right angle
  float deg;
  int frames;
};

class Catalogue {
 public:
  explicit Catalogue(const FootGeometry& g) : g_(g) {}

  // A step of `side` from gait `from` (a strike of the other foot) to gait `to` (a strike of
  // this one); standing families stay as they are.
  void step(const std::string& name, uint32_t tags, int side, FamilyId from, FamilyId to,
            int frames, float turn_deg, float v0, float v1, StepTiming timing = {}) {
    out_.push_back(step_spec(name + suffix(side), tags, strike_family(from, 1 - side),
                             strike_family(to, side), frames_s(frames), radians(turn_deg), v0, v1,
                             g_, timing));
  }
  // Steady steps of one gait, straight and turning, on either foot.
  void steady(const std::string& prefix, uint32_t tags, FamilyId gait, int frames,
              std::initializer_list<Turn> turns) {
    for (int side = 0; side < 2; ++side) {
      step(prefix, tags, side, gait, gait, frames, 0.0f, kSteadySpeed, kSteadySpeed);
      for (const Turn& t : turns) {
        step(prefix + "_turn_left_" + t.name, tags | kTagTurn, side, gait, gait, t.frames, t.deg,
             kSteadySpeed, kSteadySpeed);
        step(prefix + "_turn_right_" + t.name, tags | kTagTurn, side, gait, gait, t.frames, -t.deg,
             kSteadySpeed, kSteadySpeed);
      }
    }
  }
  // Moving -> moving between two gaits, on either foot.
  void change(const std::string& name, uint32_t tags, FamilyId from, FamilyId to, int frames) {
    for (int side = 0; side < 2; ++side)
      step(name, tags, side, from, to, frames, 0.0f, speed_of(from), speed_of(to));
  }
  // Standing -> first step and last step -> standing, on either foot. The start's root sets off
  // at `start_speed` (m/s) rather than from rest.
  void start_stop(const std::string& prefix, uint32_t tags, FamilyId standing, FamilyId gait,
                  int start_frames, int stop_frames, StepTiming start, float start_speed) {
    for (int side = 0; side < 2; ++side) {
      step(prefix + "_start", tags, side, standing, gait, start_frames, 0.0f, start_speed,
           speed_of(gait), start);
      step(prefix + "_stop", tags, side, gait, standing, stop_frames, 0.0f, speed_of(gait), 0.0f);
    }
  }
  void add(const LocomotionSpec& spec) { out_.push_back(spec); }
  const FootGeometry& geometry() const { return g_; }
  std::vector<LocomotionSpec> take() { return std::move(out_); }

 private:
  const FootGeometry& g_;
  std::vector<LocomotionSpec> out_;
};

// Turns on the spot: each foot steps round on its spot of the turning root. A quarter turn is
// two steps (the foot on the turning side opens, the other closes); a half turn is four quarter
// steps, so the feet never pass each other.
void add_spot_turns(Catalogue& c, const std::string& prefix, uint32_t tags, FamilyId family) {
  const float accept_s = gait_family(family).style.weight_accept_s;
  for (int side = 0; side < 2; ++side) {
    const int other = 1 - side;
    const float open_land = 0.22f, close_land = 0.40f;
    const std::array<SpotStep, 2> steps = {SpotStep{side, 0.0f, 0.08f, open_land, 1.0f},
                                           SpotStep{other, 0.18f, 0.26f, close_land, 1.0f}};
    // Ends once the closing foot carries its weight (the standing boundary has both loaded).
    const int frames = static_cast<int>(std::ceil((close_land + accept_s) * kFps));
    c.add(spot_turn_spec(prefix + (side == kLeft ? "_turn_left_90" : "_turn_right_90"),
                         tags | kTagTurn, family, frames_s(frames),
                         side_sign(side) * radians(90.0f), steps, c.geometry()));
  }
}

}  // namespace

std::vector<LocomotionSpec> default_locomotion_specs(const FootGeometry& g) {
  Catalogue c(g);
  const FamilyId idle = FamilyId::kIdle, crouch_idle = FamilyId::kCrouchIdle;
  const uint32_t loco = kTagLocomotion, crouching = kTagLocomotion | kTagCrouch;

  // Standing loops, 0.4 s: held poses (a breath or a weight shift would have to repeat every
  // 0.4 s, which reads as trembling).
  c.add(standing_spec("idle", kTagIdle, idle, frames_s(12), {}, g));
  c.add(standing_spec("crouch_idle", kTagIdle | kTagCrouch, crouch_idle, frames_s(12), {}, g));

  // Walking: straight steps, and turns of 22.5 and 45 deg per step (a right angle is four or two
  // steps); the slow walk is its own gait with shorter strides.
  c.steady("walk", loco, kWalk, 15, {{"22", 22.5f, 15}, {"45", 45.0f, 16}});
  c.steady("walk_slow", loco, kSlow, 15, {});
  c.change("walk_to_slow", loco, kWalk, kSlow, 15);
  c.change("slow_to_walk", loco, kSlow, kWalk, 15);
  StepTiming walk_start;
  walk_start.heel_off_s = 0.0f;
  walk_start.lift_s = 0.15f;
  // The walk sets off at once at 0.5 m/s, as game characters do: from rest, its first frames
  // moved the pelvis mostly sideways (the weight going onto the stance foot), so a key pressed
  // from standing was followed only after 233-267 ms (the lab's response measure: the last 0.2 s
  // of travel within 30 deg of the key). The speed step at the switch from idle (17 mm/frame^2)
  // is far under the pop threshold; measured in docs/MOTION_QUALITY.md ("A start that sets off").
  // The stop takes 14 frames: in 12 its last step's swing (lift to landing, 0.25 s) snapped the
  // toe at 127 mm/frame^2, the library's largest locomotion acceleration, so nearly every stop
  // shown was a pop (docs/MOTION_QUALITY.md, "Pops at stops, steps and landings").
  c.start_stop("walk", loco, idle, kWalk, 15, 14, walk_start, 0.5f);

  // Running (flight phase: the other foot is in the air at every boundary).
  c.steady("run", loco | kTagRun, kRun, 11, {{"22", 22.5f, 11}});
  c.change("walk_to_run", loco | kTagRun, kWalk, kRun, 16);
  c.change("run_to_walk", loco | kTagRun, kRun, kWalk, 11);

  // Crouch-walking; sinking / rising while stepping is half standing, so not kTagCrouch (that tag
  // promises a low body in every frame).
  c.steady("crouch_walk", crouching, kCrouchWalk, 16, {{"22", 22.5f, 16}});
  c.change("walk_to_crouch_walk", loco, kWalk, kCrouchWalk, 16);
  c.change("crouch_walk_to_walk", loco, kCrouchWalk, kWalk, 16);
  StepTiming crouch_start;
  crouch_start.heel_off_s = 0.02f;
  crouch_start.lift_s = 0.16f;
  // Sets off at 0.5 m/s as the walk does: from rest, a crouched key press was followed only
  // after 300-333 ms (27 of the obstacles' 196 slow responses in 400 seeds; 4 at 0.5 m/s).
  c.start_stop("crouch_walk", crouching, crouch_idle, kCrouchWalk, 18, 18, crouch_start, 0.5f);

  // Crouch down / stand up: the feet stay, the body sinks or rises (in place: kTagIdle).
  {
    LocomotionSpec d = transition_spec("crouch_down", kTagIdle, idle, crouch_idle, frames_s(15),
                                       Placement{}, g);
    d.style_blend_end_s = d.duration_s;
    c.add(d);
    LocomotionSpec u = transition_spec("stand_up", kTagIdle, crouch_idle, idle, frames_s(15),
                                       Placement{}, g);
    u.style_blend_end_s = u.duration_s;
    c.add(u);
  }
  // Side-steps from idle: the leading foot steps out, the other closes. Each swing takes 0.14-0.16
  // s: in 0.1 s (a 13-frame clip) the knees and toes reached 112 mm/frame^2 of the library's 121
  // pop threshold, leaving root steering no room, and 9 of the 14 pops left in 800 closed-loop
  // runs were side steps (docs/MOTION_QUALITY.md, "Side steps with room to steer").
  for (int side = 0; side < 2; ++side) {
    const float m = side_sign(side);
    LocomotionSpec s = transition_spec(side == kLeft ? "side_step_left" : "side_step_right", loco,
                                       idle, idle, frames_s(15), {vec2(m * 0.27f, 0.0f), 0.0f}, g);
    set_step(s, side, 0.0f, 0.06f, 0.22f);
    set_step(s, 1 - side, 0.17f, 0.21f, 0.35f);
    c.add(s);
  }
  // A half step forward from idle (the leading foot steps, the other closes): a fighter's footwork
  // to close a gap shorter than a walk's first step (one stopped 1.3 m from its target, whose
  // walk would touch it, side-stepped on the spot without it). Players' trees leave it out.
  for (int side = 0; side < 2; ++side) {
    LocomotionSpec s = transition_spec(side == kLeft ? "step_forward_left" : "step_forward_right",
                                       loco | kTagFootwork, idle, idle, frames_s(16),
                                       {vec2(0.0f, 0.20f), 0.0f}, g);
    set_step(s, side, 0.0f, 0.07f, 0.17f);
    set_step(s, 1 - side, 0.12f, 0.15f, 0.25f);
    c.add(s);
  }
  // Turning on the spot (kTagTurn only: neither a hold nor travel).
  add_spot_turns(c, "idle", 0, idle);
  add_spot_turns(c, "crouch_idle", kTagCrouch, crouch_idle);
  {
    // The first foot lifts at 0.06 s, not 0.08: its swing's knee, shown through the pose stage,
    // sat on the pop threshold (docs/MOTION_QUALITY.md, "Side steps with room to steer").
    const std::array<SpotStep, 4> steps = {
        SpotStep{kLeft, 0.0f, 0.06f, 0.21f, 0.5f}, SpotStep{kRight, 0.15f, 0.21f, 0.34f, 0.5f},
        SpotStep{kLeft, 0.28f, 0.34f, 0.46f, 1.0f}, SpotStep{kRight, 0.41f, 0.46f, 0.59f, 1.0f}};
    c.add(spot_turn_spec("idle_turn_180", kTagTurn, idle, frames_s(21), kPi, steps, g));
  }
  return c.take();
}

}  // namespace foresight::author
