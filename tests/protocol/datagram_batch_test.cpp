// Datagrams sent in sendmmsg batches (transport/datagram_batch.hpp) over real UDP sockets on
// loopback: every one arrives whole, in order, at its own address, past a full batch; what the
// kernel cannot take is counted, never silently lost.
#include "transport/datagram_batch.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace foresight::protocol {
namespace {

void open_loopback(UdpSocket& s) {
  std::string error;
  ASSERT_TRUE(s.open("127.0.0.1", 0, error)) << error;
}

Endpoint loopback(uint16_t port) { return Endpoint(asio::ip::make_address("127.0.0.1"), port); }

// Everything waiting on `s` (the sends are done: loopback delivers at once).
std::vector<std::vector<uint8_t>> drain(UdpSocket& s) {
  std::vector<std::vector<uint8_t>> got;
  std::vector<uint8_t> buffer(kMaxDatagramBytes + 1);
  Endpoint from;
  for (ptrdiff_t n; (n = s.receive(buffer, from)) >= 0;) got.emplace_back(buffer.begin(), buffer.begin() + n);
  return got;
}

TEST(DatagramBatch, EveryDatagramArrivesWholeInOrderAtItsAddressPastAFullBatch) {
  UdpSocket sender, a, b;
  for (UdpSocket* s : {&sender, &a, &b}) ASSERT_NO_FATAL_FAILURE(open_loopback(*s));
  DatagramBatch batch;
  const size_t count = DatagramBatch::kCapacity * 2 + 5;  // two full batches sent from add()
  size_t bytes = 0;
  for (size_t i = 0; i < count; ++i) {
    std::vector<uint8_t> d(1 + (i * 37) % kMaxDatagramBytes, static_cast<uint8_t>(i));
    bytes += d.size();
    batch.add(sender, d, loopback(i % 2 ? b.local_port() : a.local_port()));
  }
  EXPECT_EQ(batch.take_counts().sent, 2 * DatagramBatch::kCapacity) << "full batches go out as they fill";
  batch.flush(sender);
  const DatagramBatch::Counts last = batch.take_counts();
  EXPECT_EQ(last.sent, 5u);
  EXPECT_EQ(last.failed, 0u);
  const auto at_a = drain(a), at_b = drain(b);
  ASSERT_EQ(at_a.size() + at_b.size(), count);
  size_t received = 0;
  for (size_t i = 0; i < count; ++i) {
    const auto& d = i % 2 ? at_b[i / 2] : at_a[i / 2];
    EXPECT_EQ(d.size(), 1 + (i * 37) % kMaxDatagramBytes) << i;
    EXPECT_EQ(d.front(), static_cast<uint8_t>(i)) << i;
    received += d.size();
  }
  EXPECT_EQ(received, bytes);
}

TEST(DatagramBatch, WhatCannotBeSentIsCountedAndTheRestStillGoes) {
  UdpSocket sender, a;
  for (UdpSocket* s : {&sender, &a}) ASSERT_NO_FATAL_FAILURE(open_loopback(*s));
  DatagramBatch batch;
  const std::vector<uint8_t> ok(10, 1), too_large(kMaxDatagramBytes + 1, 2);
  batch.add(sender, too_large, loopback(a.local_port()));  // refused before it is queued
  batch.add(sender, ok, Endpoint(asio::ip::make_address("0.0.0.0"), 0));  // port 0: the kernel refuses it
  batch.add(sender, ok, loopback(a.local_port()));
  batch.flush(sender);
  const DatagramBatch::Counts c = batch.take_counts();
  EXPECT_EQ(c.failed, 2u);
  EXPECT_EQ(c.sent, 1u);
  EXPECT_EQ(c.bytes, 10u);
  EXPECT_EQ(drain(a).size(), 1u);
  // A closed socket: nothing sent, everything counted.
  UdpSocket closed;
  batch.add(closed, ok, loopback(a.local_port()));
  batch.flush(closed);
  EXPECT_EQ(batch.take_counts().failed, 1u);
}

}  // namespace
}  // namespace foresight::protocol

namespace foresight::protocol {
namespace {

// The receiving side: recvmmsg batches take every waiting datagram whole, in order, with its
// sender, past a full batch; one longer than the limit is reported one byte over it (so the packet
// reader refuses it as too large), exactly as UdpSocket::receive reports it; and every buffer is
// aligned for the FlatBuffers read in place (rows of 1201 bytes were not: UBSan caught it).
TEST(DatagramInbox, TakesEveryDatagramWithItsSenderAndFlagsAnOversizedOne) {
  UdpSocket receiver, a, b;
  for (UdpSocket* s : {&receiver, &a, &b}) {
    std::string error;
    ASSERT_TRUE(s->open("127.0.0.1", 0, error)) << error;
  }
  const Endpoint to(asio::ip::make_address("127.0.0.1"), receiver.local_port());
  const size_t count = DatagramInbox::kCapacity + 10;
  for (size_t i = 0; i < count; ++i) {
    const size_t size = i == 7 ? kMaxDatagramBytes + 300 : 1 + (i * 53) % kMaxDatagramBytes;
    ASSERT_TRUE((i % 2 ? b : a).send(std::vector<uint8_t>(size, static_cast<uint8_t>(i)), to));
  }
  DatagramInbox inbox;
  std::vector<std::pair<std::vector<uint8_t>, uint16_t>> got;
  for (size_t n; (n = inbox.receive(receiver)) > 0;)
    for (size_t i = 0; i < n; ++i) {
      // FlatBuffers read the bytes in place: every buffer must be aligned for them.
      EXPECT_EQ(reinterpret_cast<std::uintptr_t>(inbox.datagram(i).data()) % 8, 0u) << i;
      got.emplace_back(std::vector<uint8_t>(inbox.datagram(i).begin(), inbox.datagram(i).end()), inbox.from(i).port());
    }
  ASSERT_EQ(got.size(), count);
  for (size_t i = 0; i < count; ++i) {
    const size_t expected = i == 7 ? kMaxDatagramBytes + 1 : 1 + (i * 53) % kMaxDatagramBytes;
    EXPECT_EQ(got[i].first.size(), expected) << i;
    EXPECT_EQ(got[i].first.front(), static_cast<uint8_t>(i)) << i;
    EXPECT_EQ(got[i].second, (i % 2 ? b : a).local_port()) << i;
  }
  EXPECT_EQ(inbox.receive(receiver), 0u) << "nothing left, and no wait";
}

}  // namespace
}  // namespace foresight::protocol
