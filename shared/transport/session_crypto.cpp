#include "transport/session_crypto.hpp"

#include <sodium.h>

#include <cstdlib>
#include <cstring>

namespace foresight::protocol {

namespace {

void ensure_sodium() {
  static const bool ok = sodium_init() >= 0;
  if (!ok) std::abort();  // no usable random source: nothing can be secured
}

std::array<uint8_t, crypto_aead_chacha20poly1305_IETF_NPUBBYTES> nonce_of(uint64_t sequence) {
  std::array<uint8_t, crypto_aead_chacha20poly1305_IETF_NPUBBYTES> n{};
  for (int i = 0; i < 8; ++i) n[static_cast<size_t>(4 + i)] = static_cast<uint8_t>(sequence >> (8 * i));
  return n;
}

std::array<uint8_t, 4> ad_of(uint32_t session) {
  return {static_cast<uint8_t>(session), static_cast<uint8_t>(session >> 8), static_cast<uint8_t>(session >> 16),
          static_cast<uint8_t>(session >> 24)};
}

}  // namespace

static_assert(kSessionKeyBytes == crypto_kx_PUBLICKEYBYTES && kSessionKeyBytes == crypto_kx_SESSIONKEYBYTES);
static_assert(kSealTagBytes == crypto_aead_chacha20poly1305_IETF_ABYTES);

SessionKeyPair session_keypair() {
  ensure_sodium();
  SessionKeyPair k;
  crypto_kx_keypair(k.public_key.data(), k.secret_key.data());
  return k;
}

bool session_keys_client(const SessionKeyPair& own, std::span<const uint8_t> server_public, SessionKeys& out) {
  return server_public.size() == kSessionKeyBytes &&
         crypto_kx_client_session_keys(out.receive.data(), out.send.data(), own.public_key.data(), own.secret_key.data(),
                                       server_public.data()) == 0;
}

bool session_keys_server(const SessionKeyPair& own, std::span<const uint8_t> client_public, SessionKeys& out) {
  return client_public.size() == kSessionKeyBytes &&
         crypto_kx_server_session_keys(out.receive.data(), out.send.data(), own.public_key.data(), own.secret_key.data(),
                                       client_public.data()) == 0;
}

bool ReplayWindow::fresh(uint64_t sequence) const {
  if (sequence == 0) return false;
  if (sequence > newest_) return true;
  const uint64_t age = newest_ - sequence;
  return age < 64 && !(seen_ & (1ull << age));
}

void ReplayWindow::mark(uint64_t sequence) {
  if (sequence > newest_) {
    const uint64_t shift = sequence - newest_;
    seen_ = shift >= 64 ? 0 : seen_ << shift;
    newest_ = sequence;
  }
  const uint64_t age = newest_ - sequence;
  if (age < 64) seen_ |= 1ull << age;
}

std::span<const uint8_t> Sealer::seal(PacketWriter& w, std::span<const uint8_t> inner) {
  if (inner.size() > kMaxDatagramBytes) return {};  // never a datagram of ours
  const uint64_t sequence = next_++;
  const auto nonce = nonce_of(sequence);
  const auto ad = ad_of(session_);
  unsigned long long n = 0;
  // Sealed into the thread's scratch first: `inner` may be the writer's own last packet, which
  // begin() below starts overwriting.
  thread_local std::array<uint8_t, kMaxDatagramBytes + kSealTagBytes> sealed;
  crypto_aead_chacha20poly1305_ietf_encrypt(sealed.data(), &n, inner.data(), inner.size(), ad.data(), ad.size(),
                                            nullptr, nonce.data(), key_.data());
  auto& fbb = w.begin();
  const auto payload = fbb.CreateVector(sealed.data(), static_cast<size_t>(n));
  return w.finish(wire::CreateSealed(fbb, session_, sequence, payload));
}

const wire::Packet* Opener::open(const wire::Sealed& m, DropReason& reason) {
  reason = DropReason::kUnauthenticated;
  const auto* payload = m.payload();
  // The thread's buffer (see the header): 16-byte aligned, FlatBuffers read the packet in place.
  alignas(16) thread_local std::array<uint8_t, kMaxDatagramBytes> plain;
  if (!ready_ || m.session() != session_ || payload == nullptr || payload->size() < kSealTagBytes ||
      payload->size() - kSealTagBytes > plain.size())
    return nullptr;
  if (!window_.fresh(m.sequence())) {
    reason = DropReason::kReplayed;
    return nullptr;
  }
  const auto nonce = nonce_of(m.sequence());
  const auto ad = ad_of(session_);
  unsigned long long n = 0;
  if (crypto_aead_chacha20poly1305_ietf_decrypt(plain.data(), &n, nullptr, payload->data(), payload->size(), ad.data(),
                                                ad.size(), nonce.data(), key_.data()) != 0)
    return nullptr;  // forged or corrupted: the window stays as it was
  const wire::Packet* inner = packet_read({plain.data(), static_cast<size_t>(n)}, reason);
  if (inner == nullptr) return nullptr;
  if (inner->message_type() == wire::Message::Sealed) {  // no nesting
    reason = DropReason::kUnexpected;
    return nullptr;
  }
  window_.mark(m.sequence());
  plain_ = plain.data();
  plain_size_ = static_cast<size_t>(n);
  return inner;
}

}  // namespace foresight::protocol
