#include "import/bvh_import.hpp"

#include "anim/fk.hpp"
#include "import/humanoid_map.hpp"
#include "import/humanoid_retarget.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>

namespace foresight {
namespace {

// The motion of a document in a flat, editable form: per-frame local transforms, file units and
// axes until convert_units_and_axes runs.
struct Motion {
  std::vector<std::string> names;
  std::vector<int> parents;
  std::vector<vec3> offsets;
  std::vector<bool> end_site;
  int frames = 0;
  std::vector<vec3> pos;  // [f * n + j]
  std::vector<quat> rot;

  int num_joints() const { return static_cast<int>(parents.size()); }
  size_t at(int f, int j) const { return static_cast<size_t>(f) * parents.size() + j; }
};

const glm::dvec3 kAxes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

// `add[j]`: joint j's position channels add to its OFFSET instead of replacing it (step 0).
Motion motion_from_document(const BvhDocument& doc, const std::vector<bool>& add) {
  Motion m;
  const int n = static_cast<int>(doc.joints.size());
  for (const BvhJoint& j : doc.joints) {
    m.names.push_back(j.name);
    m.parents.push_back(j.parent);
    m.offsets.push_back(j.offset);
    m.end_site.push_back(j.end_site);
  }
  m.frames = doc.num_frames;
  m.pos.resize(static_cast<size_t>(m.frames) * n);
  m.rot.resize(static_cast<size_t>(m.frames) * n);
  const size_t channels = static_cast<size_t>(doc.num_channels());
  for (int f = 0; f < m.frames; ++f) {
    const float* v = doc.values.data() + static_cast<size_t>(f) * channels;
    for (int j = 0; j < n; ++j) {
      vec3 p = doc.joints[j].offset;
      // Composed in double: six-channel joints multiply three quaternions per frame.
      glm::dquat q(1.0, 0.0, 0.0, 0.0);
      for (BvhChannel c : doc.joints[j].channels) {
        const double value = *v++;
        if (bvh_channel_is_position(c))
          p[bvh_channel_axis(c)] = static_cast<float>(value) + (add[j] ? doc.joints[j].offset[bvh_channel_axis(c)] : 0.0f);
        else
          q = q * glm::angleAxis(glm::radians(value), kAxes[bvh_channel_axis(c)]);
      }
      m.pos[m.at(f, j)] = p;
      m.rot[m.at(f, j)] = quat(glm::normalize(q));
    }
  }
  return m;
}

void fk_frame(const Motion& m, int f, std::vector<vec3>& gpos, std::vector<quat>& grot) {
  const int n = m.num_joints();
  gpos.resize(n);
  grot.resize(n);
  for (int j = 0; j < n; ++j) {
    const int p = m.parents[j];
    if (p < 0) {
      gpos[j] = m.pos[m.at(f, j)];
      grot[j] = m.rot[m.at(f, j)];
    } else {
      gpos[j] = gpos[p] + grot[p] * m.pos[m.at(f, j)];
      grot[j] = grot[p] * m.rot[m.at(f, j)];
    }
  }
}

bool joint_is_static(const Motion& m, int j) {
  const vec3 p0 = m.pos[m.at(0, j)];
  const quat q0 = m.rot[m.at(0, j)];
  const float pos_tolerance = 1e-5f * (1.0f + glm::length(p0));
  for (int f = 1; f < m.frames; ++f) {
    if (glm::length(m.pos[m.at(f, j)] - p0) > pos_tolerance) return false;
    // |dot| of unit quaternions: 1 - 1e-7 is about 0.05 degrees, float noise is far below.
    if (std::fabs(glm::dot(m.rot[m.at(f, j)], q0)) < 1.0f - 1e-7f) return false;
  }
  return true;
}

bool anything_moves(const Motion& m) {
  for (int j = 0; j < m.num_joints(); ++j)
    if (!joint_is_static(m, j)) return true;
  return false;
}

bool joint_never_rotates(const Motion& m, int j) {
  const quat q0 = m.rot[m.at(0, j)];
  for (int f = 1; f < m.frames; ++f)
    if (std::fabs(glm::dot(m.rot[m.at(f, j)], q0)) < 1.0f - 1e-7f) return false;
  return true;
}

// Folds the ROOT into its only (non-End-Site) child when the ROOT is a dummy:
//  * it never moves (Bandai `joint_Root` in most files), or
//  * it only translates and the child rotates: a trajectory node over the real pelvis (in four
//    dataset-1 Bandai segments `joint_Root` carries the travel along Z while `Hips` stays near
//    the origin). The child-rotates condition keeps a translating pelvis above a still joint.
// Folding composes the ROOT's per-frame transform into the child, so FK is unchanged. False when
// it does not apply.
bool fold_dummy_root(Motion& m) {
  const int n = m.num_joints();
  int child = -1, children = 0;
  for (int j = 1; j < n; ++j)
    if (m.parents[j] == 0) child = j, ++children;
  if (children != 1 || m.end_site[child]) return false;
  const bool dummy = joint_is_static(m, 0) ||
                     (joint_never_rotates(m, 0) && !joint_never_rotates(m, child));
  if (!dummy) return false;
  // Depth-first order puts the only child right after the root.
  Motion out;
  for (int j = 1; j < n; ++j) {
    out.names.push_back(m.names[j]);
    out.parents.push_back(j == child ? -1 : m.parents[j] - 1);
    out.end_site.push_back(m.end_site[j]);
    out.offsets.push_back(m.offsets[j]);
  }
  // Rest offset of the new root: its OFFSET carried by the root transform of frame 0 (the only
  // one for a static root).
  out.offsets[child - 1] = m.pos[m.at(0, 0)] + m.rot[m.at(0, 0)] * m.offsets[child];
  out.frames = m.frames;
  out.pos.reserve(static_cast<size_t>(m.frames) * (n - 1));
  out.rot.reserve(static_cast<size_t>(m.frames) * (n - 1));
  for (int f = 0; f < m.frames; ++f) {
    const vec3 rp = m.pos[m.at(f, 0)];
    const quat rq = m.rot[m.at(f, 0)];
    for (int j = 1; j < n; ++j) {
      vec3 p = m.pos[m.at(f, j)];
      quat q = m.rot[m.at(f, j)];
      if (j == child) {
        p = rp + rq * p;
        q = glm::normalize(rq * q);
      }
      out.pos.push_back(p);
      out.rot.push_back(q);
    }
  }
  m = std::move(out);
  return true;
}

// Largest bounding-box side of the posed body in frame 0 and a few frames spread over the clip
// (one crouched or lying first frame should not decide the unit).
float body_size(const Motion& m) {
  constexpr int kSamples = 8;
  std::vector<vec3> gpos;
  std::vector<quat> grot;
  float size = 0.0f;
  const int samples = std::min(kSamples, m.frames);
  for (int s = 0; s < samples; ++s) {
    const int f = samples > 1 ? static_cast<int>(static_cast<int64_t>(s) * (m.frames - 1) /
                                                 (samples - 1))
                              : 0;
    fk_frame(m, f, gpos, grot);
    vec3 lo = gpos[0], hi = gpos[0];
    for (const vec3& p : gpos) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const vec3 side = hi - lo;
    size = std::max({size, side.x, side.y, side.z});
  }
  return size;
}

LengthUnit unit_from_body_size(float size) {
  // A human is ~1.7 m = 67 in = 170 cm; arms raised add ~25%, crouching removes ~40%.
  if (size < 10.0f) return LengthUnit::kMetres;
  if (size < 100.0f) return LengthUnit::kInches;
  return LengthUnit::kCentimetres;
}

// The joints that carry the whole body: the ROOT and its single-child chain.
std::vector<bool> body_carriers(const BvhDocument& doc) {
  const int n = static_cast<int>(doc.joints.size());
  std::vector<bool> out(static_cast<size_t>(n), false);
  for (int j = 0; j >= 0;) {
    out[static_cast<size_t>(j)] = true;
    int child = -1, children = 0;
    for (int c = j + 1; c < n; ++c)
      if (doc.joints[c].parent == j && !doc.joints[c].end_site) child = c, ++children;
    j = children == 1 ? child : -1;
  }
  return out;
}

// Step 0 for joints that do not carry the body: channels near the OFFSET replace it, channels
// near zero add to it.
std::vector<bool> limb_position_rules(const BvhDocument& doc) {
  const int n = static_cast<int>(doc.joints.size());
  std::vector<double> to_offset(static_cast<size_t>(n), 0.0), to_zero(static_cast<size_t>(n), 0.0);
  const size_t channels = static_cast<size_t>(doc.num_channels());
  for (int f = 0; f < doc.num_frames; ++f) {
    const float* v = doc.values.data() + static_cast<size_t>(f) * channels;
    for (int j = 0; j < n; ++j)
      for (BvhChannel c : doc.joints[j].channels) {
        const double value = *v++;
        if (!bvh_channel_is_position(c)) continue;
        to_offset[static_cast<size_t>(j)] += std::fabs(value - doc.joints[j].offset[bvh_channel_axis(c)]);
        to_zero[static_cast<size_t>(j)] += std::fabs(value);
      }
  }
  std::vector<bool> add(static_cast<size_t>(n), false);
  for (int j = 0; j < n; ++j) add[static_cast<size_t>(j)] = to_zero[static_cast<size_t>(j)] < to_offset[static_cast<size_t>(j)];
  return add;
}

vec3 up_vector(UpAxis up) {
  switch (up) {
    case UpAxis::kZUp: return {0, 0, 1};
    case UpAxis::kNegZUp: return {0, 0, -1};
    case UpAxis::kXUp: return {1, 0, 0};
    case UpAxis::kNegXUp: return {-1, 0, 0};
    case UpAxis::kNegYUp: return {0, -1, 0};
    default: return {0, 1, 0};
  }
}

// Median over (up to 64 sampled) frames of the lowest joint's height along `up`, file units.
float median_lowest(const Motion& m, vec3 up) {
  std::vector<vec3> gpos;
  std::vector<quat> grot;
  std::vector<float> lows;
  const int samples = std::min(64, m.frames);
  for (int s = 0; s < samples; ++s) {
    const int f = samples > 1 ? static_cast<int>(static_cast<int64_t>(s) * (m.frames - 1) / (samples - 1)) : 0;
    fk_frame(m, f, gpos, grot);
    float low = std::numeric_limits<float>::max();
    for (const vec3& p : gpos) low = std::min(low, glm::dot(p, up));
    lows.push_back(low);
  }
  std::nth_element(lows.begin(), lows.begin() + lows.size() / 2, lows.end());
  return lows[lows.size() / 2];
}

// The standard unit nearest to `scale` metres per unit, if within a factor of 1.5.
LengthUnit nearest_unit(float scale) {
  LengthUnit best = LengthUnit::kAuto;
  float best_ratio = std::log(1.5f);
  for (LengthUnit u : {LengthUnit::kMetres, LengthUnit::kCentimetres, LengthUnit::kMillimetres,
                       LengthUnit::kInches, LengthUnit::kFeet}) {
    const float r = std::fabs(std::log(scale / length_unit_scale(u)));
    if (r < best_ratio) best_ratio = r, best = u;
  }
  return best;
}

bool contains_head(std::string_view name) {
  std::string lower(name);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.find("head") != std::string::npos;
}

UpAxis detect_up(const Motion& m) {
  std::vector<vec3> gpos;
  std::vector<quat> grot;
  fk_frame(m, 0, gpos, grot);
  const int n = m.num_joints();
  const vec3 pelvis = gpos[0];
  vec3 top = pelvis;
  int head = -1;
  for (int j = 1; j < n && head < 0; ++j)
    if (contains_head(m.names[j])) head = j;
  if (head >= 0) top = gpos[head];
  if (head < 0 || glm::length(top - pelvis) < 1e-6f) {
    // The upper body: the root's child with the largest subtree (legs are smaller than spine +
    // arms + head), and its centroid.
    std::vector<int> branch(n, -1), size(n, 0);
    for (int j = 1; j < n; ++j) {
      branch[j] = m.parents[j] == 0 ? j : branch[m.parents[j]];
      ++size[branch[j]];
    }
    const int best = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
    if (size[best] == 0) return UpAxis::kYUp;
    vec3 sum(0.0f);
    for (int j = 1; j < n; ++j)
      if (branch[j] == best) sum += gpos[j];
    top = sum / static_cast<float>(size[best]);
  }
  const vec3 d = top - pelvis;
  const vec3 a = glm::abs(d);
  if (a.x >= a.y && a.x >= a.z && a.x > 0.0f) return d.x > 0 ? UpAxis::kXUp : UpAxis::kNegXUp;
  if (a.z > a.y) return d.z > 0 ? UpAxis::kZUp : UpAxis::kNegZUp;
  return d.y >= 0 ? UpAxis::kYUp : UpAxis::kNegYUp;
}

// The rotation that takes `up` to +Y, applied exactly (axis permutations and sign flips).
vec3 to_y_up(UpAxis up, vec3 v) {
  switch (up) {
    case UpAxis::kZUp: return {v.x, v.z, -v.y};      // -90 deg about X
    case UpAxis::kNegZUp: return {v.x, -v.z, v.y};   // +90 deg about X
    case UpAxis::kNegYUp: return {v.x, -v.y, -v.z};  // 180 deg about X
    case UpAxis::kXUp: return {-v.y, v.x, v.z};      // +90 deg about Z
    case UpAxis::kNegXUp: return {v.y, -v.x, v.z};   // -90 deg about Z
    default: return v;
  }
}

// C q C^-1 for a rotation C: same angle, axis rotated by C.
quat to_y_up(UpAxis up, quat q) {
  const vec3 axis = to_y_up(up, vec3(q.x, q.y, q.z));
  return quat(q.w, axis.x, axis.y, axis.z);
}

void convert_axes(Motion& m, UpAxis up) {
  for (vec3& o : m.offsets) o = to_y_up(up, o);
  for (vec3& p : m.pos) p = to_y_up(up, p);
  for (quat& q : m.rot) q = to_y_up(up, q);
}

void scale_lengths(Motion& m, float scale) {
  for (vec3& o : m.offsets) o *= scale;
  for (vec3& p : m.pos) p *= scale;
}

Skeleton skeleton_of(const Motion& m) {
  Skeleton s;
  s.joint_names = m.names;
  for (int p : m.parents) s.parents.push_back(static_cast<int16_t>(p));
  s.rest_offsets_m = m.offsets;
  s.is_end_site = m.end_site;
  return s;
}

// Global positions of up to 16 frames spread over the clip (the humanoid map's input).
std::vector<vec3> sampled_positions(const Motion& m) {
  std::vector<vec3> out, gpos;
  std::vector<quat> grot;
  const int samples = std::min(16, m.frames);
  for (int s = 0; s < samples; ++s) {
    const int f = samples > 1 ? static_cast<int>(static_cast<int64_t>(s) * (m.frames - 1) / (samples - 1)) : 0;
    fk_frame(m, f, gpos, grot);
    out.insert(out.end(), gpos.begin(), gpos.end());
  }
  return out;
}

void make_signs_continuous(Motion& m) {
  const int n = m.num_joints();
  for (int f = 1; f < m.frames; ++f)
    for (int j = 0; j < n; ++j)
      if (glm::dot(m.rot[m.at(f, j)], m.rot[m.at(f - 1, j)]) < 0.0f)
        m.rot[m.at(f, j)] = -m.rot[m.at(f, j)];
}

quat slerp_shortest(quat a, quat b, float t) {
  if (glm::dot(a, b) < 0.0f) b = -b;
  return glm::normalize(glm::slerp(a, b, t));
}

// Output frame k samples source time k / fps; the last output frame is the last source frame.
bool resample(Motion& m, double frame_time_s, double fps, std::string& error) {
  const double duration = (m.frames - 1) * frame_time_s;
  const double out_frames = std::round(duration * fps) + 1.0;
  const int n = m.num_joints();
  // Bounded so that a hostile frame time cannot make us allocate gigabytes: 2^23 samples (235 MB
  // of positions and rotations) hold 23 minutes at 60 fps of a 100-joint skeleton, longer than any
  // capture take; 2^26 let one 64 KB file take 2 GB (found by fuzz-bvh).
  constexpr double kMaxSamples = 1 << 23;
  if (!(out_frames * n <= kMaxSamples)) {
    error = "resampled clip too large (" + std::to_string(static_cast<int64_t>(out_frames)) +
            " frames x " + std::to_string(n) + " joints; the limit is " +
            std::to_string(static_cast<int64_t>(kMaxSamples)) + " samples)";
    return false;
  }
  const int count = static_cast<int>(out_frames);
  std::vector<vec3> pos(static_cast<size_t>(count) * n);
  std::vector<quat> rot(static_cast<size_t>(count) * n);
  for (int k = 0; k < count; ++k) {
    int i = m.frames - 1;
    float a = 0.0f;
    if (k + 1 < count) {
      const double s = (k / fps) / frame_time_s;
      i = std::clamp(static_cast<int>(std::floor(s)), 0, m.frames - 1);
      a = i + 1 < m.frames ? static_cast<float>(s - i) : 0.0f;
    }
    const int i1 = std::min(i + 1, m.frames - 1);
    for (int j = 0; j < n; ++j) {
      const size_t o = static_cast<size_t>(k) * n + j;
      pos[o] = glm::mix(m.pos[m.at(i, j)], m.pos[m.at(i1, j)], a);
      rot[o] = a == 0.0f ? m.rot[m.at(i, j)] : slerp_shortest(m.rot[m.at(i, j)], m.rot[m.at(i1, j)], a);
    }
  }
  m.frames = count;
  m.pos = std::move(pos);
  m.rot = std::move(rot);
  return true;
}

// R = Rz(z) * Rx(x) * Ry(y), angles in degrees.
vec3 euler_zxy_degrees(quat q) {
  // Normalised in double first: a float quaternion is unit only to ~1e-7, which near x = +-90
  // degrees would move x by ~0.02 degrees.
  const glm::dmat3 r = glm::mat3_cast(glm::normalize(glm::dquat(q.w, q.x, q.y, q.z)));
  // r[col][row]. Row 2 of Rz*Rx*Ry is (-cx sy, sx, cx cy); column 1 is (-sz cx, cz cx, sx).
  // x from atan2(sx, cx) rather than asin(sx): asin is ill-conditioned near +-90 degrees.
  const double cx = std::hypot(r[1][0], r[1][1]);
  const double x = std::atan2(r[1][2], cx);
  double y = 0.0, z = 0.0;
  if (cx > 1e-12) {
    z = std::atan2(-r[1][0], r[1][1]);
    y = std::atan2(-r[0][2], r[2][2]);
  } else {  // gimbal lock: Rx(+-90) Ry(y) = Rz(+-y) Rx(+-90), so y is folded into z
    z = std::atan2(r[0][1], r[0][0]);
  }
  return vec3(glm::degrees(z), glm::degrees(x), glm::degrees(y));
}

}  // namespace

float length_unit_scale(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMetres: return 1.0f;
    case LengthUnit::kCentimetres: return 0.01f;
    case LengthUnit::kInches: return 0.0254f;
    case LengthUnit::kMillimetres: return 0.001f;
    case LengthUnit::kFeet: return 0.3048f;
    default: return 0.0f;
  }
}

