#pragma once
// Avatars never walk through each other: every avatar's committed motion (the rest of the segment
// it is playing) is reserved ground, and at each decision an avatar may only take a segment whose
// every frame keeps clear of the others' reservations (docs/SERVER.md, "Avatars never overlap").
//
// Why this is enough: when an avatar commits to a segment, that segment is clear of every other
// avatar's remaining committed motion, whatever the timing (the check ignores time, so it is
// conservative). Each avatar's committed motion therefore stays clear of every other's, and since
// an avatar's body is always somewhere on its own committed motion, no two bodies overlap. A
// blocked avatar idles where it stands (inside its own reservation) or holds its pose.
// Reservations are rebuilt every tick and extended as avatars commit during the tick.
//
// Speed: at 1000 avatars every decision asks about a whole segment (30-60 frames) against the
// thousands of frames the others reserved. So each reservation is kept as a run (one add(): one
// owner's frames, their bounding box), the grid holds runs, and a frame pair is only compared
// when the candidate frame's disc reaches the run's box and the two frames' discs meet; the
// capsule test decides the rest. Every shortcut is a bound the capsules lie within, so the answer
// is the exhaustive one (tests/lookahead/reservations_test.cpp checks it against every pair).
//
// Memory: a fixed grid over the scene with per-cell run lists whose capacity is kept between
// ticks, so a tick allocates nothing once warm.
#include "library/motion_library.hpp"
#include "lookahead/motion_tree.hpp"
#include "world/scene.hpp"

#include <span>
#include <vector>

namespace foresight {

class Reservations {
 public:
  /// Covers `bounds` with cells of `cell_m`; `clearance_m` is kept between two bodies' footprints.
  void configure(const GroundRect& bounds, float cell_m = 1.0f, float clearance_m = 0.05f);
  void clear();
  /// Reserves frames [from_frame, end] of `segment` placed at `start` for avatar `owner`.
  void add(int owner, const MotionLibrary& library, int segment, int from_frame, const Placement& start);
  /// True when some frame of `segment` placed at `start` overlaps a footprint reserved by anyone
  /// but `self`.
  bool blocks(int self, const MotionLibrary& library, int segment, const Placement& start) const;

 private:
  /// One add(): frames [first, end) of bodies_, all `owner`'s, inside the box [lo, hi] (each
  /// frame's disc of reach about its centre).
  struct Run {
    vec2 lo_m, hi_m;
    int first, end;
    int owner;
  };
  /// A reserved frame: its placed volume (heights unused) and the radius of the disc about its
  /// centre that holds it.
  struct Reserved {
    BodyVolume volume;
    float reach_m;
  };
  int cell_along(float v, float origin, int count) const;
  int cell_x(float x) const { return cell_along(x, origin_m_.x, count_x_); }
  int cell_z(float z) const { return cell_along(z, origin_m_.y, count_z_); }
  static void place_frames(std::span<const BodyVolume> frames, size_t from, const Placement& start,
                           std::vector<Reserved>& out, vec2& lo, vec2& hi);
  /// Does any frame of `frames` (placed, with their reaches) come within the clearance of a frame
  /// of `run`?
  bool run_blocks(const Run& run, std::span<const Reserved> frames) const;

  vec2 origin_m_{0.0f};
  float cell_m_ = 1.0f;
  float clearance_m_ = 0.05f;
  int count_x_ = 1, count_z_ = 1;
  std::vector<Reserved> bodies_;
  std::vector<Run> runs_;
  std::vector<std::vector<int>> cells_;  ///< Indices into runs_ of the runs whose box touches the cell.
  std::vector<int> touched_;             ///< Cells with entries, for clear().
};

/// Reservations seen by one avatar, as a veto for LookaheadAvatar::step(). With a `stand_segment`
/// (the avatar's idle fallback), a segment is also vetoed when standing at its end would overlap
/// someone's reservation: an avatar then never walks so close to another that it can neither go
/// on nor stop (bodies as narrow as people let a walker reach a standing one mid-stride, where
/// only holding the pose was left).
class ReservationVeto final : public ChildVeto {
 public:
  ReservationVeto(const Reservations& r, const MotionLibrary& library, int self, int stand_segment = -1)
      : r_(r), library_(library), self_(self), stand_segment_(stand_segment) {}
  bool blocks(int segment, const Placement& start) const override {
    if (r_.blocks(self_, library_, segment, start)) return true;
    return stand_segment_ >= 0 &&
           r_.blocks(self_, library_, stand_segment_, start.compose(library_.segment_motion[segment].end));
  }

 private:
  const Reservations& r_;
  const MotionLibrary& library_;
  int self_;
  int stand_segment_;
};

}  // namespace foresight
