#pragma once
// Datagrams sent and received in batches: sendmmsg(2) and recvmmsg(2), one system call for up to
// kCapacity datagrams instead of one each (the server sends one or more datagrams a client a
// snapshot, and receives 30 inputs a second from each). Each thread keeps its own batch; the
// socket's descriptor may be written from several threads at once.
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

/// The receiving side: what is waiting on the socket, taken in one recvmmsg(2).
class DatagramInbox {
 public:
  static constexpr size_t kCapacity = 64;

  /// Takes the datagrams waiting (at most kCapacity; never waits). Returns how many.
  size_t receive(UdpSocket& socket);
  /// The i-th datagram taken (i < what receive() returned): its bytes, kMaxDatagramBytes + 1 of
  /// them when it was longer than kMaxDatagramBytes (as UdpSocket::receive reports one), and its
  /// sender.
  std::span<const uint8_t> datagram(size_t i) const { return {payload_[i].bytes.data(), sizes_[i]}; }
  const Endpoint& from(size_t i) const { return from_[i]; }

 private:
  // Each buffer starts 16-byte aligned, as the packet reader's FlatBuffers want (a row of
  // kMaxDatagramBytes + 1 bytes would put every other one at an odd address).
  struct alignas(16) Buffer {
    std::array<uint8_t, kMaxDatagramBytes + 1> bytes;
  };
  std::array<Buffer, kCapacity> payload_{};
  std::array<size_t, kCapacity> sizes_{};
  std::array<Endpoint, kCapacity> from_{};
  std::array<iovec, kCapacity> iov_{};
  std::array<mmsghdr, kCapacity> headers_{};
};

}  // namespace foresight::protocol
