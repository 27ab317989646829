// Strikes land where their annotations say: the right limb, at the annotated height band, in
// front of the body, fully extended and momentarily still at the hit frame.
#include "author/author_test_support.hpp"
#include "graph/motion_graph.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace foresight::author::testing {
namespace {

struct Band {
  float lo, hi;
};
Band band_of(const std::string& height) {
  if (height == "low") return {0.5f, 0.8f};
  if (height == "mid") return {1.0f, 1.3f};
  return {1.5f, 1.75f};
}

TEST(Strikes, EachSideHasFourPunchesAndFourKicksAcrossHeights) {
  std::map<std::string, int> count;
  std::map<std::string, std::set<std::string>> heights;
  for (const AuthoredClip& c : library().clips) {
    if (!c.strike) continue;
    const StrikeAnnotation& s = *c.strike;
    ++count[s.kind + "_" + s.side];
    heights[s.kind + "_" + s.side].insert(s.height);
  }
  for (const char* key : {"punch_left", "punch_right", "kick_left", "kick_right"}) {
    EXPECT_GE(count[key], 4) << key;
    EXPECT_EQ(heights[key], (std::set<std::string>{"low", "mid", "high"})) << key;
  }
}

TEST(Strikes, HitWhereAnnotated) {
  const Skeleton& s = library().skeleton;
  for (const AuthoredClip& c : library().clips) {
    if (!c.strike) continue;
    const StrikeAnnotation& a = *c.strike;
    const Clip& clip = c.clip;
    SCOPED_TRACE(clip.name);
    EXPECT_TRUE(c.tags & kTagFight);
    ASSERT_GT(a.hit_frame, 0);
    ASSERT_LT(a.hit_frame, clip.num_frames - 1);
    ASSERT_GE(a.hit_joint, 0);
    // The named limb: Hand for punches, Foot for kicks, on the annotated side.
    const std::string side = a.side == "left" ? "Left" : "Right";
    EXPECT_EQ(s.joint_names[a.hit_joint], side + (a.kind == "punch" ? "Hand" : "Foot"));

    const std::vector<vec3> pos = clip_positions(clip);
    const vec3 hit = at(pos, clip, a.hit_frame, a.hit_joint);
    const Band band = band_of(a.height);
    EXPECT_GE(hit.y, band.lo) << a.height;
    EXPECT_LE(hit.y, band.hi) << a.height;
    // In front of the body: along the stance's facing (frame 0), ahead of the pelvis.
    const float heading = clip_root_track(clip).front().heading_rad;
    const vec3 fwd(std::sin(heading), 0, std::cos(heading));
    const float ahead = glm::dot(hit - at(pos, clip, a.hit_frame, 0), fwd);
    EXPECT_GT(ahead, a.kind == "punch" ? 0.4f : 0.5f);
    // Extended: the limb's root is far from the effector (hooks land with the elbow bent).
    const int limb_root = a.kind == "punch" ? joint(side + "Arm") : joint(side + "UpLeg");
    const float length = a.kind == "punch" ? 0.54f : 0.84f;
    const float reach = glm::length(hit - at(pos, clip, a.hit_frame, limb_root));
    EXPECT_GT(reach, (clip.name.find("hook") != std::string::npos ? 0.6f : 0.85f) * length);
    // The hit frame is the peak: the effector is (nearly) still there, and got there fast.
    const vec3 before = at(pos, clip, a.hit_frame - 1, a.hit_joint);
    const vec3 after = at(pos, clip, a.hit_frame + 1, a.hit_joint);
    EXPECT_LT(glm::length(after - hit) * clip.fps, 0.3f);
    float travelled = 0.0f;
    for (int f = 1; f <= a.hit_frame; ++f)
      travelled += glm::length(at(pos, clip, f, a.hit_joint) - at(pos, clip, f - 1, a.hit_joint));
    EXPECT_GT(travelled, 0.3f);
    EXPECT_GT(glm::length(hit - before), glm::length(after - hit));
    // One-handed / one-footed: the other fist stays up by the head (guard), the other foot stays
    // where it stood.
    const std::string other = a.side == "left" ? "Right" : "Left";
    const int head = joint("Head");
    const auto guard_offset = [&](int f) {
      return glm::length(at(pos, clip, f, joint(other + "Hand")) - at(pos, clip, f, head));
    };
    EXPECT_LT(std::abs(guard_offset(a.hit_frame) - guard_offset(0)), 0.12f);
    const int other_foot = joint(other + "ToeBase");
    EXPECT_LT(glm::length(at(pos, clip, a.hit_frame, other_foot) - at(pos, clip, 0, other_foot)), 0.01f);
  }
}

}  // namespace
}  // namespace foresight::author::testing
