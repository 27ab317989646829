#include "transport/datagram_batch.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace foresight::protocol {

void DatagramBatch::add(UdpSocket& socket, std::span<const uint8_t> datagram, const Endpoint& to) {
  if (datagram.size() > kMaxDatagramBytes) {  // never built by our writers; refused, not cut
    ++counts_.failed;
    return;
  }
  if (count_ == kCapacity) flush(socket);
  std::memcpy(payload_[count_].data(), datagram.data(), datagram.size());
  iov_[count_] = {payload_[count_].data(), datagram.size()};
  to_[count_] = to;
  ++count_;
}

void DatagramBatch::flush(UdpSocket& socket) {
  const int fd = socket.native_handle();
  size_t done = 0;
  for (size_t i = 0; i < count_; ++i) {
    msghdr& h = headers_[i].msg_hdr;
    h = msghdr{};
    h.msg_name = to_[i].data();
    h.msg_namelen = static_cast<socklen_t>(to_[i].size());
    h.msg_iov = &iov_[i];
    h.msg_iovlen = 1;
  }
  while (done < count_) {
    const int sent = fd < 0 ? -1
                            : ::sendmmsg(fd, headers_.data() + done, static_cast<unsigned>(count_ - done), MSG_DONTWAIT);
    if (sent > 0) {
      for (size_t i = done; i < done + static_cast<size_t>(sent); ++i) counts_.bytes += iov_[i].iov_len;
      counts_.sent += static_cast<uint64_t>(sent);
      done += static_cast<size_t>(sent);
      continue;
    }
    if (sent < 0 && errno == EINTR) continue;
    // The first datagram left was refused (a full buffer, an unreachable address): count it and
    // go on with the rest, as single sends would.
    ++counts_.failed;
    ++done;
  }
  count_ = 0;
}

size_t DatagramInbox::receive(UdpSocket& socket) {
  const int fd = socket.native_handle();
  if (fd < 0) return 0;
  for (size_t i = 0; i < kCapacity; ++i) {
    iov_[i] = {payload_[i].bytes.data(), payload_[i].bytes.size()};
    msghdr& h = headers_[i].msg_hdr;
    h = msghdr{};
    h.msg_name = from_[i].data();
    h.msg_namelen = static_cast<socklen_t>(from_[i].capacity());
    h.msg_iov = &iov_[i];
    h.msg_iovlen = 1;
  }
  int n;
  do {
    n = ::recvmmsg(fd, headers_.data(), static_cast<unsigned>(kCapacity), MSG_DONTWAIT, nullptr);
  } while (n < 0 && errno == EINTR);
  if (n <= 0) return 0;  // nothing waiting (EAGAIN), or an error the next call will see again
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    from_[i].resize(headers_[i].msg_hdr.msg_namelen);
    // A datagram longer than the buffer is cut to it and flagged: reported one byte over the
    // limit, so the packet reader refuses it as too large instead of reading a cut message.
    const bool cut = (headers_[i].msg_hdr.msg_flags & MSG_TRUNC) != 0;
    sizes_[i] = cut ? kMaxDatagramBytes + 1 : std::min<size_t>(headers_[i].msg_len, kMaxDatagramBytes + 1);
  }
  return static_cast<size_t>(n);
}

DatagramBatch::Counts DatagramBatch::take_counts() {
  const Counts c = counts_;
  counts_ = {};
  return c;
}

}  // namespace foresight::protocol
