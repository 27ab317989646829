// Custom scenes reach bots that never had the file: the Accept carries the scene file's hash and
// size, a bot whose own copy is missing or different fetches the server's over the sealed session,
// and a scene named like a built-in is never mistaken for it.
#include "bot_match.hpp"
#include "support/test_paths.hpp"

#include "transport/scene_transfer.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace foresight {
namespace {

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The built-in doorways scene under another name, in a folder the bots do not look in.
std::filesystem::path custom_scene(const std::string& name) {
  std::string text = read_all(data_dir() / "scenes" / "doorways.json");
  const std::string from = "\"name\": \"doorways\"";
  text.replace(text.find(from), from.size(), "\"name\": \"" + name + "\"");
  const std::filesystem::path path = test::scratch_dir() / (name + "_custom.json");
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// A server on `scene` (by path) and two goal bots that were given no scene.
struct Played {
  test::BotMatch match;
  bots::BotFleet fleet;
  bots::BotReport report;
  Played(const std::filesystem::path& scene, int seconds)
      : match(test::test_server_config(scene.string()), 2, bots::BotScript::kGoals),
        fleet(match.server.library(), match.config) {
    match.play(fleet, 30 * seconds);
    report = fleet.report(match.now);
  }
};

TEST(SceneTransfer, BotsFetchAScenePlayedByPathAndWalkIt) {
  const std::filesystem::path path = custom_scene("custom-doorways");
  ASSERT_FALSE(std::filesystem::exists(data_dir() / "scenes" / "custom-doorways.json"));
  const Played p(path, 20);
  const bots::BotReport& r = p.report;
  const bots::BotWorld* world = &p.fleet.world();
  EXPECT_TRUE(r.error.empty()) << r.error;
  ASSERT_TRUE(world->loaded);
  EXPECT_EQ(world->scene_name, "custom-doorways");
  EXPECT_EQ(world->scene.boxes.size(), 10u);  // 4 outer walls + 3 cross walls in two pieces
  EXPECT_GT(p.match.server.counters().scene_parts_sent, 1u);
  EXPECT_GT(r.walked_m_mean, 3.0) << "bots play the fetched scene";
  EXPECT_EQ(r.scene_collisions + r.avatar_contacts, 0u);
}

TEST(SceneTransfer, ASceneNamedLikeABuiltInIsFetchedNotMistakenForIt) {
  const std::filesystem::path path = custom_scene("maze");  // the doorways rooms, called "maze"
  const Played p(path, 2);
  const bots::BotWorld* world = &p.fleet.world();
  ASSERT_TRUE(world->loaded) << p.report.error;
  EXPECT_EQ(world->scene_name, "maze");
  EXPECT_EQ(world->scene.boxes.size(), 10u) << "the server's rooms, not the built-in maze";
  EXPECT_EQ(world->scene.bounds.max_m, vec2(6.0f, 12.0f));
}

TEST(SceneTransfer, TheOwnCopyIsUsedWhenItIsTheServersFile) {
  const Played p(data_dir() / "scenes" / "dead_end.json", 1);
  ASSERT_TRUE(p.fleet.world().loaded);
  EXPECT_EQ(p.match.server.counters().scene_parts_sent, 0u);
}

TEST(SceneTransfer, TheServerAnswersInRangeRequestsOfItsOwnSessionAndCountsTheRest) {
  server::Server server;
  server::Clock::time_point now = server::Clock::now();
  std::string error;
  ASSERT_TRUE(server.start(test::test_server_config("doorways"), error)) << error;
  test::RawClient c(server.port());
  ASSERT_TRUE(c.connect(server, now, server.library().content_hash));
  const std::string file = read_all(data_dir() / "scenes" / "doorways.json");
  protocol::PacketWriter w;
  c.receive_all();  // the handshake's leftovers
  c.send_session(protocol::write_scene_request(w, c.session, 1000));
  server.run_tick(now += std::chrono::milliseconds(33));
  const auto part = c.receive(wire::Message::ScenePart);
  ASSERT_TRUE(part.has_value());
  protocol::DropReason reason;
  const wire::ScenePart* m = protocol::packet_read(*part, reason)->message_as_ScenePart();
  EXPECT_EQ(m->scene_hash(), protocol::scene_file_hash(file));
  EXPECT_EQ(m->total(), file.size());
  EXPECT_EQ(m->offset(), 1000u);
  ASSERT_NE(m->data(), nullptr);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(m->data()->data()), m->data()->size()),
            file.substr(1000, protocol::kScenePartBytes));
  // Past the end: nothing back, counted.
  const auto& drops = server.counters().drops.by_reason;
  const uint64_t unexpected = drops[static_cast<size_t>(protocol::DropReason::kUnexpected)];
  c.send_session(protocol::write_scene_request(w, c.session, static_cast<uint32_t>(file.size())));
  server.run_tick(now += std::chrono::milliseconds(33));
  EXPECT_FALSE(c.receive(wire::Message::ScenePart).has_value());
  EXPECT_EQ(drops[static_cast<size_t>(protocol::DropReason::kUnexpected)], unexpected + 1);
  // Unsealed (anyone could have sent it): nothing back.
  c.send(protocol::write_scene_request(w, c.session, 0));
  server.run_tick(now += std::chrono::milliseconds(33));
  EXPECT_FALSE(c.receive(wire::Message::ScenePart).has_value());
  EXPECT_EQ(server.counters().scene_parts_sent, 1u);
}

TEST(SceneTransfer, TheDownloadKeepsOnlyPartsInOrderWithTheRightHash) {
  const std::string text = "{\"a scene\": \"" + std::string(2500, 'x') + "\"}";
  const uint64_t hash = protocol::scene_file_hash(text);
  protocol::SceneDownload d;
  d.start(hash, static_cast<uint32_t>(text.size()));
  flatbuffers::FlatBufferBuilder fbb;
  const auto part = [&](uint64_t h, uint32_t offset, uint32_t n) {
    fbb.Clear();
    const auto data = fbb.CreateVector(reinterpret_cast<const uint8_t*>(text.data()) + offset, n);
    fbb.Finish(wire::CreateScenePart(fbb, h, static_cast<uint32_t>(text.size()), offset, data));
    return d.add(*flatbuffers::GetRoot<wire::ScenePart>(fbb.GetBufferPointer()));
  };
  EXPECT_FALSE(part(hash, 1000, 1000)) << "out of order";
  EXPECT_FALSE(part(hash ^ 1u, 0, 1000)) << "another scene's part";
  EXPECT_TRUE(part(hash, 0, 1000));
  EXPECT_FALSE(part(hash, 0, 1000)) << "a repeat";
  EXPECT_TRUE(part(hash, 1000, 1000));
  EXPECT_FALSE(d.complete());
  EXPECT_TRUE(part(hash, 2000, static_cast<uint32_t>(text.size()) - 2000));
  EXPECT_TRUE(d.verified());
  EXPECT_EQ(d.bytes(), text);
  d.start(hash ^ 1u, static_cast<uint32_t>(text.size()));  // the Accept named another hash
  for (uint32_t off = 0; off < text.size(); off += 1000)
    part(hash ^ 1u, off, std::min<uint32_t>(1000, static_cast<uint32_t>(text.size()) - off));
  EXPECT_TRUE(d.complete());
  EXPECT_FALSE(d.verified()) << "bytes that do not hash to the Accept's hash are not the scene";
}

}  // namespace
}  // namespace foresight
