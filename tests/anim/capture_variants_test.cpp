// A studio's capture is not ours: the same Bandai take, rewritten in code the ways other
// exporters write it (another unit or no unit at all, other joint names, an extra dummy root, the
// root position relative to its OFFSET, other Euler orders, other frame rates, finger and twist
// joints), must import to the same body on the canonical skeleton: standing height within 1 cm,
// feet on the floor within 2 cm, and every canonical joint where the original put it.
#include "import/bvh_import.hpp"
#include "anim/canonical_skeleton.hpp"
#include "anim/fk.hpp"
#include "anim/root_motion.hpp"
#include "support/bvh_variants.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>

namespace foresight {
namespace {

using namespace test;

const char* const kTake = "locomotion/bandai_dataset-2_walk-turn-left_normal_001.bvh";

BvhDocument original() {
  BvhDocument doc;
  std::string error;
  EXPECT_TRUE(bvh_load(test::mocap_dir() / kTake, doc, error)) << error;
  return doc;
}

struct Body {
  Skeleton skeleton;
  Clip clip;
  BvhImportReport report;
  std::vector<vec3> positions;
};

Body import_canonical(const BvhDocument& doc, BvhImportOptions options = {}) {
  Body b;
  options.canonical = true;
  std::string error;
  EXPECT_TRUE(clip_from_bvh(doc, "variant", options, b.skeleton, b.clip, &b.report, error)) << error;
  fk_clip_positions(b.skeleton, b.clip, b.positions);
  return b;
}

// Same standing height (1 cm), feet on the floor as before (2 cm), and every canonical joint of
// every frame within `tolerance_m` of the original's (but the hand ends, where fingers say more
// than a bare hand, when `hand_ends` is false).
void expect_same_body(const Body& got, const Body& want, float tolerance_m, bool hand_ends = true) {
  EXPECT_NEAR(got.report.standing_height_m, want.report.standing_height_m, 0.01f);
  EXPECT_NEAR(got.report.lowest_foot_m, want.report.lowest_foot_m, 0.02f);
  EXPECT_LT(std::fabs(got.report.lowest_foot_m), 0.10f) << "feet off the floor";
  ASSERT_EQ(got.skeleton.joint_names, want.skeleton.joint_names);
  ASSERT_EQ(got.positions.size(), want.positions.size());
  float worst = 0.0f;
  for (size_t i = 0; i < got.positions.size(); ++i) {
    const int joint = static_cast<int>(i % kCanonJointCount);
    if (!hand_ends && (joint == kCanonLeftHandEnd || joint == kCanonRightHandEnd)) continue;
    worst = std::max(worst, glm::length(got.positions[i] - want.positions[i]));
  }
  EXPECT_LT(worst, tolerance_m);
}

TEST(CaptureVariants, RescaledWithoutAUnitHintImportToTheSameBody) {
  FORESIGHT_REQUIRE_MOCAP();
  const Body base = import_canonical(original());
  EXPECT_TRUE(base.report.height_normalised);
  EXPECT_NEAR(base.report.standing_height_m, kCanonicalStandingHeightM, 0.005f);
  for (float k : {0.0254f, 0.01f, 0.056f, 1.0f}) {
    SCOPED_TRACE(k);
    BvhDocument doc = original();
    scale_document(doc, k);
    expect_same_body(import_canonical(doc), base, 0.005f);
  }
  // A given unit keeps the actor's true size (the Bandai takes are in centimetres).
  BvhImportOptions cm;
  cm.unit = LengthUnit::kCentimetres;
  const Body true_size = import_canonical(original(), cm);
  EXPECT_GT(true_size.report.standing_height_m, 1.55f);
  EXPECT_LT(true_size.report.standing_height_m, 1.75f);
  BvhImportOptions scale;
  scale.scale = 0.02f;
  EXPECT_NEAR(import_canonical(original(), scale).report.standing_height_m, 2.0f * true_size.report.standing_height_m, 0.01f);
  EXPECT_FALSE(import_canonical(original(), scale).report.warnings.empty()) << "a 2.9 m body must be warned about";
}

TEST(CaptureVariants, RenamedJointsWithoutSideHintsImportToTheSameBody) {
  FORESIGHT_REQUIRE_MOCAP();
  const Body base = import_canonical(original());
  const std::function<std::string(const std::string&)> conventions[] = {
      [](const std::string& n) { return "mixamorig:" + n; },
      [](const std::string& n) {
        std::string out = "Bip01 " + n;
        if (n.ends_with("_L")) out = "Bip01 L " + n.substr(0, n.size() - 2);
        if (n.ends_with("_R")) out = "Bip01 R " + n.substr(0, n.size() - 2);
        return out;
      },
  };
  for (const auto& rename : conventions) {
    BvhDocument doc = original();
    for (BvhJoint& j : doc.joints) j.name = rename(j.name);
    expect_same_body(import_canonical(doc), base, 0.001f);
  }
  // No name says anything at all: the sides come from the geometry.
  BvhDocument anonymous = original();
  for (size_t j = 0; j < anonymous.joints.size(); ++j) anonymous.joints[j].name = "j" + std::to_string(j * 7 % 23);
  expect_same_body(import_canonical(anonymous), base, 0.001f);
}

// The root's travel along its facing over the whole take, frame by frame, m (negative: backwards).
float travel_ahead(const BvhDocument& doc) {
  const Body b = import_canonical(doc);
  std::vector<Placement> track;
  extract_root_track(b.clip, find_forward_axis(b.skeleton, b.clip), track);
  float ahead = 0.0f;
  for (size_t f = 1; f < track.size(); ++f)
    ahead += glm::dot(track[f].pos_m - track[f - 1].pos_m, vec2(std::sin(track[f].heading_rad), std::cos(track[f].heading_rad)));
  return ahead;
}

// Which side is left comes from the way the body faces, and that from the knees (they bend
// forward): toes alone read the Bandai dash_masculinity take backwards (its feet, kicked up
// behind at a sprint, point back more than ahead), so its sides were swapped and it ran 4.5 m/s
// "backwards", every turn and fallback after it facing the wrong way. Each locomotion take must
// travel the way it faces, the backward walks backwards.
TEST(CaptureVariants, EveryTakeFacesTheWayItTravels) {
  FORESIGHT_REQUIRE_MOCAP();
  int takes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::mocap_dir() / "locomotion")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".bvh" || name.find("respond") != std::string::npos) continue;  // stands
    BvhDocument doc;
    std::string error;
    ASSERT_TRUE(bvh_load(entry.path(), doc, error)) << error;
    const float ahead = travel_ahead(doc);
    if (name.find("walk-back") != std::string::npos) EXPECT_LT(ahead, -1.0f) << name;
    else EXPECT_GT(ahead, 1.0f) << name;
    ++takes;
  }
  EXPECT_GT(takes, 20);
}