std::string_view length_unit_name(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMetres: return "metres";
    case LengthUnit::kCentimetres: return "centimetres";
    case LengthUnit::kInches: return "inches";
    case LengthUnit::kMillimetres: return "millimetres";
    case LengthUnit::kFeet: return "feet";
    default: return "auto";
  }
}

std::string_view up_axis_name(UpAxis up) {
  switch (up) {
    case UpAxis::kYUp: return "+Y";
    case UpAxis::kZUp: return "+Z";
    case UpAxis::kXUp: return "+X";
    case UpAxis::kNegXUp: return "-X";
    case UpAxis::kNegYUp: return "-Y";
    case UpAxis::kNegZUp: return "-Z";
    default: return "auto";
  }
}

std::string_view root_position_name(RootPosition rule) {
  switch (rule) {
    case RootPosition::kAbsolute: return "absolute";
    case RootPosition::kRelative: return "relative to OFFSET";
    default: return "auto";
  }
}

namespace {

// Step 0: the motion read with the body carriers' position channels absolute or relative to their
// OFFSET, as given, or (kAuto) the reading whose lowest point lies nearer the floor.
Motion read_with_root_rule(const BvhDocument& doc, const BvhImportOptions& options, RootPosition& used) {
  std::vector<bool> add = limb_position_rules(doc);
  const std::vector<bool> carriers = body_carriers(doc);
  bool carrier_offsets = false;
  for (size_t j = 0; j < carriers.size(); ++j) {
    if (carriers[j]) add[j] = options.root == RootPosition::kRelative;
    carrier_offsets |= carriers[j] && glm::length(doc.joints[j].offset) > 0.0f;
  }
  Motion m = motion_from_document(doc, add);
  used = options.root == RootPosition::kRelative ? RootPosition::kRelative : RootPosition::kAbsolute;
  if (options.root != RootPosition::kAuto || !carrier_offsets) return m;  // both readings agree
  for (size_t j = 0; j < carriers.size(); ++j)
    if (carriers[j]) add[j] = true;
  Motion relative = motion_from_document(doc, add);
  // The up axis is read from the pelvis, so dummy roots are folded first (on a copy).
  Motion folded = m;
  if (anything_moves(folded))
    while (fold_dummy_root(folded)) {}
  const vec3 up = up_vector(options.up == UpAxis::kAuto ? detect_up(folded) : options.up);
  if (std::fabs(median_lowest(relative, up)) >= std::fabs(median_lowest(m, up))) return m;
  used = RootPosition::kRelative;
  return relative;
}

// Step 3: metres per file unit, given or measured (r.body_size, r.humanoid already set).
void choose_scale(const BvhImportOptions& options, BvhImportReport& r) {
  if (options.scale > 0.0f) {
    r.scale = options.scale;
    r.unit = nearest_unit(options.scale);
  } else if (options.unit != LengthUnit::kAuto) {
    r.unit = options.unit;
    r.scale = length_unit_scale(options.unit);
  } else if (r.humanoid && r.body_size > 0.0f) {
    r.scale = kCanonicalStandingHeightM / r.body_size;
    r.unit = nearest_unit(r.scale);
    r.height_normalised = true;
  } else {
    r.unit = unit_from_body_size(r.body_size);
    r.scale = length_unit_scale(r.unit);
  }
}

// What the import made of a humanoid: its size, where its feet are, warnings, and which joint
// became which canonical joint.
// `all`: the clip's FK positions, [frame * joints + joint].
void report_humanoid(const Skeleton& s, const Clip& clip, std::span<const vec3> all, const HumanoidMap& roles,
                     BvhImportReport& r) {
  const std::vector<vec3> sample = [&] {
    std::vector<vec3> out;
    const int samples = std::min(16, clip.num_frames);
    for (int k = 0; k < samples; ++k) {
      const int f = samples > 1 ? k * (clip.num_frames - 1) / (samples - 1) : 0;
      out.insert(out.end(), all.begin() + static_cast<std::ptrdiff_t>(f) * s.num_joints(),
                 all.begin() + static_cast<std::ptrdiff_t>(f + 1) * s.num_joints());
    }
    return out;
  }();
  r.standing_height_m = humanoid_stature(roles, sample);
  r.head_height_m = humanoid_head_height(s, roles, sample);
  std::vector<float> lows;
  for (int f = 0; f < clip.num_frames; ++f) {
    float low = std::numeric_limits<float>::max();
    for (int side = 0; side < 2; ++side)
      for (int j : {roles.foot[side], roles.toe[side], roles.toe_end[side]})
        if (j >= 0) low = std::min(low, all[static_cast<size_t>(f) * s.num_joints() + j].y);
    lows.push_back(low);
  }
  std::nth_element(lows.begin(), lows.begin() + lows.size() / 2, lows.end());
  r.lowest_foot_m = lows[lows.size() / 2];
  char line[160];
  if (r.standing_height_m < 1.4f || r.standing_height_m > 2.2f) {
    std::snprintf(line, sizeof line, "the body is %.2f m tall, outside human size (1.4-2.2 m): check --bvh-units / --bvh-scale",
                  r.standing_height_m);
    r.warnings.emplace_back(line);
  }
  if (r.lowest_foot_m > 0.15f || r.lowest_foot_m < -0.05f) {
    std::snprintf(line, sizeof line, "the feet %s %.0f cm %s the floor (median lowest foot point): check --bvh-root",
                  r.lowest_foot_m > 0 ? "float" : "sink", std::fabs(r.lowest_foot_m) * 100.0f,
                  r.lowest_foot_m > 0 ? "above" : "under");
    r.warnings.emplace_back(line);
  }
  r.source_joints = s.joint_names;
  r.canonical_joint.assign(static_cast<size_t>(s.num_joints()), -1);
  const HumanoidMap canon = canonical_humanoid_map();
  auto mark = [&](int source, int target) {
    if (source >= 0) r.canonical_joint[static_cast<size_t>(source)] = target;
  };
  mark(roles.pelvis, kCanonHips), mark(roles.chest, kCanonChest), mark(roles.neck, kCanonNeck);
  mark(roles.head, kCanonHead), mark(roles.head_top, kCanonHeadTop);
  for (int side = 0; side < 2; ++side) {
    mark(roles.clavicle[side], canon.clavicle[side]), mark(roles.upper_arm[side], canon.upper_arm[side]);
    mark(roles.forearm[side], canon.forearm[side]), mark(roles.hand[side], canon.hand[side]);
    mark(roles.hand_end[side], canon.hand_end[side]), mark(roles.thigh[side], canon.thigh[side]);
    mark(roles.shin[side], canon.shin[side]), mark(roles.foot[side], canon.foot[side]);
    mark(roles.toe[side], canon.toe[side]), mark(roles.toe_end[side], canon.toe_end[side]);
  }
  r.source_joint_kept.assign(static_cast<size_t>(s.num_joints()), false);
  for (int j : roles.used_joints()) r.source_joint_kept[static_cast<size_t>(j)] = true;
}

// Step 6: the clip on the canonical skeleton with the capture's proportions, measured in its
// tallest frame (the limbs read straightest there).
void to_canonical(const Skeleton& source, const Clip& clip, std::span<const vec3> all, const HumanoidMap& roles,
                  Skeleton& skeleton, Clip& out) {
  const int n = source.num_joints();
  auto frame = [&](int f) { return std::span<const vec3>(all.data() + static_cast<size_t>(f) * n, static_cast<size_t>(n)); };
  int tallest = 0;
  float best = -1.0f;
  for (int f = 0; f < clip.num_frames; ++f) {
    const float h = humanoid_head_height(source, roles, frame(f));
    if (h > best) best = h, tallest = f;
  }
  skeleton = canonical_skeleton_from_capture(roles, frame(tallest));
  retarget_to_canonical(source, clip, roles, skeleton, 1.0f, out);
}

}  // namespace

