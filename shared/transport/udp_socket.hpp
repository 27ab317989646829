#pragma once
// A non-blocking UDP socket (standalone Asio) for fixed-tick loops: the server and the bots read
// everything waiting once per tick and never block inside a tick.
#include <asio/ip/udp.hpp>
#include <asio/io_context.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace foresight::protocol {

using Endpoint = asio::ip::udp::endpoint;

/// "host:port" (IPv4 dotted or "localhost"; port 1-65535) to an endpoint, or false with a reason.
bool parse_endpoint(std::string_view text, Endpoint& out, std::string& error);

/// The address bytes of an endpoint (4 for IPv4, 16 for IPv6), for cookies.
std::span<const uint8_t> endpoint_address_bytes(const Endpoint& e, std::array<uint8_t, 16>& storage);

class UdpSocket {
 public:
  UdpSocket();
  /// Binds to address:port (port 0: any free port). False with a reason (port in use...).
  bool open(std::string_view address, uint16_t port, std::string& error);
  bool is_open() const { return socket_.is_open(); }
  uint16_t local_port() const;
  /// The OS descriptor, for callers that wait on many sockets at once (epoll); -1 when closed.
  int native_handle() { return is_open() ? socket_.native_handle() : -1; }

  /// Reads one waiting datagram into `buffer`; returns its size, or -1 when nothing is waiting.
  /// A datagram longer than the buffer is reported as buffer.size() + 1 (the caller drops it as
  /// too large).
  ptrdiff_t receive(std::span<uint8_t> buffer, Endpoint& from);
  /// Sends one datagram; false when the kernel refused it (counted by callers, never fatal).
  bool send(std::span<const uint8_t> datagram, const Endpoint& to);
  /// Blocks until a datagram is waiting or `timeout_ms` passed (for idle clients).
  bool wait_readable(int timeout_ms);

 private:
  asio::io_context io_;
  asio::ip::udp::socket socket_;
};

}  // namespace foresight::protocol
