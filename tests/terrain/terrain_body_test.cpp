// The terrain body on the default skeleton: the mapped pose puts the skeleton's joints where the
// planners' models put them (shoulders, elbows, hands, knees, ankles), for every frame of a walk
// and for random upper-body configurations, so what the player sees is what was collision-checked.
#include "terrain/terrain_body.hpp"
#include "terrain/terrain_walker.hpp"
#include "terrain_test_util.hpp"

#include "author/default_skeleton.hpp"
#include "anim/fk.hpp"
#include "math/splitmix64.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace foresight::terrain {
namespace {

struct Fk {
  Skeleton skeleton = author::default_skeleton();
  TerrainSkeletonJoints joints;
  Pose pose;
  std::vector<vec3> pos;
  std::vector<quat> rot;
  Fk() {
    EXPECT_TRUE(terrain_skeleton_joints(skeleton, joints));
    pos.resize(static_cast<size_t>(skeleton.num_joints()));
    rot.resize(pos.size());
  }
  void run(const TerrainBodyPose& body) {
    terrain_body_to_pose(body, skeleton, joints, pose);
    fk_pose(skeleton, pose.local_pos_m, pose.local_rot, pos, rot);
  }
  vec3 at(const char* name) const { return pos[static_cast<size_t>(skeleton.find_joint(name))]; }
};

TEST(TerrainBody, ArmsAndHeadMatchTheUpperBodyModel) {
  Fk fk;
  const UpperBodyParams p;
  SplitMix64 rng{7};
  for (int trial = 0; trial < 200; ++trial) {
    TerrainBodyPose body;
    body.pelvis_m = vec3(rng.uniform(-5, 5), rng.uniform(0.8f, 1.1f), rng.uniform(-5, 5));
    body.heading_rad = rng.uniform(-kPi, kPi);
    for (int i = 0; i < kWaistDof; ++i)
      body.upper.waist[static_cast<size_t>(i)] = rng.uniform(p.waist_min[static_cast<size_t>(i)], p.waist_max[static_cast<size_t>(i)]);
    for (auto& arm : body.upper.arms)
      for (int i = 0; i < kArmDof; ++i)
        arm[static_cast<size_t>(i)] = rng.uniform(p.arm_min[static_cast<size_t>(i)], p.arm_max[static_cast<size_t>(i)]);
    fk.run(body);
    const PelvisFrame frame{body.pelvis_m, body.heading_rad, 0.0f, 0.0f};
    for (BodyPart part : {BodyPart::kLeftArm, BodyPart::kRightArm}) {
      const ArmPoints a = arm_points(p, frame, body.upper.waist, part, body.upper.part(part));
      const bool left = part == BodyPart::kLeftArm;
      EXPECT_LT(glm::length(fk.at(left ? "LeftArm" : "RightArm") - a.shoulder_m), 1e-4f) << trial;
      EXPECT_LT(glm::length(fk.at(left ? "LeftForeArm" : "RightForeArm") - a.elbow_m), 1e-4f) << trial;
      EXPECT_LT(glm::length(fk.at(left ? "LeftHand_End" : "RightHand_End") - a.hand_m), 1e-4f) << trial;
    }
    // The model's head sphere sits 7 cm above the Head joint, its top 1 cm above HeadTop_End.
    EXPECT_LT(glm::length(fk.at("HeadTop_End") - head_top(p, frame, body.upper.waist)), 0.011f) << trial;
  }
}

// Walks `path` for 4 m with the TerrainWalker and calls f(body, walk frame, swing_left, phase) at 9
// phases of every committed step, the body as the skeleton shows it (fk already run).
template <class F>
void walk_sampled(Fk& fk, const Scene& scene, const GroundPath& path, F f) {
  auto walker = std::make_unique<TerrainWalker>();
  ASSERT_TRUE(terrain_walker_init(*walker, TerrainWalkerConfig{}));
  ASSERT_TRUE(terrain_walker_start(*walker, scene, path, 9.0f));
  const WalkParams& walk = walker->config.footsteps.walk;
  while (terrain_walker_travelled_m(*walker) < 4.0f) {
    ASSERT_EQ(terrain_walker_step(*walker, scene), TerrainStepStatus::kOk);
    const bool swing_left = !walker->swing_left;  // the step just committed
    for (int k = 0; k <= 8; ++k) {
      const float phase = static_cast<float>(k) / 8.0f;
      const TerrainBodyPose body = terrain_body_at(walker->plan.steps[0], walk, path, phase, swing_left, UpperBodyConfig{});
      fk.run(body);
      WalkFrame w;
      walk_step_sample(walker->plan.steps[0], walk, phase, w);
      f(body, w, swing_left, phase);
    }
  }
}

TEST(TerrainBody, LegsMatchTheProceduralWalkAlongAWalk) {
  Fk fk;
  Scene scene = test::flat_scene();
  scene.terrain.steps.push_back({"block", vec3(-1.0f, 0.0f, 2.0f), vec3(1.0f, 0.15f, 3.0f)});
  const GroundPath path{{0.0f, 0.0f}, 0.0f, 0.0f};  // along +Z: forward (0, 0, 1), left +X
  int frames = 0;
  float highest_ankle = 0.0f;
  walk_sampled(fk, scene, path, [&](const TerrainBodyPose&, const WalkFrame& w, bool swing_left, float phase) {
    // Sagittal (forward = z, up = y) positions of the model; the skeleton's legs hang 9 cm to
    // each side of the centre line.
    auto expect_at = [&](const char* joint, vec2 model, float side) {
      const vec3 got = fk.at(joint);
      EXPECT_NEAR(got.z, model.x, 1e-4f) << joint << " phase " << phase;
      EXPECT_NEAR(got.y, model.y, 1e-4f) << joint << " phase " << phase;
      EXPECT_NEAR(got.x, side * 0.09f, 1e-4f) << joint;
    };
    const float swing_side = swing_left ? 1.0f : -1.0f;
    expect_at(swing_left ? "LeftLeg" : "RightLeg", w.swing_knee_m, swing_side);
    expect_at(swing_left ? "LeftFoot" : "RightFoot", w.swing_ankle_m, swing_side);
    expect_at(swing_left ? "RightLeg" : "LeftLeg", w.stance_knee_m, -swing_side);
    expect_at(swing_left ? "RightFoot" : "LeftFoot", w.stance_ankle_m, -swing_side);
    highest_ankle = std::max(highest_ankle, w.stance_ankle_m.y);
    ++frames;
  });
  EXPECT_GT(frames, 40);
  EXPECT_GT(highest_ankle, 0.15f + WalkParams{}.ankle_height_m - 0.01f) << "the walk never stood on the block";
}

TEST(TerrainBody, OnACurvedPathEachFootFacesThePathWhereItStands) {
  // The hip's second DOF: along an arc (radius 2.5 m) the pelvis turns while a planted foot keeps
  // the heading of the path at its foothold, and the feet stay near the arc.
  Fk fk;
  const GroundPath path = ground_path_from_velocity({0.0f, 0.0f}, 0.0f, 1.0f, 0.4f);
  float largest_yaw = 0.0f;
  walk_sampled(fk, test::flat_scene(), path, [&](const TerrainBodyPose& body, const WalkFrame& w, bool swing_left, float phase) {
    const char* stance_foot = swing_left ? "RightFoot" : "LeftFoot";
    const char* stance_toe = swing_left ? "RightToeBase" : "LeftToeBase";
    const float foot_heading = heading_of(fk.at(stance_toe) - fk.at(stance_foot));
    EXPECT_NEAR(wrap_angle(foot_heading - ground_path_heading(path, w.stance_ankle_m.x)), 0.0f, 0.02f) << phase;
    // The ankle 9 cm beside the path's point at its distance (the arc bends under it).
    const float off = glm::length(ground(fk.at(stance_foot)) - ground_path_point(path, w.stance_ankle_m.x));
    EXPECT_NEAR(off, 0.09f, 0.03f) << phase;
    largest_yaw = std::max(largest_yaw, std::abs(body.hip_yaw_rad[swing_left ? 1 : 0]));
  });
  EXPECT_GT(largest_yaw, 0.05f) << "the pelvis turned away from the planted foot";
}

TEST(TerrainBody, AnglesRoundTripAndLerpEnds) {
  TerrainBodyPose a;
  std::array<float, kTerrainBodyAngles> angles;
  for (size_t i = 0; i < angles.size(); ++i) angles[i] = 0.1f * static_cast<float>(i) - 0.7f;
  terrain_body_set_angles(a, angles);
  EXPECT_EQ(terrain_body_angles(a), angles);
  TerrainBodyPose b = a;
  b.heading_rad = 3.0f;
  a.heading_rad = -3.0f;  // the shorter arc crosses +-pi
  b.pelvis_m = vec3(1.0f, 2.0f, 3.0f);
  b.legs[0].knee_rad = 1.5f;
  const TerrainBodyPose mid = terrain_body_lerp(a, b, 0.5f);
  EXPECT_NEAR(std::abs(mid.heading_rad), kPi, 1e-4f);
  EXPECT_NEAR(mid.legs[0].knee_rad, 0.5f * (a.legs[0].knee_rad + 1.5f), 1e-6f);
  EXPECT_EQ(terrain_body_lerp(a, b, 1.0f).pelvis_m, b.pelvis_m);
}

TEST(TerrainBody, SkeletonWithoutTheJointsIsRefused) {
  Skeleton s = author::default_skeleton();
  TerrainSkeletonJoints j;
  EXPECT_TRUE(terrain_skeleton_joints(s, j));
  s.joint_names[static_cast<size_t>(s.find_joint("RightForeArm"))] = "RightElbow";
  EXPECT_FALSE(terrain_skeleton_joints(s, j));
}

}  // namespace
}  // namespace foresight::terrain
