// Spawns are checked for the body that must stand there: a spawn too close to a wall is reported
// with the room it lacks, a join still finds the nearest free place (searched finely: 0.25 m
// rings, four headings), and a join with no free place left is refused as NoSpawnPlace.
#include "raw_client.hpp"
#include "support/test_paths.hpp"

#include "library/body_fit.hpp"
#include "lookahead/lookahead_avatar.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace foresight {
namespace {

using test::RawClient;

/// A walled room `inside_x` by `inside_z` m (walls 0.2 m thick inside the bounds, 2.5 m high), one
/// spawn at (spawn_x, spawn_z) facing +Z, written to the scratch folder as `name`.json.
std::filesystem::path write_walled_room(const std::string& name, double inside_x, double inside_z, double spawn_x,
                                        double spawn_z) {
  const double x = inside_x + 0.4, z = inside_z + 0.4;
  const std::filesystem::path path = test::scratch_dir() / (name + ".json");
  std::ofstream(path) << nlohmann::json{
      {"format", "foresight-scene"}, {"version", 1}, {"name", name},
      {"bounds", {{"min", {0, 0}}, {"max", {x, z}}}},
      {"boxes",
       {{{"kind", "wall"}, {"name", "west"}, {"min", {0, 0, 0}}, {"max", {0.2, 2.5, z}}},
        {{"kind", "wall"}, {"name", "east"}, {"min", {x - 0.2, 0, 0}}, {"max", {x, 2.5, z}}},
        {{"kind", "wall"}, {"name", "south"}, {"min", {0.2, 0, 0}}, {"max", {x - 0.2, 2.5, 0.2}}},
        {{"kind", "wall"}, {"name", "north"}, {"min", {0.2, 0, z - 0.2}}, {"max", {x - 0.2, 2.5, z}}}}},
      {"spawns", {{{"name", "spawn"}, {"pos", {spawn_x, spawn_z}}, {"heading_deg", 0}}}}};
  return path;
}

/// A 3 x 3 m room, its spawn 0.25 m from the west wall.
std::filesystem::path write_small_room() { return write_walled_room("small-room", 3.0, 3.0, 0.45, 1.7); }

TEST(Spawn, ABodyThatDoesNotFitSaysWhatIsInTheWayAndByHowMuch) {
  Scene scene;
  CollisionWorld world;
  std::string error;
  ASSERT_TRUE(scene_world_load(write_small_room().string(), scene, world, error)) << error;
  const MotionLibrary lib = motion_library_default();
  const int idle = find_fallback_segment(lib);
  const Placement spawn{scene.spawns[0].pos_m, scene.spawns[0].heading_rad};
  const std::string why = body_fit_problem(lib, scene, world, idle, spawn);
  EXPECT_NE(why.find("overlaps wall 'west' by"), std::string::npos) << why;
  // The idle body's half width beyond the 0.25 m the spawn leaves.
  const float lacks = 0.5f * segment_body(lib, idle).width_m - 0.25f;
  char expected[32];
  std::snprintf(expected, sizeof expected, "by %.2f m", static_cast<double>(lacks));
  EXPECT_NE(why.find(expected), std::string::npos) << why << " (expected " << expected << ")";
  // Moved by that much (and a millimetre), it fits.
  EXPECT_EQ(body_fit_problem(lib, scene, world, idle, Placement{spawn.pos_m + vec2(lacks + 0.01f, 0.0f), 0.0f}), "");
}

TEST(Spawn, JoinsFindTheFreePlacesNearASpawnThatDoesNotFitThenAreRefusedAsNoSpawnPlace) {
  server::Server server;
  server::Clock::time_point now = server::Clock::now();
  std::string error;
  ASSERT_TRUE(server.start(test::test_server_config(write_small_room().string()), error)) << error;
  Scene scene;
  CollisionWorld world;
  ASSERT_TRUE(scene_world_load(write_small_room().string(), scene, world, error)) << error;
  std::vector<std::unique_ptr<RawClient>> clients;
  int accepted = 0;
  std::vector<uint8_t> refuse;
  for (int i = 0; i < 40 && refuse.empty(); ++i) {
    clients.push_back(std::make_unique<RawClient>(server.port()));
    if (clients.back()->connect(server, now, server.library().content_hash, &refuse)) {
      ++accepted;
      const LookaheadAvatar* a = server.avatar(clients.back()->avatar);
      ASSERT_NE(a, nullptr);
      EXPECT_EQ(body_fit_problem(server.library(), scene, world, find_fallback_segment(server.library()),
                                 a->playback().segment_start),
                "")
          << "placed where the body fits";
    }
  }
  EXPECT_GE(accepted, 2) << "a 2.8 m square room holds more than one standing body";
  ASSERT_FALSE(refuse.empty()) << "the room filled up";
  protocol::DropReason reason;
  const wire::Refuse* m = protocol::packet_read(refuse, reason)->message_as_Refuse();
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->reason(), wire::RefuseReason::NoSpawnPlace);
  EXPECT_NE(m->message()->str().find("no free spawn place"), std::string::npos) << m->message()->str();
  EXPECT_EQ(server.counters().spawn_refusals, 1u);
}

