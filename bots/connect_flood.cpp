#include "connect_flood.hpp"

#include "protocol/packet.hpp"

#include <array>
#include <chrono>
#include <memory>
#include <vector>

namespace foresight::bots {

bool ConnectFlood::start(const protocol::Endpoint& server, uint64_t library_hash, double per_second, std::string& error) {
  stop();
  auto sockets = std::make_shared<std::vector<protocol::UdpSocket>>(64);
  const std::string bind = server.address().is_v6() ? "::" : "0.0.0.0";
  for (auto& s : *sockets)
    if (!s.open(bind, 0, error)) return false;
  protocol::PacketWriter w;
  const auto request = protocol::write_connect_request(w, library_hash, "flood");
  std::vector<uint8_t> connect(request.begin(), request.end());
  const std::array<uint8_t, 16> cookie{9, 9, 9};
  const auto response = protocol::write_connect_response(w, library_hash, cookie, "flood", {});
  std::vector<uint8_t> forged(response.begin(), response.end());
  stop_.store(false);
  thread_ = std::thread([this, sockets, server, per_second, connect = std::move(connect), forged = std::move(forged)] {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point begin = Clock::now();
    std::array<uint8_t, 2048> drain{};
    protocol::Endpoint from;
    uint64_t n = 0;
    while (!stop_.load()) {
      // Catch up to the rate in 1 ms steps (a steady stream, not bursts a second apart).
      const double elapsed = std::chrono::duration<double>(Clock::now() - begin).count();
      for (const auto due = static_cast<uint64_t>(elapsed * per_second); n < due; ++n) {
        protocol::UdpSocket& s = (*sockets)[n % sockets->size()];
        s.send(n % 10 == 9 ? forged : connect, server);
      }
      sent_.store(n);
      for (auto& s : *sockets)  // the server's answers: read and dropped, so the buffers never fill
        while (s.receive(drain, from) > 0) {
        }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  return true;
}

void ConnectFlood::stop() {
  stop_.store(true);
  if (thread_.joinable()) thread_.join();
}

}  // namespace foresight::bots
