#include "library_build/library_compile.hpp"

#include "anim/fk.hpp"
#include "anim/root_motion.hpp"
#include "library/foot_contact.hpp"
#include "library/pose_check.hpp"
#include "library_build/pop_budget.hpp"

#include <xxhash.h>

#include <algorithm>
#include <type_traits>

namespace foresight {
namespace {

// Hash of everything that decides what a client would rebuild from (segment, frame, placement):
// skeleton, clip arrays, graph. Compiled data is derived from these, so it is not hashed.
class Hasher {
 public:
  Hasher() : state_(XXH3_createState()) { XXH3_64bits_reset(state_); }
  ~Hasher() { XXH3_freeState(state_); }
  Hasher(const Hasher&) = delete;
  Hasher& operator=(const Hasher&) = delete;

  template <typename T>
  void add(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    XXH3_64bits_update(state_, &value, sizeof(T));
  }
  template <typename T>
  void add_array(const std::vector<T>& values) {
    add(values.size());
    if (!values.empty()) XXH3_64bits_update(state_, values.data(), values.size() * sizeof(T));
  }
  void add_string(const std::string& s) {
    add(s.size());
    XXH3_64bits_update(state_, s.data(), s.size());
  }
  uint64_t digest() const { return XXH3_64bits_digest(state_); }

