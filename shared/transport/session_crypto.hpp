#pragma once
// Per-session authenticated encryption (libsodium; docs/PROTOCOL.md "Sealed sessions"). At connect
// each side makes an X25519 key pair for the session and sends its public key (the client in its
// ConnectResponse, the server in its Accept); crypto_kx derives one key per direction. Every later
// message goes as a Sealed packet: ChaCha20-Poly1305 (IETF) with nonce = the sender's sequence
// number (never reused: it counts up) and the session id as additional data. The receiver keeps a
// 64-wide replay window. So nobody off the path can read a session's messages or inject one, and
// a recorded one cannot be played again.
#include "protocol/packet.hpp"

#include <array>
#include <cstdint>
#include <span>

namespace foresight::protocol {

inline constexpr size_t kSessionKeyBytes = 32;
inline constexpr size_t kSealTagBytes = 16;
/// What sealing adds to a datagram at most (tag, Sealed table, its vector and header).
inline constexpr size_t kSealOverheadBytes = kSealTagBytes + 80;  // measured 88 in all (session_crypto_test)

using SessionKey = std::array<uint8_t, kSessionKeyBytes>;

struct SessionKeyPair {
  SessionKey public_key{}, secret_key{};
};
/// A fresh key pair (libsodium initialised on first use).
SessionKeyPair session_keypair();

/// One key per direction.
struct SessionKeys {
  SessionKey receive{}, send{};
};
/// The client's and the server's view of the same two keys. False for a malformed peer key.
bool session_keys_client(const SessionKeyPair& own, std::span<const uint8_t> server_public, SessionKeys& out);
bool session_keys_server(const SessionKeyPair& own, std::span<const uint8_t> client_public, SessionKeys& out);

/// Accepts each sequence number once, within 64 of the newest seen (older ones are refused).
class ReplayWindow {
 public:
  bool fresh(uint64_t sequence) const;
  void mark(uint64_t sequence);

 private:
  uint64_t newest_ = 0;
  uint64_t seen_ = 0;  ///< Bit i: newest_ - i was seen.
};

/// The sender's side: wraps `inner` (a whole Packet) into a Sealed packet written by `w`; `scratch`
/// holds the ciphertext. The sequence counts up per call. Empty for an inner packet over
/// kMaxDatagramBytes.
class Sealer {
 public:
  void set(uint32_t session, const SessionKey& key) {
    session_ = session;
    key_ = key;
    next_ = 1;
    ready_ = true;
  }
  bool ready() const { return ready_; }
  std::span<const uint8_t> seal(PacketWriter& w, std::span<const uint8_t> inner);

 private:
  uint32_t session_ = 0;
  SessionKey key_{};
  uint64_t next_ = 1;
  bool ready_ = false;
};

/// The receiver's side: the inner packet of a Sealed message, or nullptr with `reason`
/// (kUnauthenticated: wrong session or forged/corrupted; kReplayed). The inner bytes go to the
/// calling thread's buffer, not the Opener's (a server holds an Opener per session, and 1.2 KB
/// each was most of a session's memory): the returned packet and plain() are valid until the
/// next open() on this thread, by this Opener or any other.
class Opener {
 public:
  void set(uint32_t session, const SessionKey& key) {
    session_ = session;
    key_ = key;
    window_ = {};
    ready_ = true;
  }
  bool ready() const { return ready_; }
  const wire::Packet* open(const wire::Sealed& m, DropReason& reason);
  /// The inner packet's bytes of the last successful open (see above for how long).
  std::span<const uint8_t> plain() const { return {plain_, plain_size_}; }

 private:
  const uint8_t* plain_ = nullptr;
  size_t plain_size_ = 0;
  uint32_t session_ = 0;
  SessionKey key_{};
  ReplayWindow window_;
  bool ready_ = false;
};

}  // namespace foresight::protocol
