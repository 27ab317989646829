// "The view changes when the avatar moves": the player alone on the maze (no bots, so nothing
// else moves), seen from the designer cameras, shot at two moments of one script in two runs.
// The maze recording walks up the first corridor between the shots, which must change the
// picture clearly; the control, a script that never moves, must leave it (nearly) as it was, so
// the check can fail. (Not the follow camera: at the spawn places, in corners, it stands behind
// the outer wall and sways with the idle clip's root.)
#include "client_process.hpp"
#include "support/test_paths.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace {

using namespace foresight::test;

constexpr double kFirstShotS = 1.0, kSecondShotS = 3.5;  // maze_eval walks from 0.3 s on
/// The debug overlay's window (top left, 300 px wide, ImGui's 8 px margin): its figures change
/// every frame, so it is left out of the comparison.
constexpr int kOverlayRight = 320, kOverlayBottom = 390;

// Pixels outside the debug overlay where some channel differs by more than a little (the
// standing avatar's idle clip still moves a few).
size_t changed_pixels(const Image& a, const Image& b) {
  if (a.w != b.w || a.h != b.h) return a.size();
  size_t changed = 0;
  for (int y = 0; y < a.h; ++y) {
    for (int x = 0; x < a.w; ++x) {
      if (x < kOverlayRight && y < kOverlayBottom) continue;
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(a.w) + static_cast<size_t>(x);
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a.pixels[3 * i + c] - b.pixels[3 * i + c]));
      if (d > 24) ++changed;
    }
  }
  return changed;
}

// Shoots the script at kFirstShotS and kSecondShotS after connecting (a fresh server each time,
// so the player takes the maze's first spawn place both times) and returns the changed pixels.
long view_change(const std::filesystem::path& dir, const std::string& stem, const std::string& script) {
  Image first, second;
  ClientRun run;
  run.dir = dir;
  run.bots = 0;
  for (Image* img : {&first, &second}) {
    const double at = img == &first ? kFirstShotS : kSecondShotS;
    run.name = stem + (img == &first ? "-first" : "-second");
    run.client_args = "--script " + script + " --screenshot-at-s " + std::to_string(at);
    run_client_screenshot(run, *img);
    if (::testing::Test::HasFatalFailure()) return -1;
  }
  const size_t changed = changed_pixels(first, second);
  std::printf("%s: %zu pixels changed between %.1f s and %.1f s\n", stem.c_str(), changed, kFirstShotS,
              kSecondShotS);
  return static_cast<long>(changed);
}

TEST(ClientScreenshot, TheViewChangesWhenTheAvatarMovesAndNotWhenItStands) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  const std::filesystem::path dir = scratch_dir();
  // The control: the recording's start and camera, never a direction.
  const std::string still = (dir / "still.json").string();
  {
    std::ofstream f(still);
    f << R"({"format": "foresight-recording", "version": 1, "scene": "maze",
  "start": {"pos": [11.25, 8.75], "heading_deg": 90}, "goal": {"pos": [1.25, 18.75]},
  "samples": [
    {"t": 0, "dir": [0, 0], "camera_yaw_deg": -45},
    {"t": 30, "dir": [0, 0], "camera_yaw_deg": -45}
  ]})";
  }
  const long walking = view_change(dir, "walk", (foresight::data_dir() / "recordings/maze_eval.json").string());
  ASSERT_FALSE(HasFatalFailure());
  const long standing = view_change(dir, "still", still);
  ASSERT_FALSE(HasFatalFailure());
  EXPECT_GT(walking, 1000) << "the avatar walked, but the view hardly changed";
  EXPECT_LT(standing, 300) << "the avatar stood still, but the view changed";
  EXPECT_GT(walking, 5 * standing) << "walking changes the view no more than standing still";
}

}  // namespace
