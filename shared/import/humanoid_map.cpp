#include "import/humanoid_map.hpp"

#include "anim/canonical_skeleton.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace foresight {
namespace {

struct Posed {
  const Skeleton& s;
  std::span<const vec3> pos;
  int n = 0, frames = 0, ref = 0;  // ref: the tallest frame (straightest limbs)
  std::vector<float> mean_y;
  std::vector<std::vector<int>> children;
  std::vector<float> lowest;  // per frame: the lowest joint's height (the ground under the body)
  float height = 0.0f;

  vec3 at(int f, int j) const { return pos[static_cast<size_t>(f) * n + j]; }
  vec3 ref_at(int j) const { return at(ref, j); }
  float ref_distance(int a, int b) const { return glm::length(ref_at(a) - ref_at(b)); }
  // A leaf on top of its parent (an End Site with a zero OFFSET) says nothing: -1.
  int real_leaf(int leaf) const {
    return leaf >= 0 && ref_distance(leaf, s.parents[static_cast<size_t>(leaf)]) > 0.01f * height ? leaf : -1;
  }
};

// Joints from `from` (exclusive) down to `to` (inclusive), top first; empty if not a descendant.
std::vector<int> chain(const Skeleton& s, int from, int to) {
  std::vector<int> out;
  for (int j = to; j != from; j = s.parents[static_cast<size_t>(j)]) {
    if (j < 0) return {};
    out.push_back(j);
  }
  std::reverse(out.begin(), out.end());
  return out;
}

int common_ancestor(const Skeleton& s, int a, int b) {
  std::vector<bool> on_a(static_cast<size_t>(s.num_joints()), false);
  for (int j = a; j >= 0; j = s.parents[static_cast<size_t>(j)]) on_a[static_cast<size_t>(j)] = true;
  for (int j = b; j >= 0; j = s.parents[static_cast<size_t>(j)])
    if (on_a[static_cast<size_t>(j)]) return j;
  return -1;
}

bool descends(const Skeleton& s, int j, int ancestor) {
  for (; j >= 0; j = s.parents[static_cast<size_t>(j)])
    if (j == ancestor) return true;
  return false;
}

// The pair (upper, mid) on `path` before index `end` whose two straight lengths (upper -> mid,
// mid -> end) are nearly equal (within 12 %) and together at least `min_total`: hip/knee,
// shoulder/elbow. Of those, the deepest upper joint: a dummy hip joint at the pelvis centre or a
// clavicle makes a balanced pair too, the real joint lies below it. Then the most balanced.
bool balanced_pair(const Posed& p, const std::vector<int>& path, int end_index, float min_total,
                   int& upper, int& mid) {
  int best_u = -1;
  float best = 0.12f;
  const int end = path[static_cast<size_t>(end_index)];
  for (int u = 0; u < end_index; ++u)
    for (int m = u + 1; m < end_index; ++m) {
      const float a = p.ref_distance(path[static_cast<size_t>(u)], path[static_cast<size_t>(m)]);
      const float b = p.ref_distance(path[static_cast<size_t>(m)], end);
      if (a + b < min_total) continue;
      const float score = std::fabs(a - b) / (a + b);
      if (score < 0.12f && (u > best_u || score < best)) {
        if (u > best_u) best = 0.12f;
        if (score >= best) continue;
        best = score, best_u = u, upper = path[static_cast<size_t>(u)], mid = path[static_cast<size_t>(m)];
      }
    }
  return best_u >= 0;
}

std::string lower(std::string_view name) {
  std::string out(name);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// +1 for a name that says left, -1 right, 0 neither ("LeftArm", "UpperArm_L", "l_hip", "Bip01 L Thigh").
int side_from_name(std::string_view name) {
  const std::string n = lower(name);
  if (n.find("left") != std::string::npos) return 1;
  if (n.find("right") != std::string::npos) return -1;
  auto has_token = [&](char c) {
    for (size_t i = 0; i < n.size(); ++i) {
      if (n[i] != c) continue;
      const bool start = i == 0 || !std::isalpha(static_cast<unsigned char>(n[i - 1]));
      const bool end = i + 1 == n.size() || !std::isalpha(static_cast<unsigned char>(n[i + 1]));
      // "_l", "l_", " l ", ".l"; also a leading "L" before an upper-case letter ("LThigh").
      if (start && end) return true;
      if (i == 0 && i + 1 < name.size() && std::isupper(static_cast<unsigned char>(name[1])) &&
          std::toupper(static_cast<unsigned char>(name[0])) == std::toupper(static_cast<unsigned char>(c)))
        return true;
    }
    return false;
  };
  if (has_token('l')) return 1;
  if (has_token('r')) return -1;
  return 0;
}

// A chain off the spine: where it branches, its first joint, its farthest leaf and its length.
struct Branch {
  int base = -1, root = -1, leaf = -1;
  float length = 0.0f;
};

// Per side: thigh, shin, foot, toe, toe end (legs) or clavicle, upper arm, forearm, hand, hand end.
using Limbs = std::array<std::array<int, 5>, 2>;

// Along a leg's path from the pelvis to its lowest leaf: the ankle, then the most balanced
// hip/knee pair above it, the toe and the toe's end below it.
bool leg_joints(const Posed& p, const std::vector<int>& path, std::array<int, 5>& leg) {
  const float h = p.height;
  int ankle_index = -1;
  for (int k = static_cast<int>(path.size()) - 1; k >= 1 && ankle_index < 0; --k) {
    // The shin: a long bone (a foot's are under a tenth of the body) whose upper end, the knee,
    // is well off the ground in most frames, standing, running or crouching (a foot's joints
    // stay near it).
    const int a = path[static_cast<size_t>(k - 1)], b = path[static_cast<size_t>(k)];
    std::vector<float> raised;
    for (int f = 0; f < p.frames; ++f) raised.push_back(p.at(f, a).y - p.lowest[static_cast<size_t>(f)]);
    std::nth_element(raised.begin(), raised.begin() + raised.size() / 2, raised.end());
    if (p.ref_distance(a, b) > 0.12f * h && raised[raised.size() / 2] > 0.15f * h) ankle_index = k;
  }
  int hip = -1, knee = -1;
  if (ankle_index < 0 || !balanced_pair(p, path, ankle_index, 0.3f * h, hip, knee)) return false;
  const int ankle = path[static_cast<size_t>(ankle_index)];
  const int toe = ankle_index + 1 < static_cast<int>(path.size()) ? path[static_cast<size_t>(ankle_index) + 1] : -1;
  const int leaf = path.back();
  leg = {hip, knee, ankle, toe, toe >= 0 && leaf != toe ? p.real_leaf(leaf) : -1};
  return true;
}

// Along an arm's path from its branch on the spine to its farthest leaf: the wrist (where the
// fingers branch, or the chain's last joint), then the most balanced shoulder/elbow pair, the
// clavicle before the shoulder and the hand's end.
bool arm_joints(const Posed& p, const std::vector<int>& path, std::array<int, 5>& arm) {
  const int leaf = path.back();
  int wrist_index = -1;
  for (int k = static_cast<int>(path.size()) - 1; k >= 1 && wrist_index < 0; --k)
    if (p.children[static_cast<size_t>(path[static_cast<size_t>(k)])].size() >= 2) wrist_index = k;
  if (wrist_index < 0) {
    wrist_index = static_cast<int>(path.size()) - 1;
    if (p.s.is_end_site[static_cast<size_t>(leaf)] && wrist_index > 1) --wrist_index;
  }
  int shoulder = -1, elbow = -1;
  if (!balanced_pair(p, path, wrist_index, 0.2f * p.height, shoulder, elbow)) return false;
  const int shoulder_index = static_cast<int>(std::find(path.begin(), path.end(), shoulder) - path.begin());
  const int wrist = path[static_cast<size_t>(wrist_index)];
  arm = {shoulder_index >= 2 ? path[static_cast<size_t>(shoulder_index) - 1] : -1, shoulder, elbow, wrist,
         leaf != wrist ? p.real_leaf(leaf) : -1};
  return true;
}

// Sides: the body faces where the knees bend (or, legs straight, where the toes point; or where
// it travels); left = up x forward. Names decide only when the geometry cannot. Toes alone read
// a sprint backwards: a Bandai dash's feet, kicked up behind, point back more than ahead, and its
// sides came out swapped (its facing backwards, 4.5 m/s "back").
void assign_sides(const Posed& p, Limbs legs, Limbs arms, HumanoidMap& out) {
  vec3 knees(0.0f), toes(0.0f);
  for (const auto& leg : legs)
    for (int f = 0; f < p.frames; ++f) {
      knees += offset_from_line(p.at(f, leg[1]), p.at(f, leg[0]), p.at(f, leg[2]));
      if (leg[3] >= 0) toes += p.at(f, leg[3]) - p.at(f, leg[2]);
    }
  knees.y = toes.y = 0.0f;
  // Knees bent over 1 % of the height on average over the frames (a walk's: several cm) say which
  // way is ahead.
  vec3 forward = glm::length(knees) >= 0.01f * p.height * static_cast<float>(p.frames) ? knees : toes;
  if (glm::length(forward) < 1e-3f * p.height) forward = p.at(p.frames - 1, out.pelvis) - p.at(0, out.pelvis), forward.y = 0.0f;
  const vec3 left = glm::cross(vec3(0, 1, 0), forward);
  auto lateral = [&](int joint, int base) {
    float sum = 0.0f;
    for (int f = 0; f < p.frames; ++f) sum += glm::dot(p.at(f, joint) - p.at(f, base), left);
    return sum;
  };
  const float leg_split = lateral(legs[0][0], out.pelvis) - lateral(legs[1][0], out.pelvis);
  const float arm_split = lateral(arms[0][1], out.chest) - lateral(arms[1][1], out.chest);
  const float tiny = 1e-3f * p.height * static_cast<float>(p.frames);
  bool swap_legs = leg_split < 0.0f, swap_arms = arm_split < 0.0f;
  if (std::fabs(leg_split) < tiny || std::fabs(arm_split) < tiny) {
    out.sides_from_names = true;
    swap_legs = side_from_name(p.s.joint_names[static_cast<size_t>(legs[0][0])]) < 0;
    swap_arms = side_from_name(p.s.joint_names[static_cast<size_t>(arms[0][1])]) < 0;
  }
  if (swap_legs) std::swap(legs[0], legs[1]);
  if (swap_arms) std::swap(arms[0], arms[1]);
  for (int i = 0; i < 2; ++i) {
    const auto& l = legs[static_cast<size_t>(i)];
    const auto& a = arms[static_cast<size_t>(i)];
    out.thigh[i] = l[0], out.shin[i] = l[1], out.foot[i] = l[2], out.toe[i] = l[3], out.toe_end[i] = l[4];
    out.clavicle[i] = a[0], out.upper_arm[i] = a[1], out.forearm[i] = a[2], out.hand[i] = a[3], out.hand_end[i] = a[4];
  }
}

}  // namespace

std::vector<int> HumanoidMap::used_joints() const {
  std::vector<int> out{pelvis, chest, neck, head, head_top};
  out.insert(out.end(), spine.begin(), spine.end());
  for (int side = 0; side < 2; ++side)
    for (int j : {clavicle[side], upper_arm[side], forearm[side], hand[side], hand_end[side], thigh[side],
                  shin[side], foot[side], toe[side], toe_end[side]})
      out.push_back(j);
  out.erase(std::remove(out.begin(), out.end(), -1), out.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool humanoid_map_find(const Skeleton& s, std::span<const vec3> positions, HumanoidMap& out,
                       std::string& error) {
  out = HumanoidMap{};
  const int n = s.num_joints();
  if (!s.valid() || n < 10 || positions.empty() || positions.size() % static_cast<size_t>(n) != 0)
    return error = "not a humanoid: " + std::to_string(n) + " joints (a body needs at least 10)", false;
  for (const vec3& v : positions)
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      return error = "not a humanoid: joint positions beyond float range", false;
  Posed p{s, positions, n, static_cast<int>(positions.size() / static_cast<size_t>(n)), 0, {}, {}, {}, 0.0f};
  p.children.resize(static_cast<size_t>(n));
  for (int j = 1; j < n; ++j) p.children[static_cast<size_t>(s.parents[static_cast<size_t>(j)])].push_back(j);
  p.mean_y.assign(static_cast<size_t>(n), 0.0f);
  for (int f = 0; f < p.frames; ++f) {
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (int j = 0; j < n; ++j) {
      const float y = p.at(f, j).y;
      p.mean_y[static_cast<size_t>(j)] += y / static_cast<float>(p.frames);
      lo = std::min(lo, y), hi = std::max(hi, y);
    }
    p.lowest.push_back(lo);
    if (hi - lo > p.height) p.height = hi - lo, p.ref = f;
  }
  if (!(p.height > 0.0f)) return error = "not a humanoid: the body has no height", false;
  const float h = p.height;

  std::vector<int> leaves;
  for (int j = 0; j < n; ++j)
    if (p.children[static_cast<size_t>(j)].empty()) leaves.push_back(j);
  std::sort(leaves.begin(), leaves.end(),
            [&](int a, int b) { return p.mean_y[static_cast<size_t>(a)] < p.mean_y[static_cast<size_t>(b)]; });

  // Feet: the lowest leaf, then the lowest leaf of another limb (their chains meet far above).
  std::array<int, 2> foot_leaf{leaves.empty() ? -1 : leaves[0], -1};
  for (size_t i = 1; i < leaves.size() && foot_leaf[1] < 0 && foot_leaf[0] >= 0; ++i) {
    const int meet = common_ancestor(s, foot_leaf[0], leaves[i]);
    if (meet >= 0 && p.ref_distance(meet, leaves[i]) > 0.25f * h && p.ref_distance(meet, foot_leaf[0]) > 0.25f * h)
      foot_leaf[1] = leaves[i];
  }
  if (foot_leaf[1] < 0) return error = "not a humanoid: no two legs (two low chains that meet at a pelvis)", false;
  out.pelvis = common_ancestor(s, foot_leaf[0], foot_leaf[1]);
  const std::array<int, 2> leg_root{chain(s, out.pelvis, foot_leaf[0])[0], chain(s, out.pelvis, foot_leaf[1])[0]};
  auto in_leg = [&](int j) { return descends(s, j, leg_root[0]) || descends(s, j, leg_root[1]); };

  // Head: the highest leaf outside the legs, above the pelvis.
  int head_leaf = -1;
  for (auto it = leaves.rbegin(); it != leaves.rend() && head_leaf < 0; ++it)
    if (!in_leg(*it) && descends(s, *it, out.pelvis) && *it != out.pelvis) head_leaf = *it;
  if (head_leaf < 0 || p.mean_y[static_cast<size_t>(head_leaf)] <= p.mean_y[static_cast<size_t>(out.pelvis)] + 0.2f * h)
    return error = "not a humanoid: no head chain above the pelvis", false;
  std::vector<int> spine_path = chain(s, out.pelvis, head_leaf);  // pelvis excluded
  spine_path.insert(spine_path.begin(), out.pelvis);

  // Arms: the two longest chains branching off the spine above the pelvis.
  std::vector<Branch> branches;
  for (int leaf : leaves) {
    if (leaf == head_leaf || in_leg(leaf) || !descends(s, leaf, out.pelvis)) continue;
    int base = -1;
    for (int j = leaf; j >= 0 && base < 0; j = s.parents[static_cast<size_t>(j)])
      if (std::find(spine_path.begin(), spine_path.end(), j) != spine_path.end()) base = j;
    if (base < 0 || base == out.pelvis || base == head_leaf) continue;
    const std::vector<int> c = chain(s, base, leaf);
    float length = 0.0f;
    for (size_t k = 0; k < c.size(); ++k) length += p.ref_distance(k ? c[k - 1] : base, c[k]);
    auto it = std::find_if(branches.begin(), branches.end(), [&](const Branch& b) { return b.root == c[0]; });
    if (it == branches.end()) branches.push_back({base, c[0], leaf, length});
    else if (length > it->length) it->leaf = leaf, it->length = length;
  }
  std::sort(branches.begin(), branches.end(), [](const Branch& a, const Branch& b) { return a.length > b.length; });
  if (branches.size() < 2 || branches[1].length < 0.2f * h)
    return error = "not a humanoid: no two arms (two long chains branching off the spine)", false;

  // Chest: the arms' branch point nearer the head; neck and head above it.
  const auto spine_index = [&](int j) {
    return static_cast<int>(std::find(spine_path.begin(), spine_path.end(), j) - spine_path.begin());
  };
  int chest_index = std::max(spine_index(branches[0].base), spine_index(branches[1].base));
  std::vector<int> above;  // joints above the chest up to the head, the head chain's End Site left out
  for (size_t k = static_cast<size_t>(chest_index) + 1; k < spine_path.size(); ++k)
    if (!s.is_end_site[static_cast<size_t>(spine_path[k])]) above.push_back(spine_path[k]);
  if (above.empty()) return error = "not a humanoid: nothing above the arms (no neck or head)", false;
  if (above.size() == 1) {  // the arms hang off the neck: the chest is the joint below it
    if (chest_index < 2) return error = "not a humanoid: no spine between the pelvis and the neck", false;
    above.insert(above.begin(), spine_path[static_cast<size_t>(chest_index)]);
    --chest_index;
  }
  out.chest = spine_path[static_cast<size_t>(chest_index)];
  out.neck = above.front();
  out.head = above.back();
  out.head_top = head_leaf != out.head ? p.real_leaf(head_leaf) : -1;
  out.spine.assign(spine_path.begin() + 1, spine_path.begin() + chest_index);

  // Limbs, then which is left.
  Limbs legs{}, arms{};
  for (int i = 0; i < 2; ++i) {
    std::vector<int> path = chain(s, out.pelvis, foot_leaf[i]);
    path.insert(path.begin(), out.pelvis);
    if (!leg_joints(p, path, legs[static_cast<size_t>(i)]))
      return error = "not a humanoid: no hip, knee and ankle on the leg ending at '" +
                     s.joint_names[static_cast<size_t>(foot_leaf[i])] + "'", false;
    const Branch& b = branches[static_cast<size_t>(i)];
    path = chain(s, b.base, b.leaf);
    path.insert(path.begin(), b.base);
    if (!arm_joints(p, path, arms[static_cast<size_t>(i)]))
      return error = "not a humanoid: no shoulder, elbow and wrist on the arm ending at '" +
                     s.joint_names[static_cast<size_t>(b.leaf)] + "'", false;
  }
  assign_sides(p, legs, arms, out);
  return true;
}

float humanoid_head_height(const Skeleton& s, const HumanoidMap& m, std::span<const vec3> positions) {
  const int n = s.num_joints();
  const int frames = static_cast<int>(positions.size() / static_cast<size_t>(n));
  const int top = m.head_top >= 0 ? m.head_top : m.head;
  float best = 0.0f;
  for (int f = 0; f < frames; ++f) {
    const vec3* p = positions.data() + static_cast<size_t>(f) * n;
    float lowest = std::numeric_limits<float>::max();
    for (int side = 0; side < 2; ++side)
      for (int j : {m.foot[side], m.toe[side], m.toe_end[side]})
        if (j >= 0) lowest = std::min(lowest, p[j].y);
    best = std::max(best, p[top].y - lowest);
  }
  return best;
}

float humanoid_stature(const HumanoidMap& m, std::span<const vec3> positions) {
  float legs = 0.0f;
  for (int side = 0; side < 2; ++side)
    legs += glm::length(positions[static_cast<size_t>(m.shin[side])] - positions[static_cast<size_t>(m.thigh[side])]) +
            glm::length(positions[static_cast<size_t>(m.foot[side])] - positions[static_cast<size_t>(m.shin[side])]);
  return 0.5f * legs * (kCanonicalStandingHeightM / kCanonicalLegLengthM);
}

}  // namespace foresight
