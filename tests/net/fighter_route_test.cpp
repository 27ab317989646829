// A fighter whose target stands behind a wall routes around it (scene_route for the library's
// walker) instead of walking into the wall: the dead_end scene's pocket lies between them.
#include "raw_client.hpp"
#include "support/test_paths.hpp"

#include "world/data_paths.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace foresight {
namespace {

using test::RawClient;
using namespace std::chrono_literals;

TEST(FighterRoute, AFighterBehindADeadEndWalksAroundItToThePlayer) {
  // dead_end with a sparring partner at its goal: the player spawns at the start, 9 m away, the
  // pocket's back wall (6 m wide) straight between them.
  std::ifstream in(data_dir() / "scenes" / "dead_end.json", std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::string scene = text.str();
  const std::string npcs = "\"npcs\": []";
  ASSERT_NE(scene.find(npcs), std::string::npos);
  scene.replace(scene.find(npcs), npcs.size(),
                R"("npcs": [{"name": "behind", "kind": "sparring-partner", "pos": [6.0, 10.5], "heading_deg": 180.0}])");
  const std::filesystem::path path = test::scratch_dir() / "dead_end_with_fighter.json";
  std::ofstream(path, std::ios::binary) << scene;

  server::ServerConfig config = test::test_server_config(path.string());
  config.fighters = -1;  // the scene's
  config.fighters_auto_attack = false;
  server::Server server;
  std::string error;
  ASSERT_TRUE(server.start(config, error)) << error;
  server::Clock::time_point now = server::Clock::now();
  RawClient c(server.port());
  ASSERT_TRUE(c.connect(server, now, server.library().content_hash));
  ASSERT_EQ(server.fighter_ids().size(), 1u);
  const uint32_t fighter = server.fighter_ids().front();
  const vec2 player = server.avatar(c.avatar)->root().pos_m;
  uint32_t seq = 1;
  float closest = 1e9f;
  for (int i = 0; i < 30 * 40 && closest > 1.5f; ++i) {
    c.send_input(vec2(0.0f), seq++, 0.0f);
    server.run_tick(now += 33ms);
    closest = std::min(closest, glm::length(server.avatar(fighter)->root().pos_m - player));
  }
  EXPECT_LE(closest, 1.5f) << "the fighter came around the pocket to the player";
  EXPECT_EQ(server.counters().fighter_route_failures, 0u);
}

}  // namespace
}  // namespace foresight
