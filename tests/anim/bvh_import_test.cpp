// clip_from_bvh / bvh_from_clip on small documents whose answers are computed by hand: channel
// order, position-channel semantics, End Sites, root folding, unit and up-axis detection,
// resampling and the clip -> BVH -> clip round trip.
#include "import/bvh_import.hpp"
#include "anim/canonical_skeleton.hpp"
#include "bvh_test_util.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <random>

namespace foresight {
namespace {

using test::clip_positions;
using test::expect_near_positions;

constexpr float kEps = 1e-5f;

BvhImportOptions metres_y_up() {
  BvhImportOptions o;
  o.unit = LengthUnit::kMetres;
  o.up = UpAxis::kYUp;
  return o;
}

struct Imported {
  Skeleton skeleton;
  Clip clip;
  BvhImportReport report;
  std::vector<vec3> positions;  // FK, [frame * joints + joint]
  vec3 at(int frame, int joint) const { return positions[frame * clip.num_joints + joint]; }
};

Imported import_text(const std::string& text, const BvhImportOptions& options) {
  Imported out;
  BvhDocument doc;
  std::string error;
  EXPECT_TRUE(bvh_parse(text, "test.bvh", doc, error)) << error;
  EXPECT_TRUE(clip_from_bvh(doc, "test", options, out.skeleton, out.clip, &out.report, error))
      << error;
  EXPECT_TRUE(out.skeleton.valid());
  out.positions = clip_positions(out.skeleton, out.clip);
  return out;
}

Imported import_doc(const BvhDocument& doc, const BvhImportOptions& options) {
  Imported out;
  std::string error;
  EXPECT_TRUE(clip_from_bvh(doc, "doc", options, out.skeleton, out.clip, &out.report, error))
      << error;
  EXPECT_TRUE(out.skeleton.valid());
  out.positions = clip_positions(out.skeleton, out.clip);
  return out;
}

void expect_vec(vec3 got, vec3 want) {
  EXPECT_NEAR(got.x, want.x, kEps);
  EXPECT_NEAR(got.y, want.y, kEps);
  EXPECT_NEAR(got.z, want.z, kEps);
}

// Root: XYZ order with positions; child: YXZ order. CRLF line ends and tabs on purpose.
const char* const kOrders =
    "HIERARCHY\r\n"
    "ROOT Root\r\n"
    "{\r\n"
    "\tOFFSET 0 0 0\r\n"
    "\tCHANNELS 6 Xposition Yposition Zposition Xrotation Yrotation Zrotation\r\n"
    "\tJOINT Child\r\n"
    "\t{\r\n"
    "\t\tOFFSET 1 0 0\r\n"
    "\t\tCHANNELS 3 Yrotation Xrotation Zrotation\r\n"
    "\t\tEnd Site\r\n"
    "\t\t{\r\n"
    "\t\t\tOFFSET 1 0 0\r\n"
    "\t\t}\r\n"
    "\t}\r\n"
    "}\r\n"
    "MOTION\r\n"
    "Frames:\t2\r\n"
    "Frame Time:\t0.0333333\r\n"
    "1 2 3 90 90 0 90 90 0\r\n"
    "0 0 0 0 0 3e1 0 0 0\r\n";

TEST(BvhImport, RotationChannelsComposeInListedOrderFirstOutermost) {
  const Imported im = import_text(kOrders, metres_y_up());
  ASSERT_EQ(im.clip.num_frames, 2);
  ASSERT_EQ(im.clip.num_joints, 3);
  // Frame 0. Root R0 = Rx(90) Ry(90): Ry(90) takes +X to -Z, Rx(90) takes -Z to +Y, so the child
  // sits at (1,2,3) + (0,1,0). (Ry Rx would give (1,2,2).)
  expect_vec(im.at(0, 0), {1, 2, 3});
  expect_vec(im.at(0, 1), {1, 3, 3});
  // Child R1 = Ry(90) Rx(90): Rx keeps +X, Ry takes it to -Z; then R0: Ry(90) takes -Z to -X,
  // Rx(90) keeps -X: end at (0,3,3). (Rx Ry would take +X to +Y, then R0 to +Z: (1,3,4).)
  expect_vec(im.at(0, 2), {0, 3, 3});
  // Frame 1: a positive Zrotation of 30 degrees turns +X towards +Y (right-handed degrees).
  expect_vec(im.at(1, 1), {std::cos(radians(30)), std::sin(radians(30)), 0});
  expect_vec(im.at(1, 2), 2.0f * vec3(std::cos(radians(30)), std::sin(radians(30)), 0));
}

TEST(BvhImport, PositionChannelsReplaceTheOffsetComponentByComponent) {
  const std::string text =
      "HIERARCHY\nROOT Root\n{\n OFFSET 5 5 5\n CHANNELS 3 Xposition Yposition Zposition\n"
      " JOINT Full\n {\n  OFFSET 1 0 0\n"
      "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
      "  JOINT Partial\n  {\n   OFFSET 1 0 0\n   CHANNELS 2 Yposition Zrotation\n"
      "   End Site\n   {\n    OFFSET 0 0 1\n   }\n  }\n }\n}\n"
      "MOTION\nFrames: 1\nFrame Time: 0.0333333\n"
      "0 1 0  0 2 0 0 0 0  5 0\n";
  const Imported im = import_text(text, metres_y_up());
  // Root: its OFFSET (5,5,5) is replaced by the channels (0,1,0).
  expect_vec(im.at(0, 0), {0, 1, 0});
  // Full: (0,2,0) replaces OFFSET (1,0,0); adding would give (1,3,0).
  EXPECT_EQ(im.report.folded_root_joints, 0);  // one frame: nothing can be told static
  ASSERT_EQ(im.skeleton.num_joints(), 4);
  expect_vec(im.clip.frame_pos(0)[1], {0, 2, 0});
  expect_vec(im.at(0, 1), {0, 3, 0});
  // Partial: only y is replaced: (1,5,0).
  expect_vec(im.clip.frame_pos(0)[2], {1, 5, 0});
  expect_vec(im.at(0, 2), {1, 8, 0});
  // The rest offsets stay the OFFSETs.
  expect_vec(im.skeleton.rest_offsets_m[1], {1, 0, 0});
}

TEST(BvhImport, EndSitesBecomeEndSiteJointsWithTheirOffset) {
  const Imported im = import_text(kOrders, metres_y_up());
  ASSERT_EQ(im.skeleton.num_joints(), 3);
  EXPECT_EQ(im.skeleton.is_end_site, (std::vector<bool>{false, false, true}));
  EXPECT_EQ(im.skeleton.parents[2], 1);
  EXPECT_EQ(im.skeleton.joint_names[2], "Child_End");
  expect_vec(im.skeleton.rest_offsets_m[2], {1, 0, 0});
  expect_vec(im.clip.frame_pos(1)[2], {1, 0, 0});
}

// Two static dummies above the pelvis: Outer (constant translate (1,0,0) + Yrotation 90) and
// Inner (no channels, OFFSET (0,0,2)).
const char* const kDummies =
    "HIERARCHY\nROOT Outer\n{\n OFFSET 0 0 0\n"
    " CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    " JOINT Inner\n {\n  OFFSET 0 0 2\n"
    "  JOINT Pelvis\n  {\n   OFFSET 0 0 0\n"
    "   CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "   JOINT Leg\n   {\n    OFFSET 0 -1 0\n    CHANNELS 1 Xrotation\n"
    "    End Site\n    {\n     OFFSET 0 -1 0\n    }\n   }\n  }\n }\n}\n"
    "MOTION\nFrames: 2\nFrame Time: 0.0333333\n"
    "1 0 0 0 0 90  0 1 0 0 0 0  0\n"
    "1 0 0 0 0 90  0 1 1 0 0 0  0\n";

TEST(BvhImport, FoldsStaticDummyRootsIntoThePelvis) {
  const Imported im = import_text(kDummies, metres_y_up());
  EXPECT_EQ(im.report.folded_root_joints, 2);
  ASSERT_EQ(im.skeleton.num_joints(), 3);
  EXPECT_EQ(im.skeleton.joint_names[0], "Pelvis");
  EXPECT_EQ(im.skeleton.parents[0], kNoParent);
  // Pelvis = Outer * Inner * Pelvis: Inner sits at (1,0,0) + Ry(90) (0,0,2) = (3,0,0); the pelvis
  // channel (0,1,0) stays (0,1,0) under Ry(90), and (0,1,1) becomes (1,1,0).
  expect_vec(im.at(0, 0), {3, 1, 0});
  expect_vec(im.at(1, 0), {4, 1, 0});
  expect_vec(im.at(1, 1), {4, 0, 0});
  // The rotation is carried too: the pelvis's local +Z now points along world +X.
  expect_vec(im.clip.frame_rot(0)[0] * vec3(0, 0, 1), {1, 0, 0});
  expect_vec(im.skeleton.rest_offsets_m[0], {3, 0, 0});
}

TEST(BvhImport, FoldsATranslationOnlyTrajectoryRootAboveARotatingPelvis) {
  const std::string text =
      "HIERARCHY\nROOT Trajectory\n{\n OFFSET 0 0 0\n CHANNELS 3 Xposition Yposition Zposition\n"
      " JOINT Pelvis\n {\n  OFFSET 0 1 0\n  CHANNELS 1 Yrotation\n"
      "  JOINT Leg\n  {\n   OFFSET 0 -1 1\n  }\n }\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.0333333\n0 0 0 0\n0 0 2 90\n";
  const Imported im = import_text(text, metres_y_up());
  EXPECT_EQ(im.report.folded_root_joints, 1);
  ASSERT_EQ(im.skeleton.num_joints(), 2);
  EXPECT_EQ(im.skeleton.joint_names[0], "Pelvis");
  expect_vec(im.at(0, 0), {0, 1, 0});
  expect_vec(im.at(1, 0), {0, 1, 2});
  expect_vec(im.at(0, 1), {0, 0, 1});
  expect_vec(im.at(1, 1), {1, 0, 2});  // Ry(90) takes +Z to +X

  // A translating joint above a still one is not a trajectory node: the Pelvis in kDummies only
  // translates and its Leg never moves, so only the two dummies above it fold (tested above).
}

TEST(BvhImport, DoesNotFoldARotatingRootOrOneWithTwoChildren) {
  std::string turning = kDummies;
  turning.replace(turning.rfind("0 0 90"), 6, "0 0 80");  // Outer turns in frame 1
  Imported im = import_text(turning, metres_y_up());
  EXPECT_EQ(im.report.folded_root_joints, 0);
  EXPECT_EQ(im.skeleton.joint_names[0], "Outer");
  EXPECT_EQ(im.skeleton.num_joints(), 5);

  const std::string two_children =
      "HIERARCHY\nROOT Root\n{\n OFFSET 0 0 0\n"
      " JOINT A\n {\n  OFFSET 0 1 0\n  CHANNELS 1 Xrotation\n }\n"
      " JOINT B\n {\n  OFFSET 0 -1 0\n  CHANNELS 1 Xrotation\n }\n}\n"
      "MOTION\nFrames: 2\nFrame Time: 0.0333333\n0 0\n10 20\n";
  im = import_text(two_children, metres_y_up());
  EXPECT_EQ(im.report.folded_root_joints, 0);
  EXPECT_EQ(im.skeleton.num_joints(), 3);
}

TEST(BvhImport, ScalesAHumanoidToTheCanonicalHeightWhateverItsUnit) {
  // The 1.6 m test humanoid, written in metres, centimetres and inches with no unit given: the
  // same body, its standing height scaled to the canonical skeleton's, the unit recognised.
  const Imported metres = import_doc(test::humanoid_document(1.0f, false), {});
  EXPECT_TRUE(metres.report.humanoid) << metres.report.not_humanoid;
  EXPECT_TRUE(metres.report.height_normalised);
  EXPECT_EQ(metres.report.unit, LengthUnit::kMetres);
  // Its legs are 0.82 m hip to ankle: 1.68 m tall by the canonical proportions.
  EXPECT_NEAR(metres.report.body_size, 0.82f * kCanonicalStandingHeightM / kCanonicalLegLengthM, 1e-4f);
  EXPECT_NEAR(metres.report.standing_height_m, kCanonicalStandingHeightM, 1e-4f);
  EXPECT_NEAR(metres.at(0, 0).y, 0.9f * metres.report.scale, kEps);
  const struct {
    LengthUnit unit;
    float scale;
  } units[] = {{LengthUnit::kCentimetres, 100.0f}, {LengthUnit::kInches, 1.0f / 0.0254f}};
  for (const auto& u : units) {
    SCOPED_TRACE(length_unit_name(u.unit));
    const Imported im = import_doc(test::humanoid_document(u.scale, false), {});
    EXPECT_EQ(im.report.unit, u.unit);
    EXPECT_EQ(im.report.up, UpAxis::kYUp);
    expect_near_positions(im.positions, metres.positions, 1e-5f);
  }
  // An explicit unit keeps the true size.
  BvhImportOptions cm;
  cm.unit = LengthUnit::kCentimetres;
  const Imported forced = import_doc(test::humanoid_document(1.0f, false), cm);
  EXPECT_EQ(forced.report.unit, LengthUnit::kCentimetres);
  EXPECT_FALSE(forced.report.height_normalised);
  EXPECT_NEAR(forced.at(0, 0).y, 0.009f, kEps);
  EXPECT_FALSE(forced.report.warnings.empty()) << "a 1.6 cm body must be warned about";
  // Not a humanoid (a two-joint prop): the bounding box picks one of three units.
  BvhDocument prop;
  prop.joints.push_back({"Box", -1, vec3(0), {BvhChannel::kXposition, BvhChannel::kYposition, BvhChannel::kZposition}, false});
  prop.joints.push_back({"Box_End", 0, vec3(0, 50, 0), {}, true});
  prop.num_frames = 1;
  prop.values = {0, 0, 0};
  const Imported box = import_doc(prop, {});
  EXPECT_FALSE(box.report.humanoid);
  EXPECT_EQ(box.report.unit, LengthUnit::kInches);
}

TEST(BvhImport, DetectsZUpAndRotatesItToYUpWithoutMirroring) {
  BvhImportOptions cm;
  cm.unit = LengthUnit::kCentimetres;
  const Imported y_up = import_doc(test::humanoid_document(100.0f, false), cm);
  const Imported z_up = import_doc(test::humanoid_document(100.0f, true), cm);
  EXPECT_EQ(y_up.report.up, UpAxis::kYUp);
  EXPECT_EQ(z_up.report.up, UpAxis::kZUp);
  EXPECT_EQ(z_up.report.unit, LengthUnit::kCentimetres);
  expect_near_positions(z_up.positions, y_up.positions, 1e-5f);
  // Frame 1 steps forward: +Z in the Y-up result, and the left arm stays on +X.
  EXPECT_NEAR(z_up.at(1, 0).z, 0.5f, kEps);
  EXPECT_GT(z_up.at(0, z_up.skeleton.find_joint("LeftHand")).x, 0.1f);
  // The rest pose converts too (local offsets rotated, not just the root).
  expect_vec(z_up.skeleton.rest_offsets_m[1], {0, 0.1f, 0});

  // Forcing Y up on the Z-up file leaves it lying down: the head ends up along +Z.
  BvhImportOptions wrong = cm;
  wrong.up = UpAxis::kYUp;
  const Imported lying = import_doc(test::humanoid_document(100.0f, true), wrong);
  EXPECT_GT(lying.at(0, lying.skeleton.find_joint("Head")).z, 0.5f);
}

TEST(BvhImport, DetectsUpWithoutAHeadJointFromTheUpperBody) {
  BvhDocument doc = test::humanoid_document(100.0f, true);
  for (BvhJoint& j : doc.joints)
    if (j.name.starts_with("Head")) j.name = "Top" + j.name.substr(4);
  const Imported im = import_doc(doc, {});
  EXPECT_EQ(im.report.up, UpAxis::kZUp);
}

// x = f (file units), Yrotation = 10 f degrees, at `fps` for `frames` frames.
BvhDocument ramp_document(double fps, int frames) {
  BvhDocument doc;
  using C = BvhChannel;
  doc.joints.push_back({"Pelvis", -1, vec3(0), {C::kXposition, C::kYposition, C::kZposition,
                                                C::kYrotation}, false});
  doc.joints.push_back({"Pelvis_End", 0, vec3(0, 1, 0), {}, true});
  doc.num_frames = frames;
  doc.frame_time_s = 1.0 / fps;
  for (int f = 0; f < frames; ++f)
    doc.values.insert(doc.values.end(), {static_cast<float>(f), 1.0f, 0.0f, 10.0f * f});
  return doc;
}

float yaw_degrees(quat q) { return degrees(heading_of(q * vec3(0, 0, 1))); }

TEST(BvhImport, Resamples120To60KeepingDuration) {
  const Imported im = import_doc(ramp_document(120.0, 121), metres_y_up());
  EXPECT_FLOAT_EQ(im.report.source_fps, 120.0f);
  EXPECT_EQ(im.report.source_frames, 121);
  EXPECT_EQ(im.clip.fps, 60.0f);
  ASSERT_EQ(im.clip.num_frames, 61);
  EXPECT_NEAR(im.clip.duration_s(), 1.0f, 1e-6f);
  for (int k = 0; k < 61; k += 10) {
    EXPECT_NEAR(im.clip.frame_pos(k)[0].x, 2.0f * k, 1e-4f);
    EXPECT_NEAR(yaw_degrees(im.clip.frame_rot(k)[0]), wrap_angle(radians(20.0f * k)) * 180 / kPi,
                1e-3f);
  }
}

TEST(BvhImport, Resamples24To30Interpolating) {
  const Imported im = import_doc(ramp_document(24.0, 25), metres_y_up());
  EXPECT_EQ(im.clip.fps, 30.0f);
  ASSERT_EQ(im.clip.num_frames, 31);
  EXPECT_NEAR(im.clip.duration_s(), 1.0f, 1e-6f);
  // Output frame k is source time k/30 = source frame 0.8 k: x = 0.8 k, yaw = 8 k degrees.
  for (int k = 0; k < 31; ++k) {
    EXPECT_NEAR(im.clip.frame_pos(k)[0].x, 0.8f * k, 1e-4f) << k;
    EXPECT_NEAR(im.clip.frame_pos(k)[0].y, 1.0f, 1e-6f);
    EXPECT_NEAR(yaw_degrees(im.clip.frame_rot(k)[0]),
                degrees(wrap_angle(radians(8.0f * k))), 1e-2f) << k;
  }
  // 25 fps -> 30 too.
  EXPECT_EQ(import_doc(ramp_document(25.0, 26), metres_y_up()).clip.fps, 30.0f);
  // A 30 fps source is copied frame for frame.
  const Imported same = import_doc(ramp_document(30.0, 7), metres_y_up());
  EXPECT_EQ(same.clip.num_frames, 7);
  EXPECT_EQ(same.clip.frame_pos(6)[0].x, 6.0f);
}

TEST(BvhImport, ResamplingKeepsTheLastFrameAndTakesTheShortRotationPath) {
  // 10 frames at 24 fps = 0.375 s -> round(11.25) + 1 = 12 frames; the last is source frame 9.
  const Imported im = import_doc(ramp_document(24.0, 10), metres_y_up());
  ASSERT_EQ(im.clip.num_frames, 12);
  EXPECT_EQ(im.clip.frame_pos(11)[0].x, 9.0f);

  // Yaw 170 -> -170 degrees: the way through 180, not through 0.
  BvhDocument doc = ramp_document(24.0, 4);
  doc.values[3] = 170.0f;
  doc.values[7] = -170.0f;
  doc.values[11] = -150.0f;
  doc.values[15] = -130.0f;
  const Imported turn = import_doc(doc, metres_y_up());
  ASSERT_EQ(turn.clip.num_frames, 5);  // 3/24 s -> round(3.75) + 1
  // Output frame 1 = source 0.8: 170 + 0.8 * 20 = 186 = -174 degrees.
  EXPECT_NEAR(yaw_degrees(turn.clip.frame_rot(1)[0]), -174.0f, 1e-2f);
  EXPECT_NEAR(yaw_degrees(turn.clip.frame_rot(4)[0]), -130.0f, 1e-3f);
}

TEST(BvhImport, TargetFpsOverrideAndSixtyForFastSources) {
  BvhImportOptions o = metres_y_up();
  o.target_fps = 60.0f;
  const Imported up = import_doc(ramp_document(30.0, 31), o);
  EXPECT_EQ(up.clip.num_frames, 61);
  EXPECT_NEAR(up.clip.frame_pos(1)[0].x, 0.5f, 1e-5f);
  EXPECT_EQ(import_doc(ramp_document(50.0, 51), metres_y_up()).clip.fps, 60.0f);
  EXPECT_EQ(import_doc(ramp_document(45.0, 46), metres_y_up()).clip.fps, 30.0f);
}

TEST(BvhImport, RejectsEmptyMotionInvalidDocumentsAndBadTargetFps) {
  Skeleton s;
  Clip c;
  std::string error;
  BvhDocument empty = ramp_document(30.0, 0);
  EXPECT_FALSE(clip_from_bvh(empty, "empty", {}, s, c, nullptr, error));
  EXPECT_NE(error.find("empty: no motion frames"), std::string::npos) << error;
  BvhDocument bad = ramp_document(30.0, 3);
  bad.values.pop_back();
  EXPECT_FALSE(clip_from_bvh(bad, "bad", {}, s, c, nullptr, error));
  EXPECT_NE(error.find("bad: "), std::string::npos) << error;
  BvhImportOptions o;
  o.target_fps = -5.0f;
  EXPECT_FALSE(clip_from_bvh(ramp_document(30.0, 3), "fps", o, s, c, nullptr, error));
  // A frame time that would resample to billions of frames is refused, not allocated.
  BvhDocument slow = ramp_document(30.0, 3);
  slow.frame_time_s = 1e9;
  EXPECT_FALSE(clip_from_bvh(slow, "slow", {}, s, c, nullptr, error));
  EXPECT_NE(error.find("too large"), std::string::npos) << error;
  // ... and so is one that would take gigabytes (20 million samples: 560 MB before the FK and the
  // retargeting; fuzz-bvh ran out of 2 GB on such a file).
  slow.frame_time_s = 20e6 / static_cast<double>(slow.joints.size()) / 60.0;
  EXPECT_FALSE(clip_from_bvh(slow, "slow", {}, s, c, nullptr, error));
  EXPECT_NE(error.find("the limit is"), std::string::npos) << error;
  EXPECT_FALSE(clip_load_bvh(test::scratch_dir() / "absent.bvh", {}, s, c, nullptr, error));
  // OFFSETs near the float limit add up to infinity in the posed body: refused, not imported.
  BvhDocument huge = test::humanoid_document(1.0f, false);
  for (BvhJoint& j : huge.joints) j.offset *= 3e38f;
  EXPECT_FALSE(clip_from_bvh(huge, "huge", {}, s, c, nullptr, error));
  EXPECT_NE(error.find("beyond float range"), std::string::npos) << error;
  BvhImportOptions canonical;
  canonical.canonical = true;
  EXPECT_FALSE(clip_from_bvh(huge, "huge", canonical, s, c, nullptr, error));
  // Not a humanoid and asked for the canonical skeleton: refused with the reason.
  EXPECT_FALSE(clip_from_bvh(ramp_document(30.0, 3), "ramp", canonical, s, c, nullptr, error));
  EXPECT_NE(error.find("ramp: not a humanoid"), std::string::npos) << error;
}

TEST(BvhImport, ClipToBvhAndBackGivesTheSameFk) {
  // A clip with random rotations on every joint (gimbal-lock cases included), a moving pelvis and
  // one non-root joint whose translation changes.
  Imported src = import_doc(test::humanoid_document(1.0f, false), {});
  Clip clip = src.clip;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int f = 0; f < clip.num_frames; ++f) {
    for (int j = 0; j < clip.num_joints; ++j) {
      quat q = glm::normalize(quat(u(rng), u(rng), u(rng), u(rng)));
      if (j == 3) q = glm::angleAxis(kPi / 2, vec3(1, 0, 0)) * glm::angleAxis(0.3f, vec3(0, 1, 0));
      if (j == 4) q = glm::angleAxis(-kPi / 2, vec3(1, 0, 0));
      if (!src.skeleton.is_end_site[j]) clip.frame_rot(f)[j] = q;
    }
    clip.frame_pos(f)[0] += vec3(u(rng), 0.1f * u(rng), u(rng));
  }
  const int spine = src.skeleton.find_joint("Spine");
  clip.frame_pos(1)[spine] += vec3(0, 0.05f, 0);
  const std::vector<vec3> want = clip_positions(src.skeleton, clip);

  const BvhDocument doc = bvh_from_clip(src.skeleton, clip);
  std::string error;
  ASSERT_TRUE(bvh_validate(doc, error)) << error;
  EXPECT_EQ(doc.joints[0].channels.size(), 6u);
  EXPECT_EQ(doc.joints[spine].channels.size(), 6u);  // its translation moves
  EXPECT_EQ(doc.joints[src.skeleton.find_joint("Chest")].channels,
            (std::vector{BvhChannel::kZrotation, BvhChannel::kXrotation, BvhChannel::kYrotation}));
  EXPECT_TRUE(doc.joints[src.skeleton.find_joint("Head_End")].channels.empty());
  EXPECT_NEAR(doc.frame_time_s, 1.0 / 30.0, 1e-12);

  // Through text and a file, as a tool would.
  const auto path = test::scratch_dir() / "roundtrip.bvh";
  ASSERT_TRUE(bvh_save(path, doc, error)) << error;
  Skeleton s2;
  Clip c2;
  BvhImportReport report;
  ASSERT_TRUE(clip_load_bvh(path, metres_y_up(), s2, c2, &report, error)) << error;
  EXPECT_EQ(c2.name, "roundtrip");
  EXPECT_EQ(c2.num_frames, clip.num_frames);
  EXPECT_EQ(s2.joint_names, src.skeleton.joint_names);
  EXPECT_EQ(s2.parents, src.skeleton.parents);
  EXPECT_EQ(report.folded_root_joints, 0);
  expect_near_positions(clip_positions(s2, c2), want, 1e-5f);
  for (int f = 0; f < clip.num_frames; ++f) {
    for (int j = 0; j < clip.num_joints; ++j) {
      if (s2.is_end_site[j]) continue;
      EXPECT_GT(std::fabs(glm::dot(c2.frame_rot(f)[j], clip.frame_rot(f)[j])), 1.0f - 1e-6f)
          << "frame " << f << " joint " << j;
    }
  }
}

}  // namespace
}  // namespace foresight
