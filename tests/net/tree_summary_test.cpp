// TreeSummaryWriter (server/tree_summary.*) without sockets: every sample names its tree node's
// segment and start heading, so a client rebuilds the node's clip (ghost poses) from the summary
// alone, and a full summary fits one datagram.
#include "tree_summary.hpp"
#include "support/segments.hpp"

#include "library_build/library_source.hpp"
#include "protocol/quantize.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace foresight {
namespace {

using test::walk_segment;

TEST(TreeSummary, SamplesCarryTheirNodesSegmentAndStartHeading) {
  const MotionLibrary lib = motion_library_default();
  Scene scene;
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(scene_world_load("arena", scene, world, error)) << error;
  MotionTreeConfig config;
  config.max_nodes = 2048;
  MotionTree tree(lib, world, config);
  const Placement start{vec2(0.0f, -4.0f), 0.7f};  // the arena's open middle, turned
  tree.reset(walk_segment(lib), start);
  tree.set_command(vec2(0.0f, 1.0f), start);
  tree.grow(GrowBudget::expansions(2000));
  ASSERT_GT(tree.num_nodes(), static_cast<int>(protocol::kMaxTreeSamples)) << "a tree bigger than one summary";

  protocol::PacketWriter w;
  server::TreeSummaryWriter writer;
  const auto bytes = writer.write(w, tree, 7, 3);
  EXPECT_LE(bytes.size(), protocol::kMaxDatagramBytes) << "a full summary fits one datagram";
  std::printf("a full summary (%zu samples): %zu bytes\n", writer.samples().size(), bytes.size());
  const auto samples = writer.samples();
  ASSERT_EQ(samples.size(), protocol::kMaxTreeSamples);

  // Map each sample back to its node: sample 0 is the root; every other one is the child of its
  // parent's node with the same segment and (quantised) end.
  const vec2 origin = tree.start_of(tree.root()).pos_m;
  std::vector<int> node_of(samples.size(), -1);
  node_of[0] = tree.root();
  for (size_t i = 0; i < samples.size(); ++i) {
    const wire::TreeNodeSample& s = samples[i];
    if (i > 0) {
      ASSERT_LT(s.parent(), i);
      for (int k = tree.node(node_of[s.parent()]).first_child; k >= 0; k = tree.node(k).next_sibling) {
        const MotionTreeNode& c = tree.node(k);
        if (tree.segment_of(k) == s.segment() &&
            std::lround((c.end.pos_m.x - origin.x) * 100.0f) == s.dx_cm() &&
            std::lround((c.end.pos_m.y - origin.y) * 100.0f) == s.dz_cm())
          node_of[i] = k;
      }
      ASSERT_GE(node_of[i], 0) << "sample " << i << " matches no child of its parent's node";
    }
    const Placement node_start = tree.start_of(node_of[i]);
    EXPECT_EQ(s.segment(), static_cast<uint16_t>(tree.segment_of(node_of[i]))) << "sample " << i;
    EXPECT_EQ(s.start_heading(), protocol::quantize_angle(node_start.heading_rad)) << "sample " << i;
    // What the client rebuilds the ghost from: start = parent's end (origin for the root) plus
    // this heading; it must be the node's own start placement.
    const vec2 start_pos = i == 0 ? origin
                                  : origin + 0.01f * vec2(static_cast<float>(samples[s.parent()].dx_cm()),
                                                          static_cast<float>(samples[s.parent()].dz_cm()));
    EXPECT_LT(glm::length(start_pos - node_start.pos_m), 0.011f) << "sample " << i;
    EXPECT_NEAR(std::remainder(protocol::dequantize_angle(s.start_heading()) - node_start.heading_rad, 2.0f * kPi),
                0.0f, 1e-3f)
        << "sample " << i;
  }
}

}  // namespace
}  // namespace foresight
