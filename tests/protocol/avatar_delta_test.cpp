// Packed, delta-coded snapshot avatars (protocol/avatar_delta.hpp): what the client decodes is
// exactly what the server coded, whatever it was coded against; bad input is an error, never a
// wrong avatar.
#include "protocol/avatar_delta.hpp"
#include "protocol/sent_views.hpp"

#include "math/splitmix64.hpp"
#include "support/alloc_counter.hpp"
#include "protocol/protocol.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>
#include <vector>

namespace foresight::protocol {
namespace {

using State = wire::AvatarState;

bool same(const State& a, const State& b) {
  return a.id() == b.id() && a.start_x_mm() == b.start_x_mm() && a.start_z_mm() == b.start_z_mm() &&
         a.transition() == b.transition() && a.segment() == b.segment() && a.start_heading() == b.start_heading() &&
         a.frame() == b.frame() && a.flags() == b.flags() && a.reserved() == b.reserved();
}

void expect_same(const std::vector<State>& got, const std::vector<State>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_TRUE(same(got[i], want[i])) << "avatar " << i << " (id " << want[i].id() << ")";
}

// One part of `view` coded against what `sender` sent and had acknowledged (as of snapshot
// `snapshot`, server tick `tick`).
std::vector<uint8_t> encode(const std::vector<State>& view, uint32_t snapshot, uint32_t tick, WholeViewSender& sender,
                            size_t begin = 0, size_t end = SIZE_MAX) {
  AvatarDeltaEncoder encoder;
  sender.plan(encoder, view, snapshot, tick);
  std::vector<uint8_t> bytes;
  encoder.write_part(begin, std::min(end, view.size()), bytes);
  return bytes;
}

// The client's side: it decoded `view` as `snapshot` (whole: usable).
void remember(AvatarHistory& h, uint32_t snapshot, uint32_t tick, const std::vector<State>& view, bool usable = true) {
  AvatarHistory::Slot& slot = h.start(snapshot, tick);
  slot.avatars = view;
  slot.usable = usable;
}

// The server's side: it sent `view` as `snapshot`, and the client acknowledged it.
void remember(WholeViewSender& sender, uint32_t snapshot, uint32_t tick, const std::vector<State>& view,
              bool acknowledged = true) {
  sender.remember(snapshot, tick, view);
  if (acknowledged) sender.acknowledge(snapshot);
}

TEST(BitStream, CodesRoundTripAtTheirLimits) {
  std::vector<uint8_t> bytes;
  BitWriter w(bytes);
  w.put(5, 3);
  w.put_gamma(1);
  w.put_gamma(UINT64_MAX);
  w.put_wide(0);
  w.put_wide(UINT32_MAX);
  w.put_signed_wide(INT32_MIN);
  w.put_signed_wide(INT32_MAX);
  w.put_signed_gamma(-7);
  w.put_signed_gamma(INT32_MIN);
  w.finish();
  EXPECT_EQ(bytes.size(), (w.bits() + 7) / 8);
  BitReader r(bytes);
  EXPECT_EQ(r.get(3), 5u);
  EXPECT_EQ(r.get_gamma(), 1u);
  EXPECT_EQ(r.get_gamma(), UINT64_MAX);
  EXPECT_EQ(r.get_wide(), 0u);
  EXPECT_EQ(r.get_wide(), UINT32_MAX);
  EXPECT_EQ(r.get_signed_wide(), INT32_MIN);
  EXPECT_EQ(r.get_signed_wide(), INT32_MAX);
  EXPECT_EQ(r.get_signed_gamma(), -7);
  EXPECT_EQ(r.get_signed_gamma(), INT32_MIN);
  EXPECT_FALSE(r.failed());
  EXPECT_LT(r.remaining_bits(), 8u);
  // Past the end: zeros and failed, never a read out of bounds.
  BitReader empty({});
  EXPECT_EQ(empty.get_gamma(), 0u);
  EXPECT_TRUE(empty.failed());
}

TEST(AvatarDelta, WholeStatesRoundTripAtEveryFieldsLimits) {
  const std::vector<State> view{State(0, INT32_MIN, INT32_MAX, -1, kNoSegment, 0xFFFF, 255, 0xFF, 0),
                                State(1, 0, 0, INT32_MAX, 0, 0, 0, 0, 0xFFFF),
                                State(17, -1, 1, 423, 73, 12345, 29, kAvatarYours | kAvatarFar, 0),
                                State(UINT32_MAX, 5, -5, INT32_MIN, 1, 1, 1, 1, 1)};
  WholeViewSender none;
  const AvatarHistory empty;
  std::vector<State> out;
  ASSERT_EQ(decode_avatars(encode(view, 9, 9, none), 4, 9, empty, out), AvatarDecodeStatus::kOk);
  expect_same(out, view);
}

TEST(AvatarDelta, AnAvatarStillPlayingItsSegmentCostsAboutOneByte) {
  // 100 walkers; the client acknowledged snapshot 10 (server tick 15); now snapshot 11, tick 17.
  std::vector<State> before, now;
  for (uint32_t id = 1; id <= 100; ++id) {
    before.emplace_back(id, 1000 * int32_t(id), -2000, int32_t(id % 7), uint16_t(id % 50), uint16_t(id * 300), 3, 0, 0);
    now.emplace_back(id, 1000 * int32_t(id), -2000, int32_t(id % 7), uint16_t(id % 50), uint16_t(id * 300), 5, 0, 0);
  }
  WholeViewSender server;
  AvatarHistory client;
  remember(server, 10, 15, before);
  remember(client, 10, 0, before);  // the client does not know server ticks: they travel in the part
  const std::vector<uint8_t> bytes = encode(now, 11, 17, server);
  // id gap 1 bit + reference 1 + same play-through 1 + frame as predicted 1 + flags 1 + reserved 1.
  EXPECT_LE(bytes.size(), 100u * 6 / 8 + 4) << "plain AvatarStates take " << 100 * sizeof(State);
  std::vector<State> out;
  ASSERT_EQ(decode_avatars(bytes, 100, 11, client, out), AvatarDecodeStatus::kOk);
  expect_same(out, now);
}

TEST(AvatarDelta, ChangedFieldsAndNewcomersAreCodedAgainstTheRightReference) {
  WholeViewSender history;
  // Snapshot 20 (tick 30) held avatars 1-4; snapshot 24 (tick 36) held 1 and 5 (4 was far away);
  // snapshot 25 was sent but not acknowledged: never a reference.
  remember(history, 20, 30, {State(1, 0, 0, 3, 7, 100, 2, 0, 0), State(2, 500, 500, 4, 8, 200, 9, 0, 0),
                             State(3, -500, 100, 5, 9, 300, 1, 0, 0), State(4, 9000, 9000, 6, 10, 400, 4, kAvatarFar, 0)});
  remember(history, 24, 36, {State(1, 0, 0, 3, 7, 100, 8, 0, 0), State(5, 40, 40, -1, 11, 0, 0, 0, 0)});
  remember(history, 25, 37, {State(6, 1, 1, 1, 1, 1, 1, 0, 0)}, /*usable=*/false);
  const std::vector<State> now{
      State(1, 0, 0, 3, 7, 100, 9, 0, 0),                       // as predicted from 24 (frame 8 + 1 tick)
      State(2, 500, 500, 4, 8, 200, 9, 0, 0),                   // held still: frame residual -7
      State(3, 120, 790, 12, 13, 65000, 0, kAvatarFallback, 0),  // a new segment, flags changed
      State(4, 9100, 8900, 6, 10, 400, 14, 0, 0),               // new start, far flag cleared
      State(6, 2, 2, 2, 2, 2, 2, 0, 0),                         // only in the unacknowledged 25: whole
      State(7, -3, -3, -1, 0, 9, 0, 0, 0)};                     // new: whole
  const std::vector<uint8_t> bytes = encode(now, 26, 37, history);
  AvatarHistory client;  // what the client holds: 20 and 24 whole, not 25
  remember(client, 20, 0, {State(1, 0, 0, 3, 7, 100, 2, 0, 0), State(2, 500, 500, 4, 8, 200, 9, 0, 0),
                           State(3, -500, 100, 5, 9, 300, 1, 0, 0), State(4, 9000, 9000, 6, 10, 400, 4, kAvatarFar, 0)});
  remember(client, 24, 0, {State(1, 0, 0, 3, 7, 100, 8, 0, 0), State(5, 40, 40, -1, 11, 0, 0, 0, 0)});
  std::vector<State> out;
  ASSERT_EQ(decode_avatars(bytes, static_cast<uint32_t>(now.size()), 26, client, out), AvatarDecodeStatus::kOk);
  expect_same(out, now);
}

TEST(AvatarDelta, AcknowledgementsOutOfOrderStillReferToTheNewest) {
  SnapshotArchive archive;
  SentViews views;
  const std::vector<uint32_t> both{0, 1}, first{0};
  archive.start(3, 3).avatars = {State(1, 0, 0, 1, 1, 1, 1, 0, 0), State(2, 0, 0, 1, 1, 1, 1, 0, 0)};
  views.record(3, *archive.find(3), both, {});
  archive.start(4, 4).avatars = {State(1, 0, 0, 1, 1, 1, 2, 0, 0), State(2, 0, 0, 1, 1, 1, 2, 0, 0)};
  views.record(4, *archive.find(4), first, {});  // avatar 2 was not in this receiver's view of 4
  views.acknowledge(archive, 4);
  views.acknowledge(archive, 3);  // late
  views.acknowledge(archive, 3);  // and repeated
  const std::vector<State> now{State(1, 0, 0, 1, 1, 1, 3, 0, 0), State(2, 0, 0, 1, 1, 1, 3, 0, 0)};
  std::vector<AvatarReference> refs;
  views.references(archive, now, 5, refs);
  ASSERT_EQ(refs.size(), 2u);
  ASSERT_TRUE(refs[0].found && refs[1].found);
  EXPECT_EQ(refs[0].snapshot, 4u) << "avatar 1: snapshot 4 is newer";
  EXPECT_EQ(refs[0].state.frame(), 2u);
  EXPECT_EQ(refs[1].snapshot, 3u) << "avatar 2 is only in this receiver's 3";
  // 64 snapshots after 4, neither is in reach any more (references go 63 back): whole states again.
  views.references(archive, now, 4 + AvatarHistory::kSlots, refs);
  EXPECT_FALSE(refs[0].found || refs[1].found);
}

// A receiver numbers the snapshots it gets one by one, though the server serves it only some of
// the snapshots it gathers: its acknowledgements and references are in its own numbers, the
// states come from the archived snapshot each was cut from.
TEST(AvatarDelta, AReceiverServedEveryFewSnapshotsCountsInItsOwnNumbers) {
  SnapshotArchive archive;
  SentViews views;
  const std::vector<uint32_t> only{0};
  // Archived 10..15; the receiver gets 10, 12, 13 and 15 as its 1, 2, 3 and 4.
  const uint32_t served[] = {10, 12, 13, 15};
  for (uint32_t a = 10; a <= 15; ++a) archive.start(a, 100 + a).avatars = {State(1, 0, 0, 1, 1, 1, static_cast<uint8_t>(a), 0, 0)};
  for (uint32_t k = 0; k < 4; ++k) views.record(k + 1, *archive.find(served[k]), only, {});
  views.acknowledge(archive, 2);  // its 2: archived 12
  std::vector<AvatarReference> refs;
  views.references(archive, archive.find(15)->avatars, 5, refs);
  ASSERT_TRUE(refs[0].found);
  EXPECT_EQ(refs[0].snapshot, 2u) << "in the receiver's numbers (3 back from its 5)";
  EXPECT_EQ(refs[0].server_tick, 112u) << "the archived snapshot's tick";
  EXPECT_EQ(refs[0].state.frame(), 12u) << "the archived snapshot's state";
  views.acknowledge(archive, 12);  // not one of its numbers: nothing happens
  views.references(archive, archive.find(15)->avatars, 5, refs);
  EXPECT_EQ(refs[0].snapshot, 2u);
}

// The archive holds a receiver's last 64 snapshots however often it is served: 96 gathered when
// it gets 20 of 30 ticks, 64 when it gets every one, 192 when it gets 10.
TEST(AvatarDelta, TheArchiveSpansAReceiversReachAtItsRate) {
  EXPECT_EQ(SnapshotArchive::slots_for(30, 20), 96u);
  EXPECT_EQ(SnapshotArchive::slots_for(30, 30), 64u);
  EXPECT_EQ(SnapshotArchive::slots_for(30, 10), 192u);
  EXPECT_EQ(SnapshotArchive::slots_for(60, 20), 192u);
  // Served every other gathered snapshot and acknowledging its 63rd-last: still archived.
  SnapshotArchive archive(SnapshotArchive::slots_for(30, 15));
  SentViews views;
  const std::vector<uint32_t> only{0};
  for (uint32_t a = 1; a <= 130; ++a) {
    archive.start(a, a).avatars = {State(1, 0, 0, 1, 1, 1, static_cast<uint8_t>(a), 0, 0)};
    if (a % 2 == 0) views.record(a / 2, *archive.find(a), only, {});
  }
  views.acknowledge(archive, 2);  // its 2nd: gathered as 4, 126 gathered ago
  std::vector<AvatarReference> refs;
  views.references(archive, archive.find(130)->avatars, 65, refs);
  ASSERT_TRUE(refs[0].found) << "63 of its snapshots back";
  EXPECT_EQ(refs[0].state.frame(), 4u);
}

// Acknowledgements queued as inputs arrive and merged when the client is next served give the
// references that acknowledging each at once gives; repeats are dropped, and a full queue merges
// its oldest rather than losing it.
TEST(AvatarDelta, QueuedAcknowledgementsMergeAsAcknowledgingEachAtOnce) {
  SnapshotArchive archive;
  SentViews at_once, queued;
  for (uint32_t a = 1; a <= 8; ++a) {
    // Avatar a only in snapshot a, avatar 10 in every one.
    archive.start(a, a).avatars = {State(a, 0, 0, 1, 1, 1, static_cast<uint8_t>(a), 0, 0),
                                   State(10, 0, 0, 1, 1, 1, static_cast<uint8_t>(a), 0, 0)};
    const std::vector<uint32_t> both{0, 1};
    at_once.record(a, *archive.find(a), both, {});
    queued.record(a, *archive.find(a), both, {});
  }
  // Six distinct acknowledgements (one repeated, two out of order) through a queue of four.
  for (const uint32_t ack : {2u, 2u, 1u, 4u, 3u, 6u, 5u}) {
    at_once.acknowledge(archive, ack);
    queued.queue_acknowledgement(archive, ack);
  }
  queued.acknowledge_queued(archive);
  std::vector<State> view;
  for (uint32_t id = 1; id <= 8; ++id) view.emplace_back(id, 0, 0, 1, 1, 1, 0, 0, 0);
  view.emplace_back(10, 0, 0, 1, 1, 1, 0, 0, 0);
  std::vector<AvatarReference> want, got;
  at_once.references(archive, view, 9, want);
  queued.references(archive, view, 9, got);
  ASSERT_EQ(got.size(), want.size());
  int found = 0;
  for (size_t i = 0; i < view.size(); ++i) {
    EXPECT_EQ(got[i].found, want[i].found) << "avatar " << view[i].id();
    EXPECT_EQ(got[i].snapshot, want[i].snapshot) << "avatar " << view[i].id();
    found += got[i].found;
  }
  EXPECT_EQ(found, 7) << "avatars 1-6 and 10 (from 6): 7 and 8 were never acknowledged";
  EXPECT_EQ(got[8].snapshot, 6u);
}

// The receiver's own avatar comes back flagged kAvatarYours, the far ones kAvatarFar, as they were
// sent, though the archive holds each avatar once without them.
TEST(AvatarDelta, ReferencesCarryTheFlagsTheReceiverWasSent) {
  SnapshotArchive archive;
  SentViews views;
  views.set_owner(2);
  archive.start(7, 7).avatars = {State(1, 0, 0, 1, 1, 1, 1, kAvatarNpc, 0), State(2, 0, 0, 1, 1, 1, 1, 0, 0),
                                 State(3, 0, 0, 1, 1, 1, 1, 0, 0)};
  const std::vector<uint32_t> indices{0, 1, 2};
  const std::vector<uint8_t> far{1, 0, 0};
  views.record(7, *archive.find(7), indices, far);
  views.acknowledge(archive, 7);
  std::vector<AvatarReference> refs;
  views.references(archive, archive.find(7)->avatars, 8, refs);
  ASSERT_TRUE(refs[0].found && refs[1].found && refs[2].found);
  EXPECT_EQ(refs[0].state.flags(), kAvatarNpc | kAvatarFar);
  EXPECT_EQ(refs[1].state.flags(), kAvatarYours);
  EXPECT_EQ(refs[2].state.flags(), 0);
}

// A receiver holds view bits only for the snapshots in flight (issue 20 item 5): with 1000
// avatars archived, a client acknowledging each snapshot two later holds a few 250-byte bit sets,
// not 64; one whose acknowledgements stopped holds all 64 (and loses nothing: references still
// come from what it acknowledged before).
TEST(AvatarDelta, AReceiverHoldsViewBitsOnlyForSnapshotsInFlight) {
  constexpr size_t kArchived = 1000, kBitSetBytes = (2 * kArchived + 63) / 64 * 8;
  SnapshotArchive archive;
  SentViews acking, silent;
  std::vector<uint32_t> indices;
  std::vector<uint8_t> far;
  for (uint32_t i = 0; i < kArchived; i += 10) indices.push_back(i), far.push_back(i % 20 == 0);
  for (uint32_t snapshot = 1; snapshot <= 100; ++snapshot) {
    auto& avatars = archive.start(snapshot, snapshot).avatars;
    for (uint32_t id = 1; id <= kArchived; ++id) avatars.emplace_back(id, 0, 0, 1, 1, 1, 1, 0, 0);
    acking.record(snapshot, *archive.find(snapshot), indices, far);
    silent.record(snapshot, *archive.find(snapshot), indices, far);
    if (snapshot > 2) acking.acknowledge(archive, snapshot - 2);
    if (snapshot == 3) silent.acknowledge(archive, 1);
    if (snapshot == 50) {
      std::vector<AvatarReference> refs;
      silent.references(archive, archive.find(50)->avatars, 50, refs);
      EXPECT_TRUE(refs[0].found && refs[0].snapshot == 1) << "49 back, still in reach";
    }
  }
  EXPECT_LT(acking.bytes(), 6 * kBitSetBytes + 100 * sizeof(uint32_t) * 3 + sizeof(SentViews));
  EXPECT_GE(silent.bytes(), 63 * kBitSetBytes);
  std::vector<AvatarReference> refs;
  acking.references(archive, archive.find(100)->avatars, 100, refs);
  EXPECT_TRUE(refs[0].found && refs[0].snapshot == 98 && (refs[0].state.flags() & kAvatarFar));
  EXPECT_TRUE(refs[10].found && !(refs[10].state.flags() & kAvatarFar));
  EXPECT_FALSE(refs[1].found) << "never in the view";
}

// A client acknowledges only the newest snapshot it holds, so some are never acknowledged: their
// bits go once they are 8 behind the newest acknowledged, not 64 snapshots later; and after a
// stall of acknowledgements (64 sets in flight) at most 8 sets stay as spares.
TEST(AvatarDelta, SnapshotsNeverAcknowledgedAndAStallLeaveNoBitsBehind) {
  constexpr size_t kArchived = 1000, kBitSetBytes = (2 * kArchived + 63) / 64 * 8;
  SnapshotArchive archive;
  SentViews skipping, stalled;
  const std::vector<uint32_t> indices{0, 10, 20};
  for (uint32_t snapshot = 1; snapshot <= 200; ++snapshot) {
    auto& avatars = archive.start(snapshot, snapshot).avatars;
    for (uint32_t id = 1; id <= kArchived; ++id) avatars.emplace_back(id, 0, 0, 1, 1, 1, 1, 0, 0);
    skipping.record(snapshot, *archive.find(snapshot), indices, {});
    stalled.record(snapshot, *archive.find(snapshot), indices, {});
    if (snapshot > 2 && snapshot % 2 == 0) skipping.acknowledge(archive, snapshot - 2);  // every other one
    if (snapshot > 2 && (snapshot < 100 || snapshot > 170)) stalled.acknowledge(archive, snapshot - 2);
  }
  // In flight: the last 2; never acknowledged but kept: up to 8 behind the newest acknowledged.
  EXPECT_LT(skipping.bytes(), 20 * kBitSetBytes + 4096 + sizeof(SentViews));
  EXPECT_LT(stalled.bytes(), 20 * kBitSetBytes + 4096 + sizeof(SentViews)) << "the stall's 64 sets given back";
  std::vector<AvatarReference> refs;
  skipping.references(archive, archive.find(200)->avatars, 200, refs);
  EXPECT_TRUE(refs[0].found && refs[0].snapshot == 198) << "references still come from the acknowledged ones";
}

// Delta coding survives a round trip of 2 s (40 snapshots at 20 Hz, issue 19): the newest
// acknowledgement that came back is 50 snapshots old and still a reference.
TEST(AvatarDelta, AReferenceFiftySnapshotsBackStillCodesDelta) {
  std::vector<State> before, now;
  for (uint32_t id = 1; id <= 50; ++id) {
    before.emplace_back(id, 100 * int32_t(id), 0, 2, 3, 4, 0, 0, 0);
    now.emplace_back(id, 100 * int32_t(id), 0, 2, 3, 4, 75, 0, 0);
  }
  WholeViewSender server;
  AvatarHistory client;
  remember(server, 10, 10, before);
  remember(client, 10, 0, before);
  for (uint32_t s = 11; s < 60; ++s) remember(server, s, s + s / 2, now, /*acknowledged=*/false);  // still on their way
  AvatarDeltaEncoder encoder;
  server.plan(encoder, now, 60, 85);
  EXPECT_EQ(encoder.referenced(), now.size());
  std::vector<uint8_t> bytes;
  encoder.write_part(0, now.size(), bytes);
  EXPECT_LE(bytes.size(), 50u * 6 / 8 + 6);  // about 6 bits an avatar, as one snapshot back
  std::vector<State> out;
  ASSERT_EQ(decode_avatars(bytes, 50, 60, client, out), AvatarDecodeStatus::kOk);
  expect_same(out, now);
}

TEST(AvatarDelta, PartsOfOneViewDecodeOnTheirOwn) {
  WholeViewSender server;
  AvatarHistory client;
  std::vector<State> before, now;
  for (uint32_t id = 3; id < 300; id += 3) {
    before.emplace_back(id, int32_t(id) * 10, 0, 1, 2, 3, 4, 0, 0);
    now.emplace_back(id, int32_t(id) * 10 + (id % 2 ? 700 : 0), 0, 1, 2, 3, 6, 0, 0);
  }
  remember(server, 40, 60, before);
  remember(client, 40, 0, before);
  // Decoded in reverse order, as datagrams may arrive.
  std::vector<State> out;
  for (size_t begin : {66u, 33u, 0u}) {
    std::vector<State> part;
    ASSERT_EQ(decode_avatars(encode(now, 41, 62, server, begin, begin + 33), 33, 41, client, part),
              AvatarDecodeStatus::kOk);
    out.insert(out.begin(), part.begin(), part.end());
  }
  expect_same(out, now);
}

TEST(AvatarDelta, AReferenceTheClientDoesNotHoldIsAnErrorNotAWrongAvatar) {
  WholeViewSender server;
  remember(server, 5, 5, {State(1, 10, 10, 1, 1, 1, 1, 0, 0)});
  const std::vector<State> now{State(1, 10, 10, 1, 1, 1, 2, 0, 0)};
  const std::vector<uint8_t> bytes = encode(now, 6, 6, server);
  std::vector<State> out{State(99, 0, 0, 0, 0, 0, 0, 0, 0)};
  EXPECT_EQ(decode_avatars(bytes, 1, 6, AvatarHistory{}, out), AvatarDecodeStatus::kMissingBaseline);
  AvatarHistory other;  // holds snapshot 5, but without avatar 1
  remember(other, 5, 0, {State(2, 0, 0, 0, 0, 0, 0, 0, 0)});
  EXPECT_EQ(decode_avatars(bytes, 1, 6, other, out), AvatarDecodeStatus::kMissingBaseline);
  AvatarHistory unusable;  // holds it, but not whole
  remember(unusable, 5, 0, {State(1, 10, 10, 1, 1, 1, 1, 0, 0)}, false);
  EXPECT_EQ(decode_avatars(bytes, 1, 6, unusable, out), AvatarDecodeStatus::kMissingBaseline);
  ASSERT_EQ(out.size(), 1u) << "nothing appended on an error";
  EXPECT_EQ(out[0].id(), 99u);
}

TEST(AvatarDelta, CutOffPaddedOrMiscountedPartsAreMalformed) {
  std::vector<State> view;
  for (uint32_t id = 1; id <= 20; ++id) view.emplace_back(id, int32_t(id) * 77, -int32_t(id), 3, 4, 5, 6, 0, 0);
  WholeViewSender none;
  const AvatarHistory empty;
  const std::vector<uint8_t> bytes = encode(view, 1, 1, none);
  std::vector<State> out;
  for (size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_EQ(decode_avatars({bytes.data(), n}, 20, 1, empty, out), AvatarDecodeStatus::kMalformed) << n << " bytes";
    EXPECT_TRUE(out.empty());
  }
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  EXPECT_EQ(decode_avatars(longer, 20, 1, empty, out), AvatarDecodeStatus::kMalformed);
  EXPECT_EQ(decode_avatars(bytes, 21, 1, empty, out), AvatarDecodeStatus::kMalformed);
  EXPECT_EQ(decode_avatars(bytes, 19, 1, empty, out), AvatarDecodeStatus::kMalformed);
  EXPECT_TRUE(out.empty());
}

TEST(AvatarDelta, AnIdGapBeyondAnyIdIsMalformed) {
  // Found by fuzz-packet: a 64-bit gap overflowed the id arithmetic (UBSan).
  const AvatarHistory empty;
  for (const uint64_t gap : {UINT64_MAX, uint64_t{UINT32_MAX} + 2, uint64_t{1} << 40}) {
    std::vector<uint8_t> bytes;
    BitWriter w(bytes);
    w.put(0, 5), w.put(0, 6), w.put(0, 3);  // widths, no references
    w.put_gamma(gap);
    w.finish();
    std::vector<State> out;
    EXPECT_EQ(decode_avatars(bytes, 1, 1, empty, out), AvatarDecodeStatus::kMalformed) << gap;
  }
  // The largest gap the encoder writes (from -1 to the largest id) is fine.
  std::vector<State> out;
  std::vector<uint8_t> bytes;
  pack_avatars(std::vector<State>{State(UINT32_MAX, 0, 0, -1, 0, 0, 0, 0, 0)}, bytes);
  ASSERT_EQ(decode_avatars(bytes, 1, 0, empty, out), AvatarDecodeStatus::kOk);
  EXPECT_EQ(out[0].id(), UINT32_MAX);
}

TEST(AvatarDelta, HugeDifferencesWrapInsteadOfOverflowing) {
  // Found by fuzz-packet: a heading difference near INT32_MAX overflowed an int (UBSan).
  AvatarHistory history;
  remember(history, 1, 1, {State(1, INT32_MAX, INT32_MIN, 0, 0, 100, 0, 0, 0)});
  std::vector<uint8_t> bytes;
  BitWriter w(bytes);
  w.put(0, 5), w.put(0, 6);           // widths of segments and transitions
  w.put(1, 3), w.put(1, 6);           // one reference: one snapshot back,
  w.put_gamma(1);                     // 0 ticks since
  w.put_gamma(2);                     // avatar 1
  w.put_bit(true), w.put_bit(false);  // with the reference; a new play-through
  w.put_signed_wide(INT32_MAX), w.put_signed_wide(INT32_MIN), w.put_signed_wide(INT32_MAX);  // x, z, heading
  w.put_gamma(1), w.put_bit(true), w.put_bit(true);                                            // frame 0, flags, reserved
  w.finish();
  std::vector<State> out;
  ASSERT_EQ(decode_avatars(bytes, 1, 2, history, out), AvatarDecodeStatus::kOk);
  EXPECT_EQ(out[0].start_x_mm(), static_cast<int32_t>(uint32_t{INT32_MAX} + uint32_t{INT32_MAX}));
  EXPECT_EQ(out[0].start_heading(), static_cast<uint16_t>(100u + uint32_t{INT32_MAX}));
}

TEST(AvatarDelta, RandomBytesNeverDecodeOutOfBounds) {
  SplitMix64 rng(7);
  AvatarHistory history;
  remember(history, 99, 99, {State(1, 0, 0, 0, 0, 0, 0, 0, 0), State(2, 0, 0, 0, 0, 0, 0, 0, 0)});
  int ok = 0;
  std::vector<State> out;
  for (int trial = 0; trial < 20000; ++trial) {
    std::vector<uint8_t> bytes(rng.next() % 24);
    for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng.next());
    out.clear();
    const uint32_t count = static_cast<uint32_t>(rng.next() % 4);
    const AvatarDecodeStatus status = decode_avatars(bytes, count, 100, history, out);
    if (status == AvatarDecodeStatus::kOk) {
      ++ok;
      EXPECT_EQ(out.size(), count);
      for (size_t i = 1; i < out.size(); ++i) EXPECT_LT(out[i - 1].id(), out[i].id());
    } else {
      EXPECT_TRUE(out.empty());
    }
  }
  EXPECT_GT(ok, 0) << "some random parts are valid codes";
}

// The server's side per client and snapshot (plan, code, remember, acknowledge): once its vectors
// have grown to the view's size, nothing is allocated.
TEST(AvatarDelta, AWarmSenderAllocatesNothingPerSnapshot) {
  WholeViewSender history;
  AvatarDeltaEncoder encoder;
  std::vector<uint8_t> bytes;
  bytes.reserve(2048);
  std::vector<State> view;
  for (uint32_t id = 1; id <= 120; ++id) view.emplace_back(id, int32_t(id) * 100, 0, 3, 4, 5, 0, 0, 0);
  int allocations = 0;
  for (uint32_t snapshot = 1; snapshot <= 100; ++snapshot) {
    for (size_t i = 0; i < view.size(); ++i) {
      const State& a = view[i];
      view[i] = (snapshot + i) % 9 == 0 ? State(a.id(), a.start_x_mm() + 600, 0, 3, 4, 5, 0, 0, 0)
                                        : State(a.id(), a.start_x_mm(), 0, 3, 4, 5, static_cast<uint8_t>(a.frame() + 1), 0, 0);
    }
    test::AllocationCount counting(snapshot > 70);  // the archive's 64 slots and the lists have grown by then
    history.plan(encoder, view, snapshot, snapshot);
    encoder.write_part(0, view.size(), bytes);
    history.remember(snapshot, snapshot, view);
    history.acknowledge(snapshot);
    allocations += counting.allocations();
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_LT(bytes.size(), 120u * 3) << "and the view is coded against what was acknowledged";
}

// The whole scheme over a lossy link: the server codes each snapshot against what the client
// acknowledged, the client decodes what arrives, acknowledges what it holds whole (and some of
// its acknowledgements are lost too); every snapshot the client decodes is exactly the server's.
TEST(AvatarDelta, ALossyLinkNeverDesynchronises) {
  SplitMix64 rng(2026);
  WholeViewSender server;
  AvatarHistory client;
  std::vector<State> world;
  for (uint32_t id = 1; id <= 60; ++id) world.emplace_back(id, 0, 0, -1, 0, 0, 0, 0, 0);
  uint32_t next_id = 61, tick = 0;
  int decoded = 0, referenced = 0;
  for (uint32_t snapshot = 1; snapshot <= 2000; ++snapshot) {
    tick += 1 + static_cast<uint32_t>(rng.next() % 2);
    // The world moves on: frames advance, a few segments change, avatars leave and join.
    for (State& a : world) {
      const uint64_t r = rng.next() % 100;
      if (r < 10) {
        a = State(a.id(), a.start_x_mm() + int32_t(rng.next() % 2000) - 1000, a.start_z_mm() + int32_t(rng.next() % 2000) - 1000,
                  int32_t(rng.next() % 424) - 1, uint16_t(rng.next() % 74), uint16_t(rng.next()), 0,
                  uint8_t(rng.next() % 4 == 0 ? kAvatarFar : 0), 0);
      } else if (r < 95) {
        a.mutate_frame(static_cast<uint8_t>(a.frame() + (tick % 2 ? 1 : 2)));
      }
    }
    if (rng.next() % 10 == 0) world.erase(world.begin() + static_cast<std::ptrdiff_t>(rng.next() % world.size()));
    if (rng.next() % 10 == 0) world.emplace_back(next_id++, 5, 5, -1, 0, 0, 0, 0, 0);
    // The view: a random subset (interest), in id order.
    std::vector<State> view;
    for (const State& a : world)
      if (rng.next() % 5 != 0) view.push_back(a);
    AvatarDeltaEncoder encoder;
    server.plan(encoder, view, snapshot, tick);
    referenced += static_cast<int>(encoder.referenced());
    std::vector<uint8_t> bytes;
    encoder.write_part(0, view.size(), bytes);
    remember(server, snapshot, tick, view, false);
    if (rng.next() % 100 < 20) continue;  // the snapshot is lost
    std::vector<State> out;
    ASSERT_EQ(decode_avatars(bytes, static_cast<uint32_t>(view.size()), snapshot, client, out), AvatarDecodeStatus::kOk)
        << "snapshot " << snapshot;
    expect_same(out, view);
    ++decoded;
    remember(client, snapshot, 0, out);
    if (rng.next() % 100 < 20) continue;  // the acknowledgement is lost
    server.acknowledge(snapshot);
  }
  EXPECT_GT(decoded, 1400);
  EXPECT_GT(referenced, 50 * decoded) << "most avatars are coded against a reference";
}

}  // namespace
}  // namespace foresight::protocol
