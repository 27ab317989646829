// NPC fighters' streamed poses on the client (fighter_poses.hpp): the history per fighter, played
// at the avatars' render time (slerp / lerp between the bracketing snapshots, held when late or
// early), and the world joints rebuilt on the morphology's skeleton.
#include "support/alloc_counter.hpp"
#include "anim/fk.hpp"
#include "fighter_poses.hpp"
#include "protocol/quantize.hpp"
#include "renderer.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace foresight::client {
namespace {

constexpr int kJoints = 4;

quat yaw(float deg) { return glm::angleAxis(radians(deg), vec3(0, 1, 0)); }

protocol::FighterPoseState pose(uint32_t avatar, vec3 pelvis, float joint1_yaw_deg, uint8_t morphology = 0,
                                int joints = kJoints) {
  protocol::FighterPoseState f;
  f.avatar = avatar;
  f.morphology = morphology;
  f.pelvis_m = pelvis;
  f.num_joints = static_cast<uint16_t>(joints);
  for (int j = 0; j < joints; ++j) f.rotations[static_cast<size_t>(j)] = protocol::quantize_rotation(quat(1, 0, 0, 0));
  f.rotations[1] = protocol::quantize_rotation(yaw(joint1_yaw_deg));
  return f;
}

// Angle of joint 1's rotation about +Y, degrees.
float joint1_yaw(const FighterPoseSample& s) {
  const vec3 x = s.local_rot[1] * vec3(1, 0, 0);
  return degrees(std::atan2(-x.z, x.x));
}

TEST(ClientFighterPoses, InterpolatesBetweenTheBracketingSnapshots) {
  FighterPoses poses;
  const protocol::FighterPoseState a = pose(7, vec3(0, 1, 0), 0), b = pose(7, vec3(1, 1, 2), 90);
  poses.push(1.00, {&a, 1});
  poses.push(1.05, {&b, 1});
  std::vector<FighterPoseSample> out;
  poses.sample(1.025, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].avatar, 7u);
  EXPECT_EQ(out[0].num_joints, kJoints);
  EXPECT_NEAR(out[0].pelvis_m.x, 0.5f, 1e-4f);
  EXPECT_NEAR(out[0].pelvis_m.z, 1.0f, 1e-4f);
  EXPECT_NEAR(joint1_yaw(out[0]), 45.0f, 0.5f) << "slerped half way";
  poses.sample(1.04, out);
  EXPECT_NEAR(out[0].pelvis_m.x, 0.8f, 1e-4f);
  EXPECT_NEAR(joint1_yaw(out[0]), 72.0f, 0.5f);
  EXPECT_NEAR(glm::length(out[0].local_rot[1]), 1.0f, 1e-5f);
}

TEST(ClientFighterPoses, HoldsTheNewestWhenLateAndTheOldestWhenEarly) {
  FighterPoses poses;
  const protocol::FighterPoseState a = pose(3, vec3(0, 1, 0), 0), b = pose(3, vec3(2, 1, 0), 60);
  poses.push(2.0, {&a, 1});
  poses.push(2.1, {&b, 1});
  std::vector<FighterPoseSample> out;
  poses.sample(5.0, out);  // snapshots late: the newest, held (no extrapolation)
  ASSERT_EQ(out.size(), 1u);
  EXPECT_FLOAT_EQ(out[0].pelvis_m.x, 2.0f);
  EXPECT_NEAR(joint1_yaw(out[0]), 60.0f, 0.5f);
  poses.sample(1.0, out);  // before the oldest
  EXPECT_FLOAT_EQ(out[0].pelvis_m.x, 0.0f);
  poses.sample(2.1, out);  // exactly on a sample
  EXPECT_FLOAT_EQ(out[0].pelvis_m.x, 2.0f);
}

TEST(ClientFighterPoses, SameTickReplacesOlderIsIgnored) {
  FighterPoses poses;
  const protocol::FighterPoseState a = pose(1, vec3(0, 1, 0), 0), b = pose(1, vec3(1, 1, 0), 0),
                                   again = pose(1, vec3(3, 1, 0), 0), old = pose(1, vec3(-9, 1, 0), 0);
  poses.push(1.0, {&a, 1});
  poses.push(1.1, {&b, 1});
  poses.push(1.1, {&again, 1});  // a later part of the same tick
  poses.push(0.5, {&old, 1});    // older than everything: dropped
  std::vector<FighterPoseSample> out;
  poses.sample(1.05, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].pelvis_m.x, 1.5f, 1e-4f);
  poses.sample(0.5, out);
  EXPECT_FLOAT_EQ(out[0].pelvis_m.x, 0.0f);
}

