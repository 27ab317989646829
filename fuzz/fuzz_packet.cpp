// libFuzzer: any datagram through the packet decoder (protocol/packet.hpp: size checks, file
// identifier, FlatBuffers verifier with our depth and table limits), then every field of the
// message read the way its receiver reads it. A verified packet must never read out of bounds.
#include "fuzz_history.hpp"
#include "protocol/input_packet.hpp"
#include "protocol/packet.hpp"
#include "protocol/quantize.hpp"

#include <cstddef>
#include <cstdint>

using namespace foresight;
using namespace foresight::protocol;

namespace {

volatile uint64_t g_sink = 0;  // keeps the reads from being optimised away

template <class T>
void take(T v) {
  g_sink = g_sink + static_cast<uint64_t>(v);
}
void take(const flatbuffers::String* s) {
  if (s) take(s->size() + (s->size() ? static_cast<uint8_t>(s->c_str()[s->size() - 1]) : 0));
}
void take(const flatbuffers::Vector<uint8_t>* v) {
  if (v)
    for (uint8_t b : *v) take(b);
}

void walk(const wire::Snapshot& m) {
  take(m.tick()), take(m.part()), take(m.parts()), take(m.ack_input()), take(m.server_time_ms());
  // Packed avatars against a history holding one earlier snapshot (references to it resolve,
  // others are missing baselines).
  static const protocol::AvatarHistory history = fuzz::fuzz_history();
  static std::vector<wire::AvatarState> avatars;
  avatars.clear();
  take(static_cast<int>(protocol::snapshot_avatars(m, history, avatars)));
  for (const wire::AvatarState& a : avatars)
    take(a.id() + static_cast<uint32_t>(a.start_x_mm()) + a.segment() + a.frame() + a.flags() +
         static_cast<uint32_t>(a.transition()));
  if (const auto* list = m.fighters())
    for (const wire::FighterPose* f : *list) {
      take(f->avatar() + f->morphology() + static_cast<uint32_t>(f->pelvis_y_mm()));
      if (const auto* r = f->rotations())
        for (uint32_t q : *r) take(static_cast<int>(1000 * dequantize_rotation(q).w));
    }
  if (const auto* list = m.terrain_bodies())
    for (const wire::TerrainBody* b : *list) {
      take(b->avatar() + b->heading() + b->status());
      for (int16_t a : *b->angles()) take(a);
    }
  if (const auto* list = m.events())
    for (const wire::StrikeEventState* e : *list) take(e->sequence() + e->miss_mm() + e->hit());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  DropReason reason = DropReason::kNone;
  const wire::Packet* p = packet_read({data, size}, reason);
  take(static_cast<int>(reason));
  if (p == nullptr) return 0;
  switch (p->message_type()) {
    case wire::Message::ConnectRequest: {
      const auto* m = p->message_as_ConnectRequest();
      take(m->protocol() + m->library_hash()), take(m->client_name()), take(m->padding());
      break;
    }
    case wire::Message::Challenge: take(p->message_as_Challenge()->cookie()); break;
    case wire::Message::ConnectResponse: {
      const auto* m = p->message_as_ConnectResponse();
      take(m->protocol() + m->library_hash()), take(m->cookie()), take(m->client_name());
      break;
    }
    case wire::Message::Accept: {
      const auto* m = p->message_as_Accept();
      take(m->session() + m->avatar() + m->tick_hz()), take(m->scene()), take(m->library_name());
      break;
    }
    case wire::Message::Refuse: take(p->message_as_Refuse()->message()); break;
    case wire::Message::Input: {
      const auto* m = p->message_as_Input();
      take(m->session() + m->ack_snapshot());
      if (const auto* commands = m->commands())
        for (const wire::InputCommand* c : *commands) {
          const ControlInput in = control_input_from_command(*c);
          take(control_input_valid(in));
        }
      break;
    }
    case wire::Message::Snapshot: walk(*p->message_as_Snapshot()); break;
    case wire::Message::ServerStats: take(p->message_as_ServerStats()->players()); break;
    case wire::Message::TreeSummary: {
      const auto* m = p->message_as_TreeSummary();
      take(m->nodes());
      if (const auto* nodes = m->sampled())
        for (const wire::TreeNodeSample* n : *nodes) take(n->parent() + n->segment() + n->depth());
      break;
    }
    case wire::Message::Sealed: {
      const auto* m = p->message_as_Sealed();
      take(m->session() + m->sequence()), take(m->payload());
      break;
    }
    default: break;
  }
  return 0;
}