bool clip_from_bvh(const BvhDocument& doc, std::string_view name, const BvhImportOptions& options,
                   Skeleton& skeleton, Clip& clip, BvhImportReport* report, std::string& error) {
  try {
    const std::string prefix = std::string(name) + ": ";
    if (!bvh_validate(doc, error)) return error = prefix + error, false;
    if (doc.num_frames < 1) return error = prefix + "no motion frames", false;
    if (!(options.target_fps >= 0.0f && options.target_fps <= 1000.0f))
      return error = prefix + "target fps must be 0 (auto) or in (0, 1000]", false;
    if (!(options.scale >= 0.0f && options.scale < 1e6f))
      return error = prefix + "scale must be 0 (auto) or a positive number of metres per unit", false;

    BvhImportReport r;
    r.source_frames = doc.num_frames;
    r.source_fps = static_cast<float>(1.0 / doc.frame_time_s);
    Motion m = read_with_root_rule(doc, options, r.root);  // step 0

    // Step 1. In a single frame or a frozen pose nothing rotates: a dummy cannot be told from
    // the pelvis, so nothing is folded.
    if (anything_moves(m))
      while (fold_dummy_root(m)) ++r.folded_root_joints;

    r.up = options.up == UpAxis::kAuto ? detect_up(m) : options.up;  // step 2
    convert_axes(m, r.up);

    // Step 3: the roles (for the standing height and the canonical skeleton), then the scale.
    HumanoidMap roles;
    {
      const std::vector<vec3> sample = sampled_positions(m);
      r.humanoid = humanoid_map_find(skeleton_of(m), sample, roles, r.not_humanoid);
      r.body_size = r.humanoid ? humanoid_stature(roles, sample) : body_size(m);
    }
    if (options.canonical && !r.humanoid) return error = prefix + r.not_humanoid, false;
    if (!std::isfinite(r.body_size))
      return error = prefix + "the posed body reaches beyond float range (OFFSETs or position channels too large)", false;
    choose_scale(options, r);
    scale_lengths(m, r.scale);
    make_signs_continuous(m);

    // Step 4.
    const double source_fps = 1.0 / doc.frame_time_s;
    // 45 fps itself (a frame time of 1/45 printed to 7 digits) must land on 30.
    const double fps = options.target_fps > 0.0f   ? options.target_fps
                       : source_fps <= 45.0 + 1e-3 ? 30.0
                                                   : 60.0;
    r.fps = static_cast<float>(fps);
    if (std::fabs(source_fps - fps) > 1e-3 * fps && !resample(m, doc.frame_time_s, fps, error))
      return error = prefix + error, false;

    Skeleton source = skeleton_of(m);
    Clip out;
    out.name = std::string(name);
    out.fps = r.fps;
    out.num_frames = m.frames;
    out.num_joints = m.num_joints();
    out.local_pos_m = std::move(m.pos);
    out.local_rot = std::move(m.rot);
    std::vector<vec3> all;  // FK of the whole clip, for the report and the canonical skeleton
    if (r.humanoid) {  // (canonical implies humanoid: refused above otherwise)
      fk_clip_positions(source, out, all);
      report_humanoid(source, out, all, roles, r);
    }
    if (options.canonical) {
      to_canonical(source, out, all, roles, skeleton, clip);  // step 6
    } else {
      skeleton = std::move(source);
      clip = std::move(out);
    }
    if (report) *report = r;
    return true;
  } catch (const std::exception& e) {  // bad_alloc only
    error = std::string(name) + ": " + e.what();
    return false;
  }
}