// The same sprint as another exporter writes it: in inches with no unit hint under a dummy root,
// and with names that say nothing (sides from the geometry alone): it still runs the way it faces.
TEST(CaptureVariants, ASprintRescaledReRootedOrUnnamedStillFacesTheWayItRuns) {
  FORESIGHT_REQUIRE_MOCAP();
  BvhDocument dash;
  std::string error;
  ASSERT_TRUE(bvh_load(test::mocap_dir() / "locomotion/bandai_dataset-1_dash_masculinity_001.bvh", dash, error)) << error;
  BvhDocument inches = dash;
  scale_document(inches, 1.0f / 2.54f);
  insert_parent(inches, 0, "Reference", 0.0f);
  BvhDocument unnamed = dash;
  for (size_t j = 0; j < unnamed.joints.size(); ++j) unnamed.joints[j].name = "j" + std::to_string(j * 7 % 23);
  EXPECT_GT(travel_ahead(dash), 1.0f);
  EXPECT_GT(travel_ahead(inches), 1.0f);
  EXPECT_GT(travel_ahead(unnamed), 1.0f);
}

TEST(CaptureVariants, ExtraDummyRootAndRelativeRootPositionImportToTheSameBody) {
  FORESIGHT_REQUIRE_MOCAP();
  const Body base = import_canonical(original());
  BvhDocument dummy = original();
  insert_parent(dummy, 0, "World", 0.0f);
  const Body folded = import_canonical(dummy);
  EXPECT_EQ(folded.report.folded_root_joints, base.report.folded_root_joints + 1);
  expect_same_body(folded, base, 0.001f);

  // The pelvis's position channels written as motion away from its OFFSET (94 cm up).
  BvhDocument relative = original();
  const int hips = joint_named(relative, "Hips");
  const int nc = relative.num_channels();
  for (int f = 0; f < relative.num_frames; ++f) {
    float* v = relative.values.data() + static_cast<size_t>(f) * nc + relative.channel_offset(hips);
    for (int a = 0; a < 3; ++a) v[a] -= relative.joints[static_cast<size_t>(hips)].offset[a];
  }
  const Body rel = import_canonical(relative);
  EXPECT_EQ(rel.report.root, RootPosition::kRelative);
  expect_same_body(rel, base, 0.001f);
  // Forced the other way, it sinks under the floor, and the import says so.
  BvhImportOptions absolute;
  absolute.root = RootPosition::kAbsolute;
  const Body sunk = import_canonical(relative, absolute);
  EXPECT_LT(sunk.report.lowest_foot_m, -0.5f);
  EXPECT_FALSE(sunk.report.warnings.empty());
  EXPECT_EQ(base.report.root, RootPosition::kAbsolute);
}