 private:
  XXH3_state_t* state_;
};

uint64_t content_hash_of(const MotionLibrary& lib) {
  Hasher h;
  for (const std::string& n : lib.skeleton.joint_names) h.add_string(n);
  h.add_array(lib.skeleton.parents);
  h.add_array(lib.skeleton.rest_offsets_m);
  for (const Clip& c : lib.clips) {
    h.add_string(c.name);
    h.add(c.fps);
    h.add(c.num_frames);
    h.add_array(c.local_pos_m);
    h.add_array(c.local_rot);
  }
  h.add_array(lib.clip_tags);
  for (const Segment& s : lib.graph.segments) {
    h.add_string(s.name);
    h.add(s.clip);
    h.add(s.first_frame);
    h.add(s.end_frame);
    h.add(s.tags);
  }
  for (const Transition& t : lib.graph.transitions) {
    h.add(t.from);
    h.add(t.to);
    h.add(t.blend_frames);
  }
  return h.digest();
}

bool validate(const MotionLibrarySource& lib, std::string& error) {
  const int n = lib.skeleton.num_joints();
  if (!lib.skeleton.valid()) return error = lib.name + ": invalid skeleton", false;
  if (lib.clip_tags.size() != lib.clips.size())
    return error = lib.name + ": clip_tags has " + std::to_string(lib.clip_tags.size()) +
                   " entries for " + std::to_string(lib.clips.size()) + " clips",
           false;
  for (const Clip& c : lib.clips) {
    const size_t expected = static_cast<size_t>(c.num_frames) * static_cast<size_t>(n);
    if (c.num_joints != n || c.local_pos_m.size() != expected || c.local_rot.size() != expected)
      return error = lib.name + ": clip '" + c.name + "' does not match the skeleton", false;
    if (c.num_frames < 2) return error = lib.name + ": clip '" + c.name + "' has < 2 frames", false;
  }
  const int num_segments = lib.graph.num_segments();
  if (lib.graph.first_transition.size() != static_cast<size_t>(num_segments) + 1)
    return error = lib.name + ": graph not finalized", false;
  for (const Segment& s : lib.graph.segments) {
    if (s.clip < 0 || s.clip >= static_cast<int>(lib.clips.size()))
      return error = lib.name + ": segment '" + s.name + "' names clip " + std::to_string(s.clip),
             false;
    // end_frame is the boundary pose, so it must exist in the clip.
    if (s.first_frame < 0 || s.end_frame <= s.first_frame || s.end_frame >= lib.clips[s.clip].num_frames)
      return error = lib.name + ": segment '" + s.name + "' frame range [" +
                     std::to_string(s.first_frame) + ", " + std::to_string(s.end_frame) +
                     "] outside its clip",
             false;
  }
  for (const Transition& t : lib.graph.transitions)
    if (t.from < 0 || t.from >= num_segments || t.to < 0 || t.to >= num_segments || t.blend_frames < 0)
      return error = lib.name + ": transition " + std::to_string(t.from) + " -> " +
                     std::to_string(t.to) + " is invalid",
             false;
  return true;
}

/// The character's facing at `frame` of a segment's clip, in the segment's own frame (the start
/// faces +Z): what each frame's body capsule is oriented along.
vec2 facing_in(const MotionLibrary& lib, const Segment& s, int frame) {
  const float h = lib.root_placement(s.clip, frame).heading_rad - lib.root_placement(s.clip, s.first_frame).heading_rad;
  return {std::sin(h), std::cos(h)};
}

}  // namespace

bool motion_library_compile(MotionLibrarySource source, MotionLibrary& out, std::string& error) {
  if (!validate(source, error)) return false;
  MotionLibrary lib;
  static_cast<MotionLibrarySource&>(lib) = std::move(source);
  const int n = lib.num_joints();

  // Root tracks per clip.
  std::vector<Placement> track;
  lib.max_joint_step_m = 0.0f;
  for (const Clip& c : lib.clips) {
    clip_foot_contact(lib.skeleton, c, lib.foot_contact, lib.max_joint_step_m);
    const vec3 axis = find_forward_axis(lib.skeleton, c);
    extract_root_track(c, axis, track);
    lib.clip_forward_axis.push_back(axis);
    lib.clip_track_offset.push_back(static_cast<int>(lib.root_track.size()));
    lib.root_track.insert(lib.root_track.end(), track.begin(), track.end());
  }

  lib.head_top_margin_m = head_top_margin_m(lib.skeleton);
  compute_pop_budget(lib);

  // Per segment: relative movement and body volumes in the segment's own frame.
  std::vector<std::vector<BodyVolume>> volumes(lib.graph.segments.size());
  // The first frames of a segment are shown blended from any predecessor: their volumes are
  // fitted to the joints of every pose shown there (clip and blends), collected here.
  std::vector<int> blended_frames(lib.graph.segments.size(), 0);
  for (const Transition& tr : lib.graph.transitions)
    blended_frames[static_cast<size_t>(tr.to)] = std::max(blended_frames[static_cast<size_t>(tr.to)], tr.blend_frames);
  std::vector<std::vector<std::vector<vec3>>> shown_joints(lib.graph.segments.size());
  std::vector<vec3> global(static_cast<size_t>(n));
  std::vector<quat> global_rot(static_cast<size_t>(n));
  for (size_t si = 0; si < lib.graph.segments.size(); ++si) {
    const Segment& s = lib.graph.segments[si];
    const Clip& clip = lib.clips[s.clip];
    const Placement start = lib.root_placement(s.clip, s.first_frame);
    const Placement to_local = start.inverse();
    lib.segment_motion.push_back({start, to_local.compose(lib.root_placement(s.clip, s.end_frame))});
    for (int f = s.first_frame; f <= s.end_frame; ++f) {
      fk_pose(lib.skeleton, clip.frame_pos(f), clip.frame_rot(f), global, global_rot);
      for (vec3& p : global) p = to_local.apply(p);
      volumes[si].push_back(body_volume_from_pose(global, facing_in(lib, s, f), lib.body_margin_m, lib.head_top_margin_m));
      if (f - s.first_frame < blended_frames[si]) shown_joints[si].push_back(global);
    }
  }

  // Per transition: the blend offset from the successor's first pose to the predecessor's end.
  lib.transition_offset_pos_m.resize(lib.graph.transitions.size() * static_cast<size_t>(n));
  lib.transition_offset_rot.resize(lib.graph.transitions.size() * static_cast<size_t>(n));
  PoseOffset offset;
  for (size_t t = 0; t < lib.graph.transitions.size(); ++t) {
    const Segment& a = lib.graph.segments[lib.graph.transitions[t].from];
    const Segment& b = lib.graph.segments[lib.graph.transitions[t].to];
    pose_offset_between(lib.clips[a.clip], a.end_frame, lib.root_placement(a.clip, a.end_frame),
                        lib.clips[b.clip], b.first_frame, lib.root_placement(b.clip, b.first_frame),
                        offset);
    std::copy(offset.pos_m.begin(), offset.pos_m.end(), lib.transition_offset_pos_m.begin() + t * n);
    std::copy(offset.rot.begin(), offset.rot.end(), lib.transition_offset_rot.begin() + t * n);
  }

  // The poses shown while a transition blends out differ from the clip's by up to the join's gap
  // (about 1.5 cm): each blended frame's volume is fitted to every incoming blend's pose too, so
  // what the tree checks covers what is shown (shown_pose_collides), not only the clip.
  Pose pose;
  for (size_t t = 0; t < lib.graph.transitions.size(); ++t) {
    const Transition& tr = lib.graph.transitions[t];
    auto& shown = shown_joints[static_cast<size_t>(tr.to)];
    const int blended = std::min(tr.blend_frames, static_cast<int>(shown.size()));
    for (int k = 0; k < blended; ++k) {
      motion_library_sample(lib, tr.to, k, Placement{}, static_cast<int>(t), pose);
      fk_pose(lib.skeleton, pose.local_pos_m, pose.local_rot, global, global_rot);
      shown[static_cast<size_t>(k)].insert(shown[static_cast<size_t>(k)].end(), global.begin(), global.end());
    }
  }
  for (size_t si = 0; si < shown_joints.size(); ++si) {
    const Segment& s = lib.graph.segments[si];
    for (size_t k = 0; k < shown_joints[si].size(); ++k) {
      const vec2 facing = facing_in(lib, s, s.first_frame + static_cast<int>(k));
      volumes[si][k] = body_volume_from_pose(shown_joints[si][k], facing, lib.body_margin_m, lib.head_top_margin_m);
    }
  }
  for (const std::vector<BodyVolume>& frames : volumes) lib.segment_shapes.push_back(make_segment_shape(frames));

  lib.content_hash = content_hash_of(lib);
  out = std::move(lib);
  return true;
}

}  // namespace foresight
