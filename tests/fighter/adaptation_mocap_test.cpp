#include "import/bvh_import.hpp"
#include "anim/fk.hpp"
#include "fighter/adaptation_support.hpp"
#include "support/test_paths.hpp"

namespace foresight {
namespace {

// A captured jab (Bandai skeleton, another actor) driving the five morphologies: retargeted through
// the representation, then adapted so every fist lands on one shared target.
TEST(AdaptStrike, MocapPunchRetargetedToFiveMorphologiesReachesTheTarget) {
  FORESIGHT_REQUIRE_MOCAP();
  Skeleton skel;
  Clip clip;
  std::string error;
  ASSERT_TRUE(clip_load_bvh(test::mocap_dir() / "fighting" / "bandai_dataset-1_punch_normal_001.bvh", {}, skel, clip,
                            nullptr, error)) << error;
  LimbModel model;
  ASSERT_TRUE(limb_model_from_clip(skel, clip, 0, model, error)) << error;
  // The take's jabs are thrown with the left hand; the hit is the largest wrist extension in the
  // first 60 frames (the first jab).
  const FighterLimb& arm = model.rig.arm[kFighterLeft];
  std::vector<vec3> pos;
  fk_clip_positions(skel, clip, pos);
  const int n = skel.num_joints();
  int hit = 0;
  float best = 0.0f;
  for (int f = 0; f < std::min(60, clip.num_frames); ++f) {
    const float ext = glm::length(pos[static_cast<size_t>(f * n + arm.end)] - pos[static_cast<size_t>(f * n + arm.root)]);
    if (ext > best) best = ext, hit = f;
  }
  ASSERT_GT(hit, 5);
  StrikeRequest req;
  req.source = {&skel, &model};
  req.clip = &clip;
  req.start_frame = std::max(0, hit - 12);
  req.hit_frame = hit;
  req.end_frame = std::min(clip.num_frames - 1, hit + 15);
  req.side = kFighterLeft;
  req.alignment = Placement{vec2(2.0f, 1.0f), 0.3f};

  const std::vector<Morphology> morphs = default_morphologies();
  std::vector<LimbModel> models(morphs.size());
  // One target for all five: 10 cm from where the smallest fighter's jab lands, towards where the
  // others' land (so it is within everyone's reach, and every fist must move to it).
  std::vector<vec3> hits(morphs.size());
  size_t smallest = 0;
  vec3 mean(0.0f);
  for (size_t i = 0; i < morphs.size(); ++i) {
    ASSERT_TRUE(limb_model_for_morphology(morphs[i], models[i], error)) << error;
    StrikeAdapter probe;
    ASSERT_TRUE(probe.begin(req, {&morphs[i].skeleton, &models[i]}, AdaptSettings{}, {}, {}, error)) << error;
    hits[i] = probe.unadapted_hit_m();
    mean += hits[i] / static_cast<float>(morphs.size());
    if (morphs[i].height_m < morphs[smallest].height_m) smallest = i;
  }
  const vec3 target = hits[smallest] + 0.1f * glm::normalize(mean - hits[smallest]);
  req.target_m = target;
  for (size_t i = 0; i < morphs.size(); ++i) {
    StrikeAdapter adapter;
    ASSERT_TRUE(adapter.begin(req, {&morphs[i].skeleton, &models[i]}, AdaptSettings{}, {}, {}, error)) << error;
    EXPECT_GT(glm::length(adapter.unadapted_hit_m() - target), 0.02f) << morphs[i].name;
    for (int k = 0; k < adapter.num_frames(); ++k) {
      const AdaptedFrame f = adapter.pose_frame(k);
      ASSERT_TRUE(test::finite(f.effector_m)) << morphs[i].name;
      if (k == adapter.hit_index()) {
        EXPECT_LT(glm::length(f.effector_m - target), 0.01f) << morphs[i].name;
      }
      // Retargeted feet never sink into the floor.
      for (size_t side = 0; side < 2; ++side) {
        EXPECT_GT(adapter.pose().global_pos_m[static_cast<size_t>(models[i].contact[side])].y,
                  morphs[i].ball_height_m - 0.005f) << morphs[i].name;
      }
    }
  }
}

}  // namespace
}  // namespace foresight