TEST(CaptureVariants, OtherEulerOrdersImportToTheSameBody) {
  FORESIGHT_REQUIRE_MOCAP();
  const Body base = import_canonical(original());
  for (const char* order : {"XYZ", "YXZ", "ZYX"}) {
    SCOPED_TRACE(order);
    BvhDocument doc = original();
    reorder_rotations(doc, order);
    expect_same_body(import_canonical(doc), base, 0.002f);
  }
}

TEST(CaptureVariants, SixtyAndOneHundredTwentyFpsImportToTheSameBody) {
  FORESIGHT_REQUIRE_MOCAP();
  const Body base = import_canonical(original());
  for (int factor : {2, 4}) {
    SCOPED_TRACE(factor);
    BvhDocument doc = original();
    upsample(doc, factor);
    const Body b = import_canonical(doc);
    EXPECT_NEAR(b.report.source_fps, 30.0f * factor, 0.1f);
    EXPECT_FLOAT_EQ(b.clip.fps, 60.0f);
    EXPECT_NEAR(b.clip.duration_s(), base.clip.duration_s(), 0.02f);
    EXPECT_NEAR(b.report.standing_height_m, base.report.standing_height_m, 0.01f);
    EXPECT_NEAR(b.report.lowest_foot_m, base.report.lowest_foot_m, 0.02f);
    // Every second frame at 60 fps is a 30 fps frame of the original.
    float worst = 0.0f;
    const int n = base.clip.num_joints;
    for (int f = 0; f < base.clip.num_frames; ++f)
      for (int j = 0; j < n; ++j)
        worst = std::max(worst, glm::length(b.positions[static_cast<size_t>(2 * f) * n + j] -
                                            base.positions[static_cast<size_t>(f) * n + j]));
    EXPECT_LT(worst, 0.01f);
  }
}

TEST(CaptureVariants, FingerAndTwistJointsAreDroppedAndChangeNothing) {
  FORESIGHT_REQUIRE_MOCAP();
  const Body base = import_canonical(original());
  BvhDocument doc = original();
  // Twist joints halfway along both upper arms, forearms and thighs.
  for (const char* bone : {"LowerArm_L", "LowerArm_R", "Hand_L", "Hand_R", "LowerLeg_L", "LowerLeg_R"})
    insert_parent(doc, joint_named(doc, bone), std::string(bone) + "Twist", 0.5f);
  add_fingers(doc, "Hand_L", 1.0f);
  add_fingers(doc, "Hand_R", -1.0f);
  std::string error;
  ASSERT_TRUE(bvh_validate(doc, error)) << error;
  const Body b = import_canonical(doc);
  expect_same_body(b, base, 0.002f, false);
  // Dropped: the fingers (but the fingertip the hand points to), the twist bones, and End Sites
  // that sit on their joint. Every joint of the original skeleton with a length is kept.
  int dropped = 0;
  for (size_t k = 0; k < b.report.source_joints.size(); ++k) {
    const std::string& name = b.report.source_joints[k];
    const bool extra = name.find("Finger") != std::string::npos || name.find("Twist") != std::string::npos;
    if (!b.report.source_joint_kept[k]) {
      ++dropped;
      EXPECT_TRUE(extra || name.ends_with("_End")) << name << " should have been kept";
    } else if (name.find("Twist") != std::string::npos) {
      ADD_FAILURE() << name << " should have been dropped";
    }
  }
  EXPECT_GE(dropped, 30 - 2 + 6);
}

// The canonical joints lie where the capture's own joints are: retargeting moves no hand or foot.
TEST(CaptureVariants, RetargetedJointsStayWhereTheCaptureHasThem) {
  FORESIGHT_REQUIRE_MOCAP();
  const BvhDocument doc = original();
  const Body canonical = import_canonical(doc);
  Body raw;
  std::string error;
  ASSERT_TRUE(clip_from_bvh(doc, "raw", {}, raw.skeleton, raw.clip, &raw.report, error)) << error;
  fk_clip_positions(raw.skeleton, raw.clip, raw.positions);
  const int n_raw = raw.skeleton.num_joints();
  const int n = canonical.skeleton.num_joints();
  int compared = 0;
  for (size_t src = 0; src < raw.report.canonical_joint.size(); ++src) {
    const int target = raw.report.canonical_joint[src];
    if (target < 0) continue;
    ++compared;
    float worst = 0.0f;
    for (int f = 0; f < raw.clip.num_frames; ++f)
      worst = std::max(worst, glm::length(raw.positions[static_cast<size_t>(f) * n_raw + src] -
                                          canonical.positions[static_cast<size_t>(f) * n + target]));
    EXPECT_LT(worst, 0.01f) << raw.report.source_joints[src] << " -> " << canonical.skeleton.joint_names[static_cast<size_t>(target)];
  }
  EXPECT_GE(compared, 19);
}

}  // namespace
}  // namespace foresight
