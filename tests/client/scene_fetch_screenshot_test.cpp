// A client that never had the server's scene: the server plays a scene given by path (the doorways
// rooms renamed, in a folder nobody else looks in); the client fetches the file over its session
// and draws it (docs/PROTOCOL.md, "Scenes").
#include "client_process.hpp"
#include "support/test_paths.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace {

using namespace foresight::test;

TEST(ClientScreenshot, FetchesAndDrawsASceneItNeverHad) {
  if (!have_xvfb())
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  std::ifstream in(foresight::data_dir() / "scenes" / "doorways.json", std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const std::string from = "\"name\": \"doorways\"";
  scene.replace(scene.find(from), from.size(), "\"name\": \"rooms-only-the-server-has\"");
  ClientRun run;
  run.dir = scratch_dir();
  run.name = "fetched-scene";
  run.scene = (run.dir / "rooms_only_the_server_has.json").string();
  std::ofstream(run.scene, std::ios::binary) << scene;
  run.bots = 0;
  Image img;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot(run, img));
  std::ifstream log_file(run.dir / "fetched-scene-client.log");
  std::ostringstream log;
  log << log_file.rdbuf();
  EXPECT_NE(log.str().find("scene 'rooms-only-the-server-has': no copy here, fetching the server's"), std::string::npos)
      << log.str();
  EXPECT_NE(log.str().find("scene 'rooms-only-the-server-has' fetched from the server"), std::string::npos) << log.str();
  EXPECT_GT(non_uniform_share(img), 0.25) << "the image is (nearly) uniform";
  EXPECT_GT(orange_pixels(img), 20u) << "the player's avatar colour does not appear";
}

}  // namespace