TEST(ClientFighterPoses, KeepsAFixedHistoryAndSortsFightersById) {
  FighterPosesConfig config;
  config.samples_per_fighter = 4;
  FighterPoses poses(config);
  for (int i = 0; i < 20; ++i) {
    const protocol::FighterPoseState f[2] = {pose(9, vec3(static_cast<float>(i), 1, 0), 0),
                                             pose(4, vec3(0, 1, static_cast<float>(i)), 0)};
    poses.push(0.05 * i, f);
  }
  EXPECT_EQ(poses.size(), 2);
  std::vector<FighterPoseSample> out;
  poses.sample(0.05 * 17.5, out);  // within the last 4 samples
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].avatar, 4u);
  EXPECT_EQ(out[1].avatar, 9u);
  EXPECT_NEAR(out[1].pelvis_m.x, 17.5f, 1e-3f);
  EXPECT_NEAR(out[0].pelvis_m.z, 17.5f, 1e-3f);
  poses.sample(0.0, out);  // long gone from the ring: the oldest kept, held
  EXPECT_NEAR(out[1].pelvis_m.x, 16.0f, 1e-3f);
}

TEST(ClientFighterPoses, ForgetsFightersGoneFromTheSnapshotsAndCapsTheirNumber) {
  FighterPosesConfig config;
  config.max_fighters = 2;
  config.forget_after_s = 0.5;
  FighterPoses poses(config);
  const protocol::FighterPoseState three[3] = {pose(1, vec3(0), 0), pose(2, vec3(0), 0), pose(3, vec3(0), 0)};
  poses.push(1.0, three);
  EXPECT_EQ(poses.size(), 2) << "a third fighter has no slot";
  const protocol::FighterPoseState only2 = pose(2, vec3(0), 0);
  poses.push(1.3, {&only2, 1});
  EXPECT_EQ(poses.size(), 2) << "fighter 1 missing for 0.3 s: still kept";
  poses.push(1.6, {&only2, 1});
  EXPECT_EQ(poses.size(), 1) << "fighter 1 missing for 0.6 s: gone";
  const protocol::FighterPoseState two[2] = {pose(2, vec3(0), 0), pose(3, vec3(0), 0)};
  poses.push(1.7, two);  // the freed slot takes fighter 3
  std::vector<FighterPoseSample> out;
  poses.sample(1.7, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].avatar, 2u);
  EXPECT_EQ(out[1].avatar, 3u);
  poses.clear();
  poses.sample(1.7, out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(poses.size(), 0);
}

TEST(ClientFighterPoses, SlerpTakesTheShorterArcAndSwitchesMorphologyAtHalfWay) {
  FighterPoseSample a, b, out;
  a.num_joints = b.num_joints = 2;
  a.local_rot[0] = b.local_rot[0] = quat(1, 0, 0, 0);
  a.local_rot[1] = yaw(10);
  b.local_rot[1] = -yaw(30);  // the same rotation as yaw(30), opposite sign
  interpolate_fighter(a, b, 0.5f, out);
  EXPECT_NEAR(joint1_yaw(out), 20.0f, 0.1f);
  b.morphology = 2;
  interpolate_fighter(a, b, 0.4f, out);
  EXPECT_EQ(out.morphology, 0);
  interpolate_fighter(a, b, 0.6f, out);
  EXPECT_EQ(out.morphology, 2);
}

