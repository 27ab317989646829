#pragma once
// The compiled motion library: clips, motion graph, and everything the tick needs precomputed per
// segment (root placements, relative movement, body volumes, transition blend offsets). Built once
// at start-up (offline half), then shared read-only by server, client and bots (runtime half).
// Its content hash identifies it on the wire: a client whose library differs is refused.
#include "anim/pose.hpp"
#include "graph/motion_graph.hpp"
#include "world/body_volume.hpp"
#include "world/segment_shape.hpp"

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace foresight {

/// Where a segment starts and how it moves the avatar.
struct SegmentMotion {
  Placement start;  ///< Root placement of the segment's first frame, clip space.
  /// Placement of the end frame relative to `start`: the paper's relative movement r is
  /// `end.pos_m` (metres, in the segment's own frame: +Z forward, +X left); the heading change is
  /// `end.heading_rad`.
  Placement end;
};

/// What a builder fills at build time (library_build/): the skeleton, the clips and their tags,
/// the graph.
struct MotionLibrarySource {
  std::string name;
  Skeleton skeleton;
  std::vector<Clip> clips;
  std::vector<uint32_t> clip_tags;  ///< SegmentTag bits per clip.
  MotionGraph graph;
  float body_margin_m = 0.08f;      ///< Body cylinder grown sideways past the joints (flesh).

  int num_joints() const { return skeleton.num_joints(); }
};

/// The compiled library the runtime reads: its source, moved in as compiled, and the tables
/// derived from it. Made by motion_library_compile (library_build/library_compile.hpp) only;
/// every run-time function takes it const.
struct MotionLibrary : MotionLibrarySource {
  float head_top_margin_m = 0.15f;  ///< ... and above the highest joint (pose_check.hpp).
  std::vector<vec3> clip_forward_axis;   ///< Pelvis-local forward axis per clip.
  std::vector<int> clip_track_offset;    ///< Start of each clip's frames in root_track.
  std::vector<Placement> root_track;     ///< Root placement per clip frame, clip space.
  /// FootContactBit per clip frame (indexed like root_track): which parts of the feet the clip
  /// plants (foot_contact.hpp).
  std::vector<uint8_t> foot_contact;
  /// The farthest any joint moves between two frames of a clip (the pose stage's jump test).
  float max_joint_step_m = 0.0f;
  /// Per clip frame (indexed like root_track): its largest joint acceleration, m per frame^2
  /// (FK positions' second difference, root motion included; a clip's first and last frames take
  /// the next inner frame's)...
  std::vector<float> frame_acceleration_m;
  /// ...the value 99.9 % of the inner frames' stay under: a shown frame over it is a pop...
  float pop_threshold_m = 0.0f;
  /// ...and how far root steering may turn the motion on that frame, rad (the least over the frame
  /// and its neighbours, whose accelerations it changes; library_build/pop_budget.hpp).
  std::vector<float> steer_limit_rad;
  std::vector<SegmentMotion> segment_motion;
  /// Per segment: body volumes of frames [first_frame, end_frame] (end inclusive), in the
  /// segment's own frame (its start placement is the origin facing +Z), ready for
  /// segment_feasible().
  std::vector<SegmentCollisionShape> segment_shapes;
  /// Per transition, the offset that carries the successor's first pose onto the predecessor's end
  /// pose: [transition * num_joints + joint].
  std::vector<vec3> transition_offset_pos_m;
  std::vector<quat> transition_offset_rot;
  uint64_t content_hash = 0;

  Placement root_placement(int clip, int frame) const {
    return root_track[static_cast<size_t>(clip_track_offset[clip] + frame)];
  }
  uint8_t foot_contact_at(int clip, int frame) const {
    return foot_contact[static_cast<size_t>(clip_track_offset[clip] + frame)];
  }
  /// frame_acceleration_m and steer_limit_rad of a clip frame; a frame past either end of the
  /// clip reads the end's.
  float frame_acceleration_at(int clip, int frame) const { return frame_acceleration_m[clip_frame_index(clip, frame)]; }
  float steer_limit_at(int clip, int frame) const { return steer_limit_rad[clip_frame_index(clip, frame)]; }
  size_t clip_frame_index(int clip, int frame) const {
    return static_cast<size_t>(clip_track_offset[clip] + std::clamp(frame, 0, clips[clip].num_frames - 1));
  }
  std::span<const BodyVolume> volumes(int segment) const { return segment_shapes[segment].frames; }
  /// Index of a transition from -> to, or -1.
  int find_transition(int from, int to) const;
};

/// The pose of `frame` (0-based, within [0, num_frames]) of `segment`, whose start is placed at
/// `segment_start` in the world. `incoming_transition` (or -1) is the transition the segment was
/// entered by: its offset is blended out over the transition's blend frames.
/// Pelvis in world space, other joints parent-relative. No allocation once `out` is sized.
void motion_library_sample(const MotionLibrary& library, int segment, int frame,
                           const Placement& segment_start, int incoming_transition, Pose& out);

/// How much room a segment's body needs: the widest footprint across its long axis (2 x radius),
/// the longest along it, the tallest frame above its feet. What a level designer compares with
/// doorways, gaps and beams (docs/SCENES.md).
struct SegmentBody {
  float width_m = 0.0f;
  float length_m = 0.0f;
  float height_m = 0.0f;
};
SegmentBody segment_body(const MotionLibrary& library, int segment);

inline constexpr float kStandingHeight_m = 1.85f;  ///< Walking body height (docs/SCENES.md).
/// Room a route leaves beside the library's walker to steer in (moving_body_clearance_m).
inline constexpr float kMovingBodySteerRoom_m = 0.03f;

/// The lowest body the library moves in: the minimum over locomotion segments of the highest
/// point of their collision volumes (crouch-walking for the default library). 1.85 m when the
/// library has no locomotion.
float lowest_moving_body_m(const MotionLibrary& library);

/// The clearance a route needs for the library's walkers: half the median width of its
/// locomotion segments' bodies (segment_body) plus 3 cm of room to steer (the look-ahead checks
/// every motion exactly: only those that fit are taken); 0.35 m for a library with no locomotion.
float moving_body_clearance_m(const MotionLibrary& library);


/// World placement of the root at `frame` of a segment placed at `segment_start`.
Placement motion_library_root_at(const MotionLibrary& library, int segment, int frame,
                                 const Placement& segment_start);

}  // namespace foresight
