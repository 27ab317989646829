// Writes a seed corpus for fuzz-packet: one valid datagram of each kind the peers exchange, so
// the fuzzer starts past the identifier and the verifier. Usage: fuzz-packet-seeds DIR
#include "fuzz_history.hpp"
#include "protocol/input_packet.hpp"
#include "protocol/packet.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

using namespace foresight;
using namespace foresight::protocol;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz-packet-seeds DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  int n = 0;
  auto save = [&](std::span<const uint8_t> bytes) {
    std::ofstream(dir + "/seed-" + std::to_string(n++) + ".bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  };
  PacketWriter w;
  save(write_connect_request(w, 0x1234, "seed"));
  const std::array<uint8_t, 16> cookie{1, 2, 3};
  save(write_connect_response(w, 0x1234, cookie, "seed"));
  save(write_heartbeat(w, 1, 1000));
  save(write_disconnect(w, 1));
  save(write_stats_request(w, 1));
  save(write_tree_request(w, 1));
  ControlInput in;
  in.camera_dir = {0.6f, 0.8f};
  const std::array<wire::InputCommand, 2> commands{input_command_from(in, 7), input_command_from({}, 8)};
  save(write_input(w, 1, 3, 1000, commands));
  // Avatar 1 coded against the fuzz history's snapshot 1 (this is snapshot 2), 9 whole.
  protocol::WholeViewSender sender;
  fuzz::fuzz_sent(sender);
  const std::array<wire::AvatarState, 2> avatars{wire::AvatarState(1, 100, 200, -1, 3, 500, 4, 0, 0),
                                                wire::AvatarState(9, 0, 0, -1, 0xFFFF, 0, 0, 16, 0)};
  protocol::AvatarDeltaEncoder encoder;
  sender.plan(encoder, avatars, 2, 3);
  std::vector<uint8_t> packed;
  encoder.write_part(0, avatars.size(), packed);
  auto& fbb = w.begin();
  const std::array<uint32_t, 3> rotations{0, 12345, 0xFFFFFFFFu};
  const auto fighter = wire::CreateFighterPose(fbb, 1, 0, 10, 900, 20, fbb.CreateVector(rotations.data(), rotations.size()));
  const std::array<int16_t, 18> angles{100, -100, 2000};
  const wire::TerrainBody body(2, 1, 950, 2, 300, 0, 1, flatbuffers::span<const int16_t, 18>(angles));
  const wire::StrikeEventState event(1, 1, 2, 0, 1600, 0, 40, true, false);
  const auto snapshot = wire::CreateSnapshot(fbb, 2, 0, 1, 8, 1000, 2000, fbb.CreateVector(&fighter, 1),
                                             fbb.CreateVectorOfStructs(&event, 1), fbb.CreateVectorOfStructs(&body, 1),
                                             static_cast<uint16_t>(avatars.size()), fbb.CreateVector(packed));
  save(w.finish(snapshot));
  auto& sealed_fbb = w.begin();
  const std::array<uint8_t, 40> payload{1, 2, 3};
  save(w.finish(wire::CreateSealed(sealed_fbb, 1, 7, sealed_fbb.CreateVector(payload.data(), payload.size()))));
  std::printf("%d seeds in %s\n", n, dir.c_str());
  return 0;
}
