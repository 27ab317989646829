// Sealed sessions (transport/session_crypto.hpp): what one side seals the other opens, and nothing
// else: a flipped bit, another key, another session, a replay, a sequence too old for the window,
// a Sealed inside a Sealed are all refused, with the reason counted by the receiver.
#include "transport/session_crypto.hpp"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

namespace foresight::protocol {
namespace {

struct Pair {
  SessionKeyPair client = session_keypair(), server = session_keypair();
  SessionKeys client_keys, server_keys;
  Pair() {
    EXPECT_TRUE(session_keys_client(client, server.public_key, client_keys));
    EXPECT_TRUE(session_keys_server(server, client.public_key, server_keys));
  }
};

const wire::Sealed* as_sealed(const std::vector<uint8_t>& d) {
  DropReason reason;
  const wire::Packet* p = packet_read(d, reason);
  return p ? p->message_as_Sealed() : nullptr;
}

std::vector<uint8_t> copy(std::span<const uint8_t> s) { return {s.begin(), s.end()}; }

TEST(SessionCrypto, WhatOneSideSealsTheOtherOpensOnce) {
  Pair k;
  EXPECT_EQ(k.client_keys.send, k.server_keys.receive);
  EXPECT_EQ(k.client_keys.receive, k.server_keys.send);
  EXPECT_NE(k.client_keys.send, k.client_keys.receive);
  Sealer sealer;
  sealer.set(42, k.client_keys.send);
  Opener opener;
  opener.set(42, k.server_keys.receive);
  PacketWriter inner_writer, seal_writer;
  const auto inner = copy(write_heartbeat(inner_writer, 42, 1234));
  const auto sealed = copy(sealer.seal(seal_writer, inner));
  EXPECT_LE(sealed.size(), inner.size() + kSealOverheadBytes);
  EXPECT_EQ(std::search(sealed.begin(), sealed.end(), inner.begin() + 8, inner.end()), sealed.end())
      << "the message is not readable in the datagram";
  DropReason reason = DropReason::kNone;
  const wire::Packet* got = opener.open(*as_sealed(sealed), reason);
  ASSERT_NE(got, nullptr);
  ASSERT_NE(got->message_as_Heartbeat(), nullptr);
  EXPECT_EQ(got->message_as_Heartbeat()->client_time_ms(), 1234u);
  EXPECT_EQ(copy(opener.plain()), inner);
  // The same datagram again: a replay.
  EXPECT_EQ(opener.open(*as_sealed(sealed), reason), nullptr);
  EXPECT_EQ(reason, DropReason::kReplayed);
}

// The seal and open buffers are the thread's, not the session's (a server holds a Sealer and an
// Opener per session): sessions sealed and opened on two threads at once each get their own
// messages back, every time.
TEST(SessionCrypto, SessionsOnTwoThreadsSealAndOpenTheirOwnMessages) {
  EXPECT_LT(sizeof(Sealer) + sizeof(Opener), 256u) << "no datagram-sized buffer per session";
  Pair k;
  int wrong[2] = {0, 0};
  const auto run = [&](int t) {
    const uint32_t session = 10 + static_cast<uint32_t>(t);
    Sealer sealer;
    sealer.set(session, k.client_keys.send);
    Opener opener;
    opener.set(session, k.server_keys.receive);
    PacketWriter inner_writer, seal_writer;
    for (uint32_t i = 1; i <= 2000; ++i) {
      const auto inner = copy(write_heartbeat(inner_writer, session, i * 2 + static_cast<uint32_t>(t)));
      const auto sealed = copy(sealer.seal(seal_writer, inner));
      DropReason reason = DropReason::kNone;
      const wire::Packet* got = opener.open(*as_sealed(sealed), reason);
      if (got == nullptr || got->message_as_Heartbeat() == nullptr ||
          got->message_as_Heartbeat()->client_time_ms() != i * 2 + static_cast<uint32_t>(t) || copy(opener.plain()) != inner)
        ++wrong[t];
    }
  };
  std::thread a(run, 0), b(run, 1);
  a.join();
  b.join();
  EXPECT_EQ(wrong[0], 0);
  EXPECT_EQ(wrong[1], 0);
}

TEST(SessionCrypto, ForgedTamperedAndMisdirectedMessagesAreRefused) {
  Pair k, other;
  PacketWriter inner_writer, seal_writer;
  const auto inner = copy(write_heartbeat(inner_writer, 42, 1));
  Opener opener;
  opener.set(42, k.server_keys.receive);
  DropReason reason = DropReason::kNone;
  // Another key (someone who made up a session key), another session, one flipped bit.
  Sealer wrong_key, wrong_session, right;
  wrong_key.set(42, other.client_keys.send);
  wrong_session.set(43, k.client_keys.send);
  right.set(42, k.client_keys.send);
  EXPECT_EQ(opener.open(*as_sealed(copy(wrong_key.seal(seal_writer, inner))), reason), nullptr);
  EXPECT_EQ(reason, DropReason::kUnauthenticated);
  EXPECT_EQ(opener.open(*as_sealed(copy(wrong_session.seal(seal_writer, inner))), reason), nullptr);
  EXPECT_EQ(reason, DropReason::kUnauthenticated);
  auto tampered = copy(right.seal(seal_writer, inner));
  tampered[tampered.size() - 20] ^= 0x01;  // inside the ciphertext
  const wire::Sealed* s = as_sealed(tampered);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(opener.open(*s, reason), nullptr);
  EXPECT_EQ(reason, DropReason::kUnauthenticated);
  // A refused datagram does not burn its sequence: the genuine one still opens.
  Sealer again;
  again.set(42, k.client_keys.send);
  EXPECT_NE(opener.open(*as_sealed(copy(again.seal(seal_writer, inner))), reason), nullptr);
  // A Sealed inside a Sealed is not opened twice.
  const auto nested = copy(right.seal(seal_writer, copy(again.seal(inner_writer, inner))));
  EXPECT_EQ(opener.open(*as_sealed(nested), reason), nullptr);
  // Too large to be a datagram: not sealed at all.
  std::vector<uint8_t> huge(kMaxDatagramBytes + 1, 0);
  EXPECT_TRUE(right.seal(seal_writer, huge).empty());
}

TEST(SessionCrypto, TheReplayWindowTakesReorderedButNotOldOrRepeated) {
  ReplayWindow w;
  EXPECT_FALSE(w.fresh(0));
  for (uint64_t s : {5u, 3u, 4u, 1u, 2u, 70u}) {
    EXPECT_TRUE(w.fresh(s)) << s;
    w.mark(s);
    EXPECT_FALSE(w.fresh(s)) << s;
  }
  EXPECT_FALSE(w.fresh(6)) << "64 behind the newest (70) is too old to tell";
  EXPECT_TRUE(w.fresh(7)) << "63 behind, never seen";
  EXPECT_TRUE(w.fresh(69));
  w.mark(200);
  EXPECT_FALSE(w.fresh(70));
  EXPECT_TRUE(w.fresh(199));
}

}  // namespace
}  // namespace foresight::protocol
