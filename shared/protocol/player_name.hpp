#pragma once
// A player's name as the server keeps it: it comes from an untrusted ConnectRequest and goes into
// log lines, the admin endpoint and other tools, so it holds no control characters (a name with a
// newline could forge a server log line; an escape sequence could recolour a terminal).
#include <cstddef>
#include <string>
#include <string_view>

namespace foresight::protocol {

inline constexpr std::size_t kMaxPlayerNameBytes = 64;

/// At most kMaxPlayerNameBytes bytes of `raw`, with every ASCII control character (0x00-0x1f,
/// 0x7f) replaced by '?'. Other bytes (UTF-8 letters) are kept.
std::string printable_name(std::string_view raw);

}  // namespace foresight::protocol