bool clip_load_bvh(const std::filesystem::path& path, const BvhImportOptions& options,
                   Skeleton& skeleton, Clip& clip, BvhImportReport* report, std::string& error) {
  BvhDocument doc;
  if (!bvh_load(path, doc, error)) return false;
  return clip_from_bvh(doc, path.stem().string(), options, skeleton, clip, report, error);
}

BvhDocument bvh_from_clip(const Skeleton& skeleton, const Clip& clip) {
  using C = BvhChannel;
  BvhDocument doc;
  const int n = skeleton.num_joints();
  constexpr float kMovedM = 1e-6f;  // below a micrometre a translation counts as the rest offset
  for (int j = 0; j < n; ++j) {
    BvhJoint joint;
    joint.name = skeleton.joint_names[j];
    joint.parent = skeleton.parents[j];
    joint.offset = skeleton.rest_offsets_m[j];
    joint.end_site = skeleton.is_end_site[j];
    if (!joint.end_site) {
      bool moves = j == 0;
      for (int f = 0; f < clip.num_frames && !moves; ++f)
        moves = glm::length(clip.frame_pos(f)[j] - joint.offset) > kMovedM;
      if (moves) joint.channels = {C::kXposition, C::kYposition, C::kZposition};
      joint.channels.insert(joint.channels.end(), {C::kZrotation, C::kXrotation, C::kYrotation});
    }
    doc.joints.push_back(std::move(joint));
  }
  doc.num_frames = clip.num_frames;
  doc.frame_time_s = 1.0 / clip.fps;
  doc.values.reserve(static_cast<size_t>(clip.num_frames) * doc.num_channels());
  for (int f = 0; f < clip.num_frames; ++f) {
    for (int j = 0; j < n; ++j) {
      const BvhJoint& joint = doc.joints[j];
      if (joint.end_site) continue;
      if (joint.channels.size() == 6) {
        const vec3 p = clip.frame_pos(f)[j];
        doc.values.insert(doc.values.end(), {p.x, p.y, p.z});
      }
      const vec3 e = euler_zxy_degrees(clip.frame_rot(f)[j]);
      doc.values.insert(doc.values.end(), {e.x, e.y, e.z});
    }
  }
  return doc;
}

}  // namespace foresight
