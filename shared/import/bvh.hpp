#pragma once
// The raw BVH (Biovision Hierarchy) document: the joint tree and the motion table exactly as the
// file states them (file units, file axes, degrees), plus a strict, bounded text parser and a
// writer. Turning a document into a normalised Skeleton + Clip is bvh_import.hpp's job.
//
// Accepted syntax (see docs/BVH.md):
//   HIERARCHY
//   ROOT <name>            one ROOT; the name is the rest of the line (may contain spaces)
//   {
//     OFFSET x y z         required, first in every body
//     CHANNELS n c1 .. cn  optional, second; 0 <= n <= 6, each of Xposition Yposition Zposition
//                          Xrotation Yrotation Zrotation at most once, in any order, one line
//     JOINT <name> { ... } any number of children
//     End Site { OFFSET x y z }
//   }
//   MOTION
//   Frames: N              tab/space/nothing after the colon
//   Frame Time: t          seconds, finite, > 0
//   N lines of exactly (sum of n) numbers each; blank lines are ignored
// Keywords are case-insensitive; LF, CRLF or CR line ends; spaces/tabs anywhere; a UTF-8 BOM is
// skipped; numbers are locale-free (std::from_chars): "-0", "1.5e-06", ".5" are fine, a leading
// '+' is accepted, NaN/inf/hex/junk are not.
//
// Failure: false plus "<source>:<line>: <what was expected>, got '<token>'"; the functions never
// throw and never allocate from an unchecked count (the value storage reserved is at most what
// the bytes left can hold, 2 bytes a value; joints are capped at kBvhMaxJoints; Frames is
// 0..2^31-1). A hierarchy without any channel is refused. One frame per line.
#include "math/types.hpp"

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace foresight {

inline constexpr int kBvhMaxJoints = 1024;        ///< End Sites included.
inline constexpr int kBvhMaxChannelsPerJoint = 6;  ///< Each channel kind at most once.

enum class BvhChannel : uint8_t {
  kXposition,
  kYposition,
  kZposition,
  kXrotation,
  kYrotation,
  kZrotation
};

/// "Xposition" ... "Zrotation".
std::string_view bvh_channel_name(BvhChannel channel);
inline bool bvh_channel_is_position(BvhChannel c) { return c <= BvhChannel::kZposition; }
/// 0, 1, 2 for X, Y, Z.
inline int bvh_channel_axis(BvhChannel c) { return static_cast<int>(c) % 3; }

struct BvhJoint {
  std::string name;  ///< End Sites are named "<parent>_End" (the file gives them no name).
  int parent = -1;   ///< -1 for the ROOT (joint 0) only.
  vec3 offset{0.0f};  ///< File units, parent space.
  std::vector<BvhChannel> channels;  ///< In file order; empty for End Sites.
  bool end_site = false;
};

struct BvhDocument {
  std::vector<BvhJoint> joints;  ///< Depth-first file order: parent < index.
  int num_frames = 0;
  double frame_time_s = 1.0 / 30.0;
  /// num_frames * num_channels(), frame-major, joints and channels in file order; file units and
  /// degrees.
  std::vector<float> values;

  int num_channels() const;
  /// Index of the first value of joint `joint` within a frame (its channels follow).
  int channel_offset(int joint) const;
};

/// Parses BVH text. `source_name` prefixes error messages ("walk.bvh:17: ..."). On failure `out`
/// is left in an unspecified but valid state.
bool bvh_parse(std::string_view text, std::string_view source_name, BvhDocument& out,
               std::string& error);
/// Reads and parses a file (error messages use the path as given).
bool bvh_load(const std::filesystem::path& path, BvhDocument& out, std::string& error);

/// Checks a document built in code: one root, parent < index, depth-first order (every parent is
/// an ancestor still open in the tree), End Sites are channel-less leaves, <= 6 distinct channels
/// per joint and at least one in all, names writable (non-empty, no braces, no line breaks, no
/// outer blanks), values sized num_frames * num_channels and finite, frame time > 0.
bool bvh_validate(const BvhDocument& doc, std::string& error);

/// BVH text (tabs, LF, floats printed shortest-exact so parsing gives back the same values).
/// Returns "" for a document that fails bvh_validate.
std::string bvh_write(const BvhDocument& doc);
/// bvh_write to a file; false with an error for an invalid document or an I/O failure.
bool bvh_save(const std::filesystem::path& path, const BvhDocument& doc, std::string& error);

}  // namespace foresight
