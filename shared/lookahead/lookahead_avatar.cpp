#include "lookahead/lookahead_avatar.hpp"

#include "anim/fk.hpp"
#include "lookahead/scene_path.hpp"

#include <algorithm>
#include <cmath>

namespace foresight {

int find_fallback_segment(const MotionLibrary& library, bool crouching) {
  int best = -1;
  float best_move = 0.0f;
  for (int s = 0; s < library.graph.num_segments(); ++s) {
    const uint32_t tags = library.graph.segments[s].tags;
    if (!(tags & kTagIdle) || (tags & kTagFight) || ((tags & kTagCrouch) != 0) != crouching) continue;
    const float move = glm::length(library.segment_motion[s].end.pos_m);
    if (best < 0 || move < best_move) best = s, best_move = move;
  }
  return best;
}

int find_spawn_segment(const MotionLibrary& library) {
  const int idle = find_fallback_segment(library);
  if (idle >= 0) return idle;
  int best = -1;
  float best_speed = 0.0f;
  for (int s = 0; s < library.graph.num_segments(); ++s) {
    const Segment& seg = library.graph.segments[s];
    if ((seg.tags & kTagFight) || seg.num_frames() <= 0) continue;
    const float speed = glm::length(library.segment_motion[s].end.pos_m) / static_cast<float>(seg.num_frames());
    if (best < 0 || speed < best_speed) best = s, best_speed = speed;
  }
  return best;
}

LookaheadAvatar::LookaheadAvatar(const MotionLibrary& library, const CollisionWorld& world,
                                 MotionTreeConfig config, int start_segment, const Placement& start)
    : library_(library),
      world_(world),
      tree_(library, world, std::move(config)),
      playback_{start_segment, 0, start, -1},
      fallback_segment_(find_fallback_segment(library)),
      crouch_fallback_segment_(find_fallback_segment(library, true)),
      body_clearance_m_(moving_body_clearance_m(library) - kMovingBodySteerRoom_m),
      body_height_m_(lowest_moving_body_m(library)) {
  tree_.reset(start_segment, start);
  // Per segment, once: is it a standing loop (a held pose that goes nowhere, every frame the
  // same: idle loops), and does it end standing (a standing loop may follow it: stops, side
  // steps, turns on the spot, the loops themselves)?
  const size_t n = static_cast<size_t>(library.graph.num_segments());
  standing_loop_.resize(n);
  ends_standing_.resize(n);
  for (size_t s = 0; s < n; ++s) {
    const Segment& seg = library.graph.segments[s];
    const SegmentMotion& m = library.segment_motion[s];
    standing_loop_[s] = (seg.tags & kTagIdle) && !(seg.tags & kTagTurn) && glm::length(m.end.pos_m) < 0.01f &&
                        std::abs(m.end.heading_rad) < 0.02f;
  }
  for (size_t s = 0; s < n; ++s)
    for (const Transition& t : library.graph.successors(static_cast<int>(s)))
      if (standing_loop_[static_cast<size_t>(t.to)]) ends_standing_[s] = 1;
  traps_.reserve(64);  // the root's children: a segment's successors (grows once for a bushier graph)
}

void LookaheadAvatar::set_input(const ControlInput& input) {
  if (control_input_valid(input)) {
    input_ = input;
  } else {
    input_ = ControlInput{};  // a broken command stops the avatar rather than steering it anywhere
    ++rejected_inputs_;
  }
  // A key released or turned away from the one the escape began under: the player steers again.
  const vec2 command = control_world_direction(input_);
  if (recovering() && !(glm::dot(command, command) > 1e-8f &&
                        glm::dot(glm::normalize(command), escape_command_) > kSameCommandCos)) {
    recover_s_ = -1.0f;
    watch_s_ = -1.0f;
  }
  tree_.set_command(steering_command(), root(), input_.crouch);
}

vec2 LookaheadAvatar::steering_command() const {
  return recovering() ? escape_ : control_world_direction(input_);
}

// Wedged: a direction held for kWedgedAfter_s and the root no kProgress_m from where it was
// (standing where nothing forward fits, or stepping left and right in place). If the scene has
// room ahead for the body, the avatar's placement is what blocks it (say, 15 cm off a narrow
// corridor's centre line, too close to a beam to crouch), so it backs off, the tree following an
// escape direction (back, then back-left, then back-right on later recoveries, so that each try
// comes in differently) until kBackOff_m or kEscapeMax_s, and tries again. A dead end in front
// of the held key is the player's choice: the avatar stands.
bool LookaheadAvatar::watch_progress() {
  const vec2 command = control_world_direction(input_);
  if (tree_.config().steer_rad_per_s <= 0.0f || glm::dot(command, command) < 1e-8f) {
    watch_s_ = -1.0f;
    return false;
  }
  const float fps = library_.clips[library_.graph.segments[playback_.segment].clip].fps;
  const float dt = 1.0f / (fps > 0.0f ? fps : 30.0f);
  const vec2 pos = root().pos_m;
  if (recovering()) {
    recover_s_ += dt;
    if (glm::length(pos - escape_from_) >= kBackOff_m || recover_s_ >= kEscapeMax_s) {
      recover_s_ = -1.0f;
      watch_s_ = -1.0f;
      tree_.set_command(command, root(), input_.crouch);
    }
    return false;
  }
  if (watch_s_ < 0.0f || glm::length(pos - watch_from_) > kProgress_m) {
    watch_from_ = pos;
    watch_s_ = 0.0f;
    return false;
  }
  watch_s_ += dt;
  if (watch_s_ < kWedgedAfter_s) return false;
  watch_s_ = 0.0f;  // a dead end is looked at again later: another avatar may have moved away
  if (!way_ahead_open(command)) return false;
  static constexpr float kEscapeTurns_rad[] = {0.0f, 0.785f, -0.785f};  // back, back-left, back-right
  escape_command_ = glm::normalize(command);
  escape_ = rotate_ground(-escape_command_, kEscapeTurns_rad[recoveries_ % 3]);
  escape_from_ = pos;
  recover_s_ = 0.0f;
  ++recoveries_;
  tree_.set_command(escape_, root(), input_.crouch);
  return true;
}

bool LookaheadAvatar::way_ahead_open(vec2 command) const {
  const vec2 pos = root().pos_m;
  const vec2 dir = glm::normalize(command);
  for (const float turn : {0.0f, 0.5f * kProbeSpread_rad, -0.5f * kProbeSpread_rad, kProbeSpread_rad, -kProbeSpread_rad})
    if (scene_segment_clear(world_, pos, pos + rotate_ground(dir, turn) * kProbe_m, body_clearance_m_, body_height_m_))
      return true;
  return false;
}

GrowResult LookaheadAvatar::grow(const GrowBudget& budget) { return tree_.grow(budget); }

bool LookaheadAvatar::steer(const ChildVeto* veto) {
  const vec2 command = steering_command();
  if (glm::dot(command, command) < 1e-8f || settle_frames_ > 0) return false;
  const Segment& seg = library_.graph.segments[playback_.segment];
  if (!(seg.tags & kTagLocomotion)) return false;
  const Placement now = root();
  const float want = std::atan2(command.x, command.y);  // heading convention: forward = (sin h, cos h)
  // Within 15 deg the clips' own turns do: steering there would regrow the tree every frame. The
  // root's heading sways a few degrees with each stride: measured from it, a key held 11 deg off
  // a corridor's axis was steered to at every sway and walked the avatar into the wall, where the
  // clips alone walk straight down the middle. So whether to steer is decided on the heading the
  // segment means to have (intended_heading); how far, on the root's.
  // But a turning clip's body faces 15-20 deg ahead of its path: once its heading was within the
  // dead zone the path was still about 30 deg off the key for 3-4 frames (most of the maze's slow
  // 90 deg turns). So the way the root goes over the next kSteerAheadFrames (a few frames' way
  // averages the stride's sway out) is steered onto the key too while it is kWayOff_rad or more
  // off. Steering on that way alone, with no heading rule, broke corridors, the stairs and
  // wedge recovery (tests Recovery.*Wedged, MotionQuality.UpTheStairs*, Lab.QuickClosedLoop*).
  const vec2 way = way_ahead();
  const bool going = glm::dot(way, way) > kSteerAheadMin_m * kSteerAheadMin_m;
  const float way_error = going ? wrap_angle(want - std::atan2(way.x, way.y)) : 0.0f;
  const bool way_off = std::abs(way_error) >= kWayOff_rad;
  if (!way_off && std::abs(wrap_angle(want - intended_heading())) < kWalkingDeadZone_rad) return false;
  const float error = way_off ? way_error : wrap_angle(want - now.heading_rad);
  // The heading rule turning against a way already near the key (the body faces past the key
  // while the path comes round to it) would turn the path away again, and the way rule back on
  // the next frame: left alone, the clip's own turn brings both round.
  if (!way_off && error * way_error < 0.0f && std::abs(way_error) > kWayNearKey_rad) return false;
  const float sideways = going ? std::abs(wrap_angle(std::atan2(way.x, way.y) - now.heading_rad)) : 0.0f;
  const float share = sideways > kSidewaysFrom_rad && sideways < kSidewaysTo_rad ? kSidewaysSteerShare : 1.0f;
  // No faster than the clip frames about this one leave room for: a turn must not push a joint
  // over the library's pop threshold (MotionLibrary::steer_limit_rad).
  const float step = std::min(frame_turn(share * tree_.config().steer_rad_per_s),
                              library_.steer_limit_at(seg.clip, seg.first_frame + playback_.frame));
  return rotate_playing(std::clamp(error, -step, step), veto, true);
}

vec2 LookaheadAvatar::way_ahead() const {
  const int frames = library_.graph.segments[playback_.segment].num_frames();
  const auto way_to = [&](int frame) {
    return motion_library_root_at(library_, playback_.segment, frame, playback_.segment_start).pos_m - root().pos_m;
  };
  const vec2 near = way_to(std::min(playback_.frame + kSteerAheadFrames, frames));
  if (glm::dot(near, near) >= kSteerAheadMin_m * kSteerAheadMin_m || playback_.frame >= kSteerAheadFrames) return near;
  // A move that sets off slowly (a side step shifting its weight before the root goes) has barely
  // begun over its first few frames: its way is where the segment ends. Taken as standing, those
  // frames were turned by the heading rule at the full rate, the body towards the key and the
  // step's way away from it. (Not at a stop's end, which slows down: steering its last
  // centimetres onto the key cost the captured fighters' strikes their hits, test
  // Bots.FightersOnCapturedLocomotionAndStrikesStrikeAndHit.)
  return way_to(frames);
}

// The playing segment's heading with its gait sway taken out: from its start's to its end's,
// in proportion to the frames played.
float LookaheadAvatar::intended_heading() const {
  const Placement& start = playback_.segment_start;
  const float turn = wrap_angle(start.compose(library_.segment_motion[playback_.segment].end).heading_rad - start.heading_rad);
  const int frames = library_.graph.segments[playback_.segment].num_frames();
  return start.heading_rad + turn * static_cast<float>(playback_.frame) / static_cast<float>(std::max(1, frames));
}

float LookaheadAvatar::frame_turn(float rad_per_s) const {
  const float fps = library_.clips[library_.graph.segments[playback_.segment].clip].fps;
  return rad_per_s / (fps > 0.0f ? fps : 30.0f);
}

Placement LookaheadAvatar::turned_start(float turn) const { return playback_turned_start(library_, playback_, turn); }

bool LookaheadAvatar::rotate_playing(float turn, const ChildVeto* veto, bool keep_way_on) {
  const Placement rotated = turned_start(turn);
  // The veto sees the whole rotated segment (conservative: its played frames too).
  if (!segment_feasible(world_, library_.segment_shapes[playback_.segment], rotated) ||
      (veto != nullptr && veto->blocks(playback_.segment, rotated)) ||
      (keep_way_on && !has_way_on(playback_.segment, rotated, kWayOnDepth)))
    return false;
  playback_.segment_start = rotated;
  tree_.reset(playback_.segment, rotated, playback_.incoming_transition);
  tree_.set_command(steering_command(), root(), input_.crouch);
  return true;
}

// A standing avatar whose tree finds nothing better than standing turns on the spot, as a person
// shuffles round to face a doorway: the library's turns on the spot are coarse (90 deg) and may
// not fit where it stands. It turns towards the heading nearest the command (within
// kFacingCone_rad of it) from which it can move on (has_way_on), e.g. square to a corridor when
// the key held points 11 deg into its wall. The target is searched once per stand and command.
bool LookaheadAvatar::turn_on_spot(const ChildVeto* veto) {
  if (settle_frames_ > 0) return false;  // a fallback's jump is still being shown (kFallbackSettle_s)
  const vec2 command = steering_command();
  if (glm::dot(command, command) < 1e-8f || !is_standing_loop(playback_.segment)) return false;
  const vec2 dir = glm::normalize(command);
  // The scene does not move: the search holds while the avatar stands where it was made (a stand
  // held for seconds, say waiting for another avatar to pass, searches once) and the key is the same.
  const vec2 here = root().pos_m;
  if (!facing_searched_ || glm::dot(dir, facing_for_) < kSameFacingCos || glm::length(here - facing_at_) > 0.02f ||
      facing_segment_ != playback_.segment) {
    facing_searched_ = true;
    facing_for_ = dir;
    facing_at_ = here;
    facing_segment_ = playback_.segment;
    has_facing_ = false;
    const Placement now = root();
    const float want = std::atan2(dir.x, dir.y);  // heading convention: forward = (sin h, cos h)
    for (float off = 0.0f; off <= kFacingCone_rad && !has_facing_; off += kFacingStep_rad)
      for (const float h : {want + off, want - off}) {
        const Placement at = turned_start(wrap_angle(h - now.heading_rad));
        if (segment_feasible(world_, library_.segment_shapes[playback_.segment], at) &&
            has_way_on(playback_.segment, at, kWayOnDepth)) {
          facing_ = h;
          has_facing_ = true;
          break;
        }
      }
  }
  if (!has_facing_) return false;
  const float error = wrap_angle(facing_ - root().heading_rad);
  if (std::abs(error) < kFacedWithin_rad) return false;
  const float step = frame_turn(std::min(tree_.config().steer_rad_per_s, kStandingTurn_rad_per_s));
  if (rotate_playing(std::clamp(error, -step, step), veto, false)) return true;
  has_facing_ = false;  // something stands in the way of the turn: stand
  return false;
}

// The tree only looks ahead of the placement it was grown for, so it cannot see what a rotation
// shuts off: a step steered towards a corner can leave nothing feasible but a stop, and then
// nothing but standing there for ever. A rotation is kept only if the rotated segment can still
// be followed the way it goes for `depth` more segments: a moving segment by one that keeps
// moving, a stop by one that is not a standing loop.
bool LookaheadAvatar::has_way_on(int segment, const Placement& start, int depth) const {
  const bool moving = !ends_standing_[static_cast<size_t>(segment)];
  const Placement end = start.compose(library_.segment_motion[segment].end);
  for (const Transition& t : library_.graph.successors(segment)) {
    if (library_.graph.segments[t.to].tags & tree_.config().excluded_tags) continue;
    if (moving ? ends_standing_[static_cast<size_t>(t.to)] != 0 : is_standing_loop(t.to)) continue;
    if (segment_feasible(world_, library_.segment_shapes[t.to], end) &&
        (depth <= 1 || has_way_on(t.to, end, depth - 1)))
      return true;
  }
  return false;
}

// What is left of the segment goes (almost) nowhere: a standing loop at any frame, a stop once
// its last foot is down and only the weight settles. Ending it here for a moving child shows a
// jump of at most this much, and a start no longer waits for the settling. The body's height
// counts too: a stand-up or crouch-down stays in place on the ground while the pelvis rises or
// sinks (left half way, the head jumped 22 cm in one shown frame).
bool LookaheadAvatar::may_end_early() const {
  const vec2 command = steering_command();
  if (playback_.frame <= 0 || glm::dot(command, command) < 1e-8f) return false;
  const Placement now = root();
  const Placement end = playback_next_start(library_, playback_);
  const Segment& seg = library_.graph.segments[playback_.segment];
  const Clip& clip = library_.clips[seg.clip];
  const int last = clip.num_frames - 1;
  const int end_frame = std::min(seg.end_frame, last), here_frame = std::min(seg.first_frame + playback_.frame, last);
  // From the frame shown last (this one is not, if the segment ends here).
  const float rise = clip.frame_pos(end_frame)[0].y - clip.frame_pos(std::min(seg.first_frame + playback_.frame - 1, last))[0].y;
  if (!(glm::length(end.pos_m - now.pos_m) < kEarlyEndMove_m && std::abs(rise) < kEarlyEndRise_m &&
        std::abs(wrap_angle(end.heading_rad - now.heading_rad)) < kEarlyEndTurn_rad))
    return false;
  // Nor may a limb skip more than that: the end's pose is shown in place of this frame's, so what
  // a joint moves between the two is added to its step in one frame and taken off on the next (a
  // slow walk's last frame moves the root under 2 cm and its swinging toe 5-18 cm: a pop).
  thread_local std::vector<vec3> here_pos, end_pos;  // the thread's scratch (capacity kept)
  thread_local std::vector<quat> rot;
  const size_t n = static_cast<size_t>(library_.num_joints());
  here_pos.resize(n), end_pos.resize(n), rot.resize(n);
  fk_pose(library_.skeleton, clip.frame_pos(here_frame), clip.frame_rot(here_frame), here_pos, rot);
  fk_pose(library_.skeleton, clip.frame_pos(end_frame), clip.frame_rot(end_frame), end_pos, rot);
  for (size_t j = 0; j < n; ++j)
    if (glm::length(end_pos[j] - here_pos[j]) >= kEarlyEndMove_m) return false;
  return true;
}

// A child is a trap when it moves the avatar somewhere from which, as far as the tree has looked
// (every node of the branch expanded, or at the depth cap), it can only stand still: a pocket of
// the scene where no motion but a standing loop fits. Taken, the avatar stands there for ever.
// A dead end (a node expanded with no feasible successor, not even a standing loop) leads nowhere
// either, and is worse: the avatar freezes on its last frame where not even idle fits (obstacles
// seed 1 froze for 100 s at the end of slow_to_walk_l, whose both successors were dead ends).
void LookaheadAvatar::find_traps() {
  traps_.clear();
  thread_local std::vector<int> visit;  // the thread's scratch stack (capacity kept)
  const MotionTree& t = tree_;
  for (int c = t.node(t.root()).first_child; c >= 0; c = t.node(c).next_sibling) {
    if (is_standing_loop(t.segment_of(c))) continue;  // standing where it is, not going anywhere
    bool trap = true;
    visit.clear();
    visit.push_back(c);
    while (trap && !visit.empty()) {
      const int i = visit.back();
      visit.pop_back();
      const MotionTreeNode& n = t.node(i);
      const bool dead_end = n.expanded && n.first_child < 0;
      if ((i != c && !dead_end && !is_standing_loop(t.segment_of(i))) || (!n.expanded && n.depth < t.config().max_depth))
        trap = false;
      for (int k = n.first_child; k >= 0; k = t.node(k).next_sibling) visit.push_back(k);
    }
    if (trap) traps_.push_back(t.segment_of(c));
  }
}

// Steering mode's choice, while a direction is held. The tree's look-ahead undervalues walking
// on: it places every future step unsteered, so a turn it sees as two wide turning steps, which
// the steering makes in a few frames, often loses the branch sum to stop, turn on the spot,
// start. So a moving avatar takes a child that ends standing only if no child that keeps moving
// is feasible; and no avatar walks into a trap (find_traps) while anything else is feasible.
// Nor does it take a turn on the spot while anything else is feasible: a standing avatar with a
// key held beside it sets off at once, its start steered round to the key within the clips' room,
// where a whole turn on the spot first (0.57 s for 90 deg) answered late (lab maze: 21 of the 25
// responses that began in one were over 250 ms). Where no start fits, it stands and turns its
// stand round to the key (turn_on_spot).
int LookaheadAvatar::select_child(const ChildVeto* veto) {
  const vec2 command = steering_command();
  if (tree_.config().steer_rad_per_s <= 0.0f || glm::dot(command, command) < 1e-8f) return tree_.select_child(veto);
  // Three choices from one ranking, each child's veto (every frame of it against the others'
  // reservations, on the server) asked at most once: this runs every frame for every standing
  // avatar with a key held.
  const std::span<const int> ranked = tree_.ranked_children();
  if (ranked.empty()) return -1;
  find_traps();
  const bool want_moving = !ends_standing_[static_cast<size_t>(playback_.segment)];
  int best = -1, moving = -1, free = -1;
  for (const bool spot_turns : {false, true}) {  // the turns on the spot only if nothing else is feasible
    if (best >= 0) break;
    for (const int c : ranked) {
      const int segment = tree_.segment_of(c);
      if (is_spot_turn(segment) != spot_turns) continue;
      const bool trap = std::find(traps_.begin(), traps_.end(), segment) != traps_.end();
      const bool could_move = want_moving && moving < 0 && !trap && !ends_standing_[static_cast<size_t>(segment)];
      const bool could_be_free = free < 0 && !trap;
      if (best >= 0 && !could_move && !could_be_free) continue;  // nothing left for it to answer
      if (veto != nullptr && veto->blocks(segment, tree_.start_of(c))) continue;
      if (best < 0) best = c;
      if (could_move) moving = c;
      if (could_be_free) free = c;
      if ((moving >= 0 || !want_moving) && free >= 0) break;
    }
  }
  if (moving >= 0) return moving;
  if (traps_.empty()) return best;
  return free >= 0 ? free : best;
}

AvatarStepResult LookaheadAvatar::step(const ChildVeto* veto) {
  AvatarStepResult result;
  result.recovery = watch_progress();
  ++playback_.frame;
  if (settle_frames_ > 0) --settle_frames_;
  int child = -1;
  if (!playback_at_end(library_, playback_)) {
    if (tree_.config().steer_rad_per_s <= 0.0f) return result;
    if (!may_end_early()) {
      result.steered = steer(veto);
      return result;
    }
    child = select_child(veto);
    if (child < 0 || (library_.graph.segments[tree_.segment_of(child)].tags & kTagIdle)) {
      result.steered = turn_on_spot(veto);  // nothing better than standing
      return result;
    }
    playback_.frame = library_.graph.segments[playback_.segment].num_frames();  // its end, now
  } else {
    child = select_child(veto);
  }

  result.segment_changed = true;
  // The naive baseline kept children unchecked: it finds out only now, and stops.
  const bool child_free =
      child >= 0 && (tree_.config().check_collisions ||
                     segment_feasible(world_, library_.segment_shapes[tree_.segment_of(child)],
                                      tree_.start_of(child)));
  if (child_free) {
    result.transition = tree_.advance_root(child);
    playback_take(library_, playback_, result.transition);
    return result;
  }
  // Nothing feasible ahead: idle where the segment ends, crouching if it was crouching (standing
  // up under a beam would pop the pose and leave it where it cannot crouch again), if that is
  // free. A segment may end where not even idle fits (a capture's dash ends a hand's width from
  // a box its narrower running body clears): held on its last frame, the avatar stood in that
  // pose for ever (obstacles, Bandai capture, 110 s). So the idle is tried back along the way
  // the avatar came (where its body just was: it stops short), then turned; the stage shows the
  // move as an inertialized jump. Only if no stand fits within kStandSearch_m does it hold
  // the last frame and look again from the same root next frame.
  result.fallback = true;
  ++fallbacks_;
  const Placement here = playback_next_start(library_, playback_);
  const bool crouching = (library_.graph.segments[playback_.segment].tags & kTagCrouch) != 0;
  const auto idle_fits = [&](int idle, const Placement& at) {
    return segment_feasible(world_, library_.segment_shapes[idle], at) &&
           (veto == nullptr || !veto->blocks(idle, at));
  };
  static constexpr float kTurns_rad[] = {0.0f, 0.785f, -0.785f, 1.571f, -1.571f, 3.142f};
  // Back the way the segment came, where its body just was: behind the facing for most motion,
  // but ahead of it for a walk backwards (searching behind that, into the wall it backed into,
  // the avatar froze there: a Bandai backward walk on the doorways, 100 s).
  const vec2 came = playback_.segment_start.pos_m - here.pos_m;
  const vec2 back = glm::length(came) > 0.01f ? glm::normalize(came) : rotate_ground(vec2(0.0f, -1.0f), here.heading_rad);
  for (const int idle : {crouching ? crouch_fallback_segment_ : -1, fallback_segment_}) {
    if (idle < 0) continue;
    for (const float turn : kTurns_rad)
      for (float d = 0.0f; d <= kStandSearch_m + 1e-4f; d += kStandSearchStep_m) {
        const Placement at{here.pos_m + back * d, wrap_angle(here.heading_rad + turn)};
        if (!idle_fits(idle, at)) continue;
        playback_ = {idle, 0, at, -1};
        tree_.reset(idle, at);
        const float fps = library_.clips[library_.graph.segments[idle].clip].fps;
        settle_frames_ = static_cast<int>(std::lround(kFallbackSettle_s * fps));
        return result;
      }
  }
  playback_.frame = library_.graph.segments[playback_.segment].num_frames() - 1;
  tree_.reset(playback_.segment, playback_.segment_start, playback_.incoming_transition);
  return result;
}

}  // namespace foresight
