// NPC fighters as a person sees them: a real server on the arena scene (its five NPC spawns, the
// fighters' own policy on: they walk up to the player and strike), the client under Xvfb with the
// follow camera, a shot a few seconds after connecting. The fighters are drawn from their
// streamed poses in crimson (fighter_poses.hpp): that colour must appear, and must not without
// fighters (the control, so the check can fail).
#include "client_process.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using namespace foresight::test;

/// Left out of the count: a band along the edges (the hit flash tints them red) and the debug
/// overlay's corner (its red quality dot).
constexpr int kEdgeMargin = 100, kOverlayRight = 330, kOverlayBottom = 460;

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ClientScreenshot, ShowsTheArenaFightersInTheirColour) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  ClientRun run;
  run.dir = scratch_dir();
  run.scene = "arena";
  run.bots = 0;
  // The player stands still at the arena's first spawn, facing the centre; the fighters (one per
  // NPC spawn) walk towards it, so after 5 s the nearest are in front of the follow camera.
  run.client_args = "--follow-camera --screenshot-at-s 5";
  run.name = "fighters";
  Image with;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot(run, with));
  run.name = "no-fighters";
  run.server_args = {"--fighters", "0"};
  Image without;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot(run, without));

  EXPECT_EQ(with.w, 1280);
  EXPECT_EQ(with.h, 720);
  const size_t fighters = fighter_pixels(with, kEdgeMargin, kOverlayRight, kOverlayBottom);
  const size_t control = fighter_pixels(without, kEdgeMargin, kOverlayRight, kOverlayBottom);
  std::printf("fighter-coloured pixels: %zu with fighters, %zu without\n", fighters, control);
  EXPECT_GT(fighters, 300u) << "the fighters' crimson does not appear; see " << (run.dir / "fighters.png");
  EXPECT_LT(control, 20u) << "the fighters' colour appears without fighters";
  // The client said how many fighters it drew in the shot.
  const std::string log = read_file(run.dir / "fighters-client.log");
  EXPECT_NE(log.find("fighters)"), std::string::npos) << log;
  EXPECT_EQ(log.find(", 0 fighters)"), std::string::npos) << log;
  EXPECT_NE(read_file(run.dir / "no-fighters-client.log").find(", 0 fighters)"), std::string::npos);
}

}  // namespace