TEST(ClientFighterPoses, JointPositionsOnTheMorphologysSkeleton) {
  const std::vector<Morphology> morphologies = default_morphologies();
  ASSERT_EQ(morphologies.size(), 5u);
  const Morphology& tall = morphologies[1];
  const int n = tall.skeleton.num_joints();
  FighterPoseSample s;
  s.morphology = 1;
  s.num_joints = static_cast<uint16_t>(n);
  s.pelvis_m = vec3(2, 1.1f, -3);
  for (int j = 0; j < n; ++j) s.local_rot[static_cast<size_t>(j)] = yaw(static_cast<float>(j));
  std::vector<vec3> local, global;
  std::vector<quat> rot;
  ASSERT_TRUE(fighter_joint_positions(morphologies, s, local, global, rot));
  ASSERT_EQ(static_cast<int>(global.size()), n);
  EXPECT_EQ(global[0], s.pelvis_m);
  // The same FK by hand.
  std::vector<vec3> lp = tall.skeleton.rest_offsets_m, gp(static_cast<size_t>(n));
  std::vector<quat> gr(static_cast<size_t>(n));
  lp[0] = s.pelvis_m;
  fk_pose(tall.skeleton, lp, std::span<const quat>(s.local_rot.data(), static_cast<size_t>(n)), gp, gr);
  for (int j = 0; j < n; ++j) EXPECT_LT(glm::length(gp[static_cast<size_t>(j)] - global[static_cast<size_t>(j)]), 1e-6f);
  // Wire data naming a morphology or joint count the client does not have draws nothing.
  s.morphology = 5;
  EXPECT_FALSE(fighter_joint_positions(morphologies, s, local, global, rot));
  s.morphology = 1;
  s.num_joints = static_cast<uint16_t>(n - 1);
  EXPECT_FALSE(fighter_joint_positions(morphologies, s, local, global, rot));
}

TEST(ClientFighterPoses, NoAllocationOnceWarm) {
  FighterPoses poses;
  const int n = default_morphologies()[0].skeleton.num_joints();
  std::vector<protocol::FighterPoseState> wire;
  for (uint32_t id = 10; id < 15; ++id) wire.push_back(pose(id, vec3(0, 1, 0), 5.0f * static_cast<float>(id), 0, n));
  const std::vector<Morphology> morphologies = default_morphologies();
  std::vector<FighterPoseSample> out;
  out.reserve(static_cast<size_t>(poses.config().max_fighters));
  std::vector<vec3> local, global;
  std::vector<quat> rot;
  auto step = [&](int i) {
    poses.push(0.05 * i, wire);
    poses.sample(0.05 * i - 0.1, out);
    for (const FighterPoseSample& f : out) fighter_joint_positions(morphologies, f, local, global, rot);
  };
  for (int i = 0; i < 5; ++i) step(i);  // warm: scratch sized
  test::AllocationCount count;
  for (int i = 5; i < 200; ++i) step(i);
  EXPECT_EQ(count.allocations(), 0);
  EXPECT_EQ(out.size(), 5u);
}

// The renderer's instance lists (no GL context needed to fill them): a fighter is one capsule
// per bone of its morphology's skeleton and a contact shadow under each foot standing on the
// floor; a strike marker is one box.
TEST(ClientFighterPoses, DrawnAsOneCapsulePerBoneOfItsMorphologyWithShadowedFeet) {
  const std::vector<Morphology> morphologies = default_morphologies();
  for (size_t m = 0; m < morphologies.size(); ++m) {
    const Skeleton& sk = morphologies[m].skeleton;
    FighterPoseSample s;
    s.morphology = static_cast<uint8_t>(m);
    s.num_joints = static_cast<uint16_t>(sk.num_joints());
    s.pelvis_m = vec3(0, 1, 0);
    std::vector<vec3> local, global;
    std::vector<quat> rot;
    ASSERT_TRUE(fighter_joint_positions(morphologies, s, local, global, rot));
    float lowest = global.front().y;  // stand it on the floor
    for (const vec3& p : global) lowest = std::min(lowest, p.y);
    for (vec3& p : global) p.y -= lowest;
    size_t bones = 0;
    for (size_t j = 1; j < global.size(); ++j)
      if (glm::length(global[j] - global[static_cast<size_t>(sk.parents[j])]) >= 0.01f) ++bones;
    Renderer renderer;  // no init(): no GL objects
    renderer.begin_frame();
    renderer.add_skeleton(sk.parents, global, vec3(0.72f, 0.06f, 0.10f));
    EXPECT_EQ(renderer.avatar_instances(), bones) << morphologies[m].name;
    EXPECT_EQ(renderer.shadow_instances(), 2u) << "feet on the floor: " << morphologies[m].name;
    renderer.add_marker(vec3(0, 1.6f, 0), 0.2f, vec3(1, 0, 1));
    EXPECT_EQ(renderer.avatar_instances(), bones + 1);
    // Lifted 1 m, the feet cast no contact shadow.
    for (vec3& p : global) p.y += 1.0f;
    renderer.begin_frame();
    renderer.add_skeleton(sk.parents, global, vec3(0.72f, 0.06f, 0.10f));
    EXPECT_EQ(renderer.shadow_instances(), 0u);
  }
}

}  // namespace
}  // namespace foresight::client
