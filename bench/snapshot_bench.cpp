// snapshot: the per-client cost of the packed snapshot avatars (protocol/avatar_delta.hpp), the
// server's side and the client's, without sockets or sealing. A world of N avatars plays as the
// server plays it: each tick every avatar's frame moves on and about one in twenty starts a new
// segment somewhere near. R receivers each see V avatars (a fixed random choice, in id order) and
// get every snapshot; each acknowledges the snapshot two before (a round trip in flight). Timed,
// per snapshot and receiver: the server's references and coding (WholeViewSender::plan,
// AvatarDeltaEncoder::write_part, remember, acknowledge) and the client's decoding
// (decode_avatars against its AvatarHistory, then keeping the snapshot). Medians over rounds,
// in ns per avatar; the bytes per avatar come with them so a faster coder that codes worse shows.
#include "bench_commands.hpp"
#include "bench_json.hpp"
#include "protocol/avatar_delta.hpp"
#include "protocol/sent_views.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

namespace foresight::bench {

int bench_snapshot(const SnapshotBenchOptions& o) {
  using namespace protocol;
  using State = wire::AvatarState;
  using Clock = std::chrono::steady_clock;
  std::mt19937 rng(static_cast<unsigned>(o.seed));
  const auto n = static_cast<uint32_t>(o.avatars);
  std::uniform_int_distribution<int32_t> coordinate(0, 64000);
  std::uniform_int_distribution<int> segment(0, 199), step(-800, 800);
  std::vector<State> world;
  for (uint32_t id = 1; id <= n; ++id)
    world.emplace_back(id, coordinate(rng), coordinate(rng), -1, static_cast<uint16_t>(segment(rng)),
                       static_cast<uint16_t>(rng()), static_cast<uint8_t>(rng() % 30), 0, 0);
  struct Receiver {
    std::vector<uint32_t> view;  // indices into world, ascending
    WholeViewSender server;
    AvatarHistory client;
  };
  std::vector<Receiver> receivers(static_cast<size_t>(o.receivers));
  const auto per_view = static_cast<size_t>(std::min(o.view, o.avatars));
  for (Receiver& r : receivers) {
    std::vector<uint32_t> all(n);
    for (uint32_t i = 0; i < n; ++i) all[i] = i;
    std::shuffle(all.begin(), all.end(), rng);
    r.view.assign(all.begin(), all.begin() + static_cast<long>(per_view));
    std::sort(r.view.begin(), r.view.end());
    r.client.reserve(per_view);
  }
  AvatarDeltaEncoder encoder;
  std::vector<uint8_t> bytes;
  bytes.reserve(16384);
  std::vector<State> view, decoded;
  view.reserve(per_view);
  decoded.reserve(per_view);
  std::vector<double> encode_ns, decode_ns;
  double bytes_sum = 0, avatars_sum = 0;
  const int warm = 80;  // the histories' 64 slots filled
  for (int round = 0; round < warm + o.snapshots; ++round) {
    const auto snapshot = static_cast<uint32_t>(round + 1), tick = snapshot * 3 / 2;
    for (State& a : world) {  // the world moves on a tick and a half (20 Hz snapshots, 30 Hz ticks)
      if (rng() % 20 == 0)
        a = State(a.id(), a.start_x_mm() + step(rng), a.start_z_mm() + step(rng), static_cast<int32_t>(rng() % 500),
                  static_cast<uint16_t>(segment(rng)), static_cast<uint16_t>(a.start_heading() + step(rng)), 0, 0, 0);
      else
        a.mutate_frame(static_cast<uint8_t>(a.frame() + 1));
    }
    double encode = 0, decode = 0;
    for (Receiver& r : receivers) {
      view.clear();
      for (uint32_t i : r.view) view.push_back(world[i]);
      const auto t0 = Clock::now();
      r.server.plan(encoder, view, snapshot, tick);
      encoder.write_part(0, view.size(), bytes);
      r.server.remember(snapshot, tick, view);
      if (snapshot > 2) r.server.acknowledge(snapshot - 2);
      const auto t1 = Clock::now();
      decoded.clear();
      const AvatarDecodeStatus status =
          decode_avatars(bytes, static_cast<uint32_t>(view.size()), snapshot, r.client, decoded);
      AvatarHistory::Slot& kept = r.client.start(snapshot, tick);
      kept.avatars.assign(decoded.begin(), decoded.end());
      kept.usable = true;
      const auto t2 = Clock::now();
      if (status != AvatarDecodeStatus::kOk || decoded.size() != view.size()) {
        std::fprintf(stderr, "foresight-bench snapshot: decoding failed at snapshot %u\n", snapshot);
        return 1;
      }
      encode += std::chrono::duration<double, std::nano>(t1 - t0).count();
      decode += std::chrono::duration<double, std::nano>(t2 - t1).count();
      if (round >= warm) bytes_sum += static_cast<double>(bytes.size()), avatars_sum += static_cast<double>(view.size());
    }
    if (round < warm) continue;
    const double avatars = static_cast<double>(receivers.size() * per_view);
    encode_ns.push_back(encode / avatars);
    decode_ns.push_back(decode / avatars);
  }
  const double enc = median(encode_ns), dec = median(decode_ns), per_avatar = bytes_sum / avatars_sum;
  print_machine_line();
  std::printf("%d avatars, %d receivers seeing %zu each, %d snapshots (after %d to warm up), one thread\n", o.avatars,
              o.receivers, per_view, o.snapshots, warm);
  std::printf("  server: %.1f ns an avatar (references, coding, remembering, acknowledging); client: %.1f ns an avatar "
              "(decoding, keeping); %.2f bytes an avatar\n",
              enc, dec, per_avatar);
  if (o.json)
    print_json_line({{"bench", "snapshot"},
                     {"avatars", o.avatars},
                     {"receivers", o.receivers},
                     {"view", per_view},
                     {"snapshots", o.snapshots},
                     {"encode_ns_per_avatar", rounded(enc, 1)},
                     {"decode_ns_per_avatar", rounded(dec, 1)},
                     {"bytes_per_avatar", rounded(per_avatar, 3)}});
  return 0;
}

}  // namespace foresight::bench
