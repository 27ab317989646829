#pragma once
// Datagrams gathered and sent together with sendmmsg(2): one system call for up to kCapacity
// datagrams instead of one each (the server's snapshot phase sends one or more a client a
// snapshot). Each thread keeps its own batch; the socket's descriptor may be written from
// several threads at once.
#include "protocol/packet.hpp"
#include "transport/udp_socket.hpp"

#include <sys/socket.h>

#include <array>
#include <cstdint>
#include <span>

namespace foresight::protocol {

class DatagramBatch {
 public:
  static constexpr size_t kCapacity = 64;

  /// Copies `datagram` (at most kMaxDatagramBytes) for `to`; sends the batch first when full.
  void add(UdpSocket& socket, std::span<const uint8_t> datagram, const Endpoint& to);
  /// Sends what is gathered.
  void flush(UdpSocket& socket);

  /// Since the last take_counts(): datagrams and bytes the kernel took, and datagrams it refused.
  struct Counts {
    uint64_t sent = 0, bytes = 0, failed = 0;
  };
  Counts take_counts();

 private:
  std::array<std::array<uint8_t, kMaxDatagramBytes>, kCapacity> payload_{};
  std::array<Endpoint, kCapacity> to_{};
  std::array<iovec, kCapacity> iov_{};
  std::array<mmsghdr, kCapacity> headers_{};
  size_t count_ = 0;
  Counts counts_;
};

}  // namespace foresight::protocol
