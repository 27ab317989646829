// The client as a person runs it: a real server and real bots as separate processes, the client
// under Xvfb (Mesa software GL) writing a screenshot, then the PNG checked.
#include "client_process.hpp"
#include "support/test_paths.hpp"
#include "tree_overlay.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace foresight::test;

// One run of the client against a maze server with `bots` bots, in this test's scratch folder.
void run_client_screenshot(const std::string& name, const std::string& client_args, Image& img, int bots = 3,
                           std::vector<std::string> server_args = {}) {
  ClientRun run;
  run.dir = scratch_dir();
  run.name = name;
  run.client_args = client_args;
  run.bots = bots;
  run.server_args = std::move(server_args);
  foresight::test::run_client_screenshot(run, img);
}

TEST(ClientScreenshot, ShowsTheSceneAndThePlayersAvatar) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  Image img;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("shot", "", img));
  EXPECT_EQ(img.w, 1280);
  EXPECT_EQ(img.h, 720);
  EXPECT_GT(non_uniform_share(img), 0.25) << "the image is (nearly) uniform";
  EXPECT_GT(orange_pixels(img), 20u) << "the player's avatar colour does not appear";
}

// --resize-at-s: the window shrinks mid-run (as a person dragging its border would); the shot
// after it has the new size and still shows the scene and the player.
TEST(ClientScreenshot, FollowsAWindowResize) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  Image img;
  ASSERT_NO_FATAL_FAILURE(
      run_client_screenshot("resize", "--resize-at-s 1 --resize-to 800x450 --screenshot-at-s 2.5", img));
  EXPECT_EQ(img.w, 800);
  EXPECT_EQ(img.h, 450);
  EXPECT_GT(non_uniform_share(img), 0.25) << "the image is (nearly) uniform after the resize";
  EXPECT_GT(orange_pixels(img), 10u) << "the player's avatar colour does not appear after the resize";
}

// --script steers the player: the client replays the maze recording for 4 s, takes the shot then
// and exits 0. (With the follow camera a wall may stand between camera and avatar: where the
// avatar is on screen is not checked.)
TEST(ClientScreenshot, RunsWithAScript) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  const std::string script = "--script " + (foresight::data_dir() / "recordings/maze_eval.json").string();
  Image img;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("script", script + " --screenshot-at-s 4", img));
  EXPECT_EQ(img.w, 1280);
  EXPECT_EQ(img.h, 720);
}

// --strip: frames side by side, each showing the avatar: the turning-feet figure's own command
// (docs/MOTION_QUALITY.md), smaller.
TEST(ClientScreenshot, TakesAStripOfFramesOverTime) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  ClientRun run;
  run.dir = scratch_dir();
  run.name = "strip";
  run.scene = "field";
  run.bots = 0;
  run.client_args = "--script " + (foresight::data_dir() / "scripts/turning-feet.json").string() +
                    " --follow-camera --follow-distance-m 2.6 --no-overlay --width 160 --height 200"
                    " --screenshot-at-s 2.5 --strip 4 --strip-interval-s 0.25";
  Image img;
  ASSERT_NO_FATAL_FAILURE(foresight::test::run_client_screenshot(run, img));
  ASSERT_EQ(img.w, 4 * 160);
  ASSERT_EQ(img.h, 200);
  for (int k = 0; k < 4; ++k)
    EXPECT_GT(orange_pixels(img, k * 160, (k + 1) * 160), 100u) << "frame " << k << " shows the avatar";
}

// Counts pixels within `tolerance` of an exact (unlit) colour.
size_t count_colour(const Image& img, int r0, int g0, int b0, int tolerance = 12) {
  const size_t n = img.size();
  size_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    const int r = img.pixels[3 * i], g = img.pixels[3 * i + 1], b = img.pixels[3 * i + 2];
    if (std::abs(r - r0) <= tolerance && std::abs(g - g0) <= tolerance && std::abs(b - b0) <= tolerance) ++count;
  }
  return count;
}

// The ghosts' pale yellow (1.00, 0.90, 0.55) under any shading: green close to red, blue about
// half of red (the chosen line's yellow has almost no blue; walls and floor have as much blue as
// red; the player's orange half as much green).
size_t ghost_pixels(const Image& img) {
  static_assert(foresight::client::kGhostColour.y == 0.90f && foresight::client::kGhostColour.z == 0.55f);
  size_t count = 0;
  for (size_t i = 0; i < img.size(); ++i) {
    const int r = img.pixels[3 * i], g = img.pixels[3 * i + 1], b = img.pixels[3 * i + 2];
    if (r > 80 && g > 0.82 * r && g < 0.97 * r && b > 0.40 * r && b < 0.70 * r) ++count;
  }
  return count;
}

TEST(ClientScreenshot, TheTreeOverlayDrawsTheTreeAndItsChosenBranch) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  // Walking (the maze recording, 3 s in, follow camera: the docs figure), so the chosen branch
  // leads away from the avatar: a standing avatar's chosen idle clips stand where it stands, and
  // its ghosts hide inside its own body.
  const std::string walking = "--follow-camera --script " +
                              (foresight::data_dir() / "recordings/maze_eval.json").string() +
                              " --screenshot-at-s 3";
  // No bots: one that walks between the camera and the player hides the tree's lines on the
  // floor (it did in CI), and the player's own tree does not depend on them.
  // A fixed number of expansions a tick, not a time budget: on a loaded machine (CI runs tests
  // side by side) a time budget grew a bare chain, so no unchosen line was left to see.
  const std::vector<std::string> fixed_growth = {"--expansions", "300"};
  Image plain, overlay;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("tree-off", walking, plain, 0, fixed_growth));
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("tree-overlay", walking + " --tree-overlay", overlay, 0, fixed_growth));
  // The overlay's unlit colours (tree_overlay.hpp): cyan (0.10, 0.85, 0.85) for the tree, yellow
  // (1.00, 0.95, 0.10) for the chosen branch. Without the overlay neither appears.
  static_assert(foresight::client::kTreeColour.y == 0.85f && foresight::client::kChosenColour.z == 0.10f);
  const size_t tree = count_colour(overlay, 26, 217, 217), chosen = count_colour(overlay, 255, 242, 26);
  EXPECT_GT(tree, 30u) << "the tree's lines do not appear";
  EXPECT_GT(chosen, 10u) << "the chosen branch is not highlighted";
  EXPECT_LT(count_colour(plain, 26, 217, 217) + count_colour(plain, 255, 242, 26), 10u)
      << "the overlay colours appear without the overlay";
  // The chosen branch's ghost poses: lit pale yellow, so any shading of it.
  const size_t ghosts = ghost_pixels(overlay), ghosts_without = ghost_pixels(plain);
  EXPECT_GT(ghosts, 150u) << "no ghost poses";
  EXPECT_LT(ghosts_without, 50u) << "the ghost colour appears without the overlay";
  std::printf("tree %zu, chosen %zu, ghost %zu pixels (%zu without the overlay)\n", tree, chosen, ghosts,
              ghosts_without);
}

}  // namespace
