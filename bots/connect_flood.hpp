#pragma once
// A connect flood beside the bots (foresight-bots --flood-connects-per-s, docs/RELIABILITY.md
// "Connect floods"): bogus ConnectRequests at a steady rate from 64 sockets, never following up a
// Challenge, plus one forged ConnectResponse (a made-up cookie) in ten, on a thread of its own, so
// the server's tick time and memory can be measured in real time under a flood while bots play.
#include "transport/udp_socket.hpp"

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

namespace foresight::bots {

class ConnectFlood {
 public:
  ConnectFlood() = default;
  ~ConnectFlood() { stop(); }
  ConnectFlood(const ConnectFlood&) = delete;
  ConnectFlood& operator=(const ConnectFlood&) = delete;

  /// Starts flooding `server` at `per_second` datagrams. False (with error) if no socket opens.
  bool start(const protocol::Endpoint& server, uint64_t library_hash, double per_second, std::string& error);
  void stop();
  uint64_t sent() const { return sent_.load(); }

 private:
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> sent_{0};
};

}  // namespace foresight::bots
