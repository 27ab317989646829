// The library as data: determinism, clip conventions, and the manifest's graph.
#include "author/author_test_support.hpp"
#include "graph/motion_graph.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <queue>
#include <set>

namespace foresight::author::testing {
namespace {

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(DefaultLibrary, IsDeterministic) {
  const DefaultLibrarySpec a = build_default_library();
  const DefaultLibrarySpec b = build_default_library();
  ASSERT_EQ(a.clips.size(), b.clips.size());
  for (size_t i = 0; i < a.clips.size(); ++i) {
    const Clip& ca = a.clips[i].clip;
    const Clip& cb = b.clips[i].clip;
    EXPECT_EQ(ca.name, cb.name);
    EXPECT_EQ(ca.num_frames, cb.num_frames);
    EXPECT_TRUE(same_bytes(ca.local_pos_m, cb.local_pos_m)) << ca.name;
    EXPECT_TRUE(same_bytes(ca.local_rot, cb.local_rot)) << ca.name;
    EXPECT_EQ(a.clips[i].tags, b.clips[i].tags);
  }
  ASSERT_EQ(a.transitions.size(), b.transitions.size());
  for (size_t i = 0; i < a.transitions.size(); ++i) {
    EXPECT_EQ(a.transitions[i].from, b.transitions[i].from);
    EXPECT_EQ(a.transitions[i].to, b.transitions[i].to);
    EXPECT_EQ(a.transitions[i].blend_frames, b.transitions[i].blend_frames);
  }
  EXPECT_TRUE(same_bytes(a.skeleton.rest_offsets_m, b.skeleton.rest_offsets_m));
  // And the cached copy the other tests read is the same library.
  EXPECT_TRUE(same_bytes(a.clips.front().clip.local_rot, library().clips.front().clip.local_rot));
}

TEST(DefaultLibrary, HasEveryRequiredClip) {
  // Steps come on either foot: walk_l is a left step (right-foot strike -> left-foot strike).
  for (const char* step :
       {"walk", "walk_slow", "walk_turn_left_22", "walk_turn_right_22", "walk_turn_left_45",
        "walk_turn_right_45", "walk_to_slow", "slow_to_walk", "walk_start", "walk_stop", "run",
        "run_turn_left_22", "run_turn_right_22", "walk_to_run", "run_to_walk", "crouch_walk",
        "crouch_walk_turn_left_22", "crouch_walk_turn_right_22", "crouch_walk_start",
        "crouch_walk_stop", "walk_to_crouch_walk", "crouch_walk_to_walk"})
    for (const char* foot : {"_l", "_r"})
      EXPECT_NE(find_clip(std::string(step) + foot), nullptr) << step << foot;
  for (const char* name :
       {"idle", "crouch_idle", "crouch_down", "stand_up", "side_step_left", "side_step_right",
        "step_forward_left", "step_forward_right",
        "idle_turn_left_90", "idle_turn_right_90", "idle_turn_180", "crouch_idle_turn_left_90",
        "crouch_idle_turn_right_90", "fight_stance", "idle_to_stance", "stance_to_idle"})
    EXPECT_NE(find_clip(name), nullptr) << name;
}

TEST(DefaultLibrary, ClipsFollowTheConventions) {
  const DefaultLibrarySpec& lib = library();
  std::set<std::string> names;
  for (const AuthoredClip& c : lib.clips) {
    const Clip& clip = c.clip;
    SCOPED_TRACE(clip.name);
    EXPECT_TRUE(names.insert(clip.name).second) << "duplicate name";
    EXPECT_EQ(clip.fps, 30.0f);
    EXPECT_EQ(clip.num_joints, lib.skeleton.num_joints());
    EXPECT_GE(clip.num_frames, 10);
    ASSERT_EQ(clip.local_pos_m.size(), static_cast<size_t>(clip.num_frames * clip.num_joints));
    ASSERT_EQ(clip.local_rot.size(), clip.local_pos_m.size());
    EXPECT_NE(c.tags, 0u);
    for (int f = 0; f < clip.num_frames; ++f) {
      for (int j = 1; j < clip.num_joints; ++j)
        ASSERT_EQ(clip.frame_pos(f)[j], lib.skeleton.rest_offsets_m[j]) << "frame " << f;
      for (int j = 0; j < clip.num_joints; ++j)
        ASSERT_NEAR(glm::length(clip.frame_rot(f)[j]), 1.0f, 1e-4f);
    }
    // Starts at the ground origin, facing +Z (give or take the pelvis's own sway and twist).
    const Placement start = clip_root_track(clip).front();
    EXPECT_LT(glm::length(start.pos_m), 0.1f);
    EXPECT_LT(std::abs(start.heading_rad), radians(8.0f));
  }
}

TEST(DefaultLibrary, TagsDescribeTheClips) {
  const int head_top = joint("HeadTop_End");
  int crouched = 0;
  for (const AuthoredClip& c : library().clips) {
    const std::string& n = c.clip.name;
    SCOPED_TRACE(n);
    const auto has = [&](const char* part) { return n.find(part) != std::string::npos; };
    // kTagCrouch promises a low body in every frame (planners use it to pass under things), so
    // it marks exactly the clips that stay crouched, and never the half-standing transitions.
    const float top = max_joint_height(c.clip, head_top);
    EXPECT_EQ((c.tags & kTagCrouch) != 0, top <= 1.15f) << "head top " << top;
    crouched += (c.tags & kTagCrouch) != 0;
    if (has("turn")) { EXPECT_TRUE(c.tags & kTagTurn); }
    if (has("run")) { EXPECT_TRUE(c.tags & kTagRun); }
    if (has("walk") || has("side_step")) { EXPECT_TRUE(c.tags & kTagLocomotion); }
    if (c.strike || has("stance")) { EXPECT_TRUE(c.tags & kTagFight); }
    if (n == "idle" || n == "crouch_idle") { EXPECT_TRUE(c.tags & kTagIdle); }
    // Clips that stay in place are not locomotion.
    const std::vector<Placement> track = clip_root_track(c.clip);
    if (glm::length(track.back().pos_m - track.front().pos_m) < 0.1f) {
      EXPECT_FALSE(c.tags & kTagLocomotion);
    }
  }
  EXPECT_GE(crouched, 6);
}

TEST(Manifest, NamesExistAndBlendsAreShort) {
  const DefaultLibrarySpec& lib = library();
  ASSERT_FALSE(lib.transitions.empty());
  std::set<std::pair<std::string, std::string>> seen;
  for (const DeclaredTransition& t : lib.transitions) {
    EXPECT_NE(find_clip(t.from), nullptr) << t.from;
    EXPECT_NE(find_clip(t.to), nullptr) << t.to;
    EXPECT_GE(t.blend_frames, 4);
    EXPECT_LE(t.blend_frames, 8);
    EXPECT_TRUE(seen.insert({t.from, t.to}).second) << t.from << " -> " << t.to;
  }
}

std::map<std::string, std::set<std::string>> successor_map(bool reversed) {
  std::map<std::string, std::set<std::string>> next;
  for (const DeclaredTransition& t : library().transitions)
    next[reversed ? t.to : t.from].insert(reversed ? t.from : t.to);
  return next;
}

std::set<std::string> reachable(const std::string& from, bool reversed) {
  const auto next = successor_map(reversed);
  std::set<std::string> seen{from};
  std::queue<std::string> open;
  open.push(from);
  while (!open.empty()) {
    const std::string n = open.front();
    open.pop();
    const auto it = next.find(n);
    if (it == next.end()) continue;
    for (const std::string& m : it->second)
      if (seen.insert(m).second) open.push(m);
  }
  return seen;
}

TEST(Manifest, GraphIsStronglyConnected) {
  const std::set<std::string> forward = reachable("idle", false);
  const std::set<std::string> backward = reachable("idle", true);
  for (const AuthoredClip& c : library().clips) {
    EXPECT_TRUE(forward.count(c.clip.name)) << c.clip.name << " not reachable from idle";
    EXPECT_TRUE(backward.count(c.clip.name)) << "idle not reachable from " << c.clip.name;
  }
}

// Clips reachable from `from` in at most `depth` transitions (not counting `from` itself).
std::set<std::string> within(const std::string& from, int depth) {
  const auto next = successor_map(false);
  std::set<std::string> seen, frontier{from};
  for (int d = 0; d < depth; ++d) {
    std::set<std::string> further;
    for (const std::string& n : frontier) {
      const auto it = next.find(n);
      if (it == next.end()) continue;
      for (const std::string& m : it->second)
        if (seen.insert(m).second) further.insert(m);
    }
    frontier = further;
  }
  return seen;
}

TEST(Manifest, IsRichEnoughToSteer) {
  const auto next = successor_map(false);
  // From any walking step (either foot, straight or turning): the next step can go straight,
  // turn either way by 22.5 or 45 deg, stop, or start running / crouching; within two clips the
  // slow walk, the run and the crouch-walk themselves.
  for (const char* step : {"walk_l", "walk_r", "walk_turn_left_45_l", "walk_turn_right_22_r",
                           "walk_start_l", "walk_start_r", "slow_to_walk_l", "run_to_walk_r",
                           "crouch_walk_to_walk_l"}) {
    SCOPED_TRACE(step);
    const std::string same = std::string(step).back() == 'l' ? "_l" : "_r";
    const std::string other = same == "_l" ? "_r" : "_l";
    const auto& one = next.at(step);
    for (const char* name :
         {"walk", "walk_turn_left_22", "walk_turn_right_22", "walk_turn_left_45",
          "walk_turn_right_45", "walk_stop", "walk_to_run", "walk_to_crouch_walk", "walk_to_slow"})
      EXPECT_TRUE(one.count(name + other)) << "-> " << name << other;
    const std::set<std::string> two = within(step, 2);
    for (const char* gait : {"walk_slow", "run", "crouch_walk"})  // steps alternate feet
      EXPECT_TRUE(two.count(gait + same)) << "within two: " << gait << same;
    EXPECT_TRUE(two.count("idle"));
  }
  // Steps alternate feet: a left step is followed by right steps only.
  for (const std::string& n : next.at("walk_l")) EXPECT_EQ(n.back(), 'r') << "walk_l -> " << n;
  EXPECT_TRUE(next.at("idle").count("walk_start_l"));
  EXPECT_TRUE(next.at("idle").count("walk_start_r"));
  EXPECT_TRUE(next.at("walk_stop_l").count("idle"));
  EXPECT_TRUE(next.at("run_l").count("run_turn_left_22_r"));
  EXPECT_TRUE(next.at("run_l").count("run_turn_right_22_r"));
  EXPECT_TRUE(next.at("run_l").count("run_to_walk_r"));
  EXPECT_TRUE(next.at("walk_to_crouch_walk_l").count("crouch_walk_r"));
  EXPECT_TRUE(next.at("crouch_walk_l").count("crouch_walk_to_walk_r"));
  EXPECT_TRUE(next.at("crouch_walk_l").count("crouch_walk_turn_left_22_r"));
  EXPECT_TRUE(next.at("crouch_walk_l").count("crouch_walk_stop_r"));
  // Turning round in a dead end: from standing, and from the last step of a walk.
  for (const char* turn : {"idle_turn_left_90", "idle_turn_right_90", "idle_turn_180"}) {
    EXPECT_TRUE(next.at("idle").count(turn)) << turn;
    EXPECT_TRUE(next.at(turn).count("walk_start_l")) << turn;
    EXPECT_TRUE(next.at("walk_stop_r").count(turn)) << turn;
  }
  EXPECT_TRUE(next.at("crouch_idle").count("crouch_idle_turn_left_90"));
  EXPECT_TRUE(next.at("crouch_walk_stop_l").count("crouch_idle_turn_right_90"));
  // The fight is entered and left through the idle.
  EXPECT_TRUE(next.at("idle").count("idle_to_stance"));
  EXPECT_TRUE(next.at("idle_to_stance").count("fight_stance"));
  EXPECT_TRUE(next.at("fight_stance").count("stance_to_idle"));
  EXPECT_TRUE(next.at("stance_to_idle").count("idle"));
  // Strikes: out of and back into the stance, nothing else.
  int strikes = 0;
  for (const AuthoredClip& c : library().clips) {
    if (!c.strike) continue;
    ++strikes;
    EXPECT_TRUE(next.at("fight_stance").count(c.clip.name)) << c.clip.name;
    EXPECT_EQ(next.at(c.clip.name), std::set<std::string>{"fight_stance"}) << c.clip.name;
  }
  EXPECT_EQ(strikes, 16);
}

TEST(Manifest, EveryLocomotionClipReachesATurnEachWayWithinTwoTransitions) {
  // The controller's latency budget: whatever the avatar is doing, a clip that turns left and
  // one that turns right are at most two boundaries away.
  for (const AuthoredClip& c : library().clips) {
    if (!(c.tags & kTagLocomotion)) continue;
    bool left = false, right = false;
    for (const std::string& n : within(c.clip.name, 2)) {
      const AuthoredClip* t = find_clip(n);
      if (!(t->tags & kTagTurn)) continue;
      const std::vector<Placement> track = clip_root_track(t->clip);
      const float turn = track.back().heading_rad - track.front().heading_rad;
      left |= turn > radians(10.0f);
      right |= turn < -radians(10.0f);
    }
    EXPECT_TRUE(left) << c.clip.name << ": no left turn within two transitions";
    EXPECT_TRUE(right) << c.clip.name << ": no right turn within two transitions";
  }
}

}  // namespace
}  // namespace foresight::author::testing
