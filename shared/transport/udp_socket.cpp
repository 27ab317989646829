#include "transport/udp_socket.hpp"

#include <poll.h>
#include <sys/socket.h>

#include <asio/ip/address.hpp>
#include <charconv>
#include <cstring>

namespace foresight::protocol {

bool parse_endpoint(std::string_view text, Endpoint& out, std::string& error) {
  const size_t colon = text.rfind(':');
  if (colon == std::string_view::npos) {
    error = "expected host:port, got '" + std::string(text) + "'";
    return false;
  }
  std::string host(text.substr(0, colon));
  if (host == "localhost") host = "127.0.0.1";
  const std::string_view port_text = text.substr(colon + 1);
  unsigned port = 0;
  const auto [end, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (ec != std::errc() || end != port_text.data() + port_text.size() || port == 0 || port > 65535) {
    error = "bad port in '" + std::string(text) + "'";
    return false;
  }
  asio::error_code aec;
  const asio::ip::address address = asio::ip::make_address(host, aec);
  if (aec) {
    error = "bad address '" + host + "': " + aec.message();
    return false;
  }
  out = Endpoint(address, static_cast<uint16_t>(port));
  return true;
}

std::span<const uint8_t> endpoint_address_bytes(const Endpoint& e, std::array<uint8_t, 16>& storage) {
  if (e.address().is_v4()) {
    const auto b = e.address().to_v4().to_bytes();
    std::memcpy(storage.data(), b.data(), b.size());
    return {storage.data(), b.size()};
  }
  const auto b = e.address().to_v6().to_bytes();
  std::memcpy(storage.data(), b.data(), b.size());
  return {storage.data(), b.size()};
}

UdpSocket::UdpSocket() : socket_(io_) {}

bool UdpSocket::open(std::string_view address, uint16_t port, std::string& error) {
  asio::error_code ec;
  const asio::ip::address a = asio::ip::make_address(std::string(address), ec);
  if (ec) {
    error = "bad bind address '" + std::string(address) + "': " + ec.message();
    return false;
  }
  socket_.open(a.is_v4() ? asio::ip::udp::v4() : asio::ip::udp::v6(), ec);
  if (!ec) socket_.non_blocking(true, ec);
  // Room for a burst of a few thousand datagrams between two ticks.
  if (!ec) socket_.set_option(asio::socket_base::receive_buffer_size(4 << 20), ec);
  if (!ec) socket_.set_option(asio::socket_base::send_buffer_size(4 << 20), ec);
  if (!ec) socket_.bind(Endpoint(a, port), ec);
  if (ec) {
    error = "cannot bind UDP " + std::string(address) + ":" + std::to_string(port) + ": " + ec.message();
    socket_.close(ec);
    return false;
  }
  return true;
}

uint16_t UdpSocket::local_port() const {
  asio::error_code ec;
  const Endpoint e = socket_.local_endpoint(ec);
  return ec ? 0 : e.port();
}

ptrdiff_t UdpSocket::receive(std::span<uint8_t> buffer, Endpoint& from) {
  // MSG_TRUNC makes recvfrom report the datagram's real length, so an oversized one is seen as
  // such instead of silently cut to the buffer.
  socklen_t len = static_cast<socklen_t>(from.capacity());
  const ssize_t n = ::recvfrom(socket_.native_handle(), buffer.data(), buffer.size(), MSG_TRUNC,
                               from.data(), &len);
  if (n < 0) return -1;  // nothing waiting (EAGAIN), or an error the next read will see again
  from.resize(len);
  return static_cast<size_t>(n) > buffer.size() ? static_cast<ptrdiff_t>(buffer.size() + 1) : n;
}

bool UdpSocket::send(std::span<const uint8_t> datagram, const Endpoint& to) {
  asio::error_code ec;
  socket_.send_to(asio::buffer(datagram.data(), datagram.size()), to, 0, ec);
  return !ec;
}

bool UdpSocket::wait_readable(int timeout_ms) {
  pollfd p{socket_.native_handle(), POLLIN, 0};
  return ::poll(&p, 1, timeout_ms) > 0;
}

}  // namespace foresight::protocol