/// A corridor 1 m wide and 4.6 m long (a level drawn by someone else: narrower than our scenes'
/// passages), its spawn near the south end.
std::filesystem::path write_narrow_corridor() {
  return write_walled_room("narrow-corridor", 1.0, 4.6, 0.7, 0.9);
}

// A join passes over the places found taken in the last half second (in a burst of joins they
// are still taken: checking them again made each join cost O(players)), but not when nothing
// else is free: in a full scene, a player who leaves frees a place the next join takes at once,
// where the body fits and clear of everybody. In our small room and in a narrow corridor.
void expect_freed_place_given_at_once(const std::filesystem::path& scene_path) {
  server::Server server;
  server::Clock::time_point now = server::Clock::now();
  std::string error;
  ASSERT_TRUE(server.start(test::test_server_config(scene_path.string()), error)) << error;
  std::vector<std::unique_ptr<RawClient>> clients;
  std::vector<uint8_t> refuse;
  for (int i = 0; i < 40 && refuse.empty(); ++i) {
    clients.push_back(std::make_unique<RawClient>(server.port()));
    if (!clients.back()->connect(server, now, server.library().content_hash, &refuse)) clients.pop_back();
  }
  ASSERT_FALSE(refuse.empty()) << "the room filled up";
  ASSERT_GE(clients.size(), 2u);
  const Placement freed = server.avatar(clients.front()->avatar)->playback().segment_start;
  RawClient& leaving = *clients.front();
  leaving.send_session(protocol::write_disconnect(leaving.writer_, leaving.session));
  server.run_tick(now += std::chrono::milliseconds(1));
  clients.push_back(std::make_unique<RawClient>(server.port()));
  refuse.clear();
  ASSERT_TRUE(clients.back()->connect(server, now, server.library().content_hash, &refuse))
      << "the freed place, found taken a few ticks ago, is free now";
  const Placement given = server.avatar(clients.back()->avatar)->playback().segment_start;
  EXPECT_LT(glm::length(given.pos_m - freed.pos_m), 0.01f) << "the only free place is the one left";
  EXPECT_EQ(server.counters().avatar_contacts, 0u);
}

TEST(Spawn, APlaceFreedInAFullSceneIsGivenToTheNextJoinAtOnce) {
  ASSERT_NO_FATAL_FAILURE(expect_freed_place_given_at_once(write_small_room())) << "small room";
  ASSERT_NO_FATAL_FAILURE(expect_freed_place_given_at_once(write_narrow_corridor())) << "narrow corridor";
}

}  // namespace
}  // namespace foresight
