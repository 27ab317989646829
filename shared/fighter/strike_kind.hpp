#pragma once
// What a strike is (paper 3.2.1's semantics): punch or kick, left or right, low, mid or high; their
// names as the sidecar (fighter_build/strike_annotation.hpp), the admin and the logs write them.
#include <cstdint>
#include <string_view>

namespace foresight {

enum class StrikeKind : std::uint8_t { kPunch, kKick };
enum class StrikeSide : std::uint8_t { kLeft, kRight };
enum class StrikeHeight : std::uint8_t { kLow, kMid, kHigh };

std::string_view strike_kind_name(StrikeKind kind);      ///< "punch" / "kick"
std::string_view strike_side_name(StrikeSide side);      ///< "left" / "right"
std::string_view strike_height_name(StrikeHeight height);///< "low" / "mid" / "high"
bool strike_kind_parse(std::string_view text, StrikeKind& out);
bool strike_side_parse(std::string_view text, StrikeSide& out);
bool strike_height_parse(std::string_view text, StrikeHeight& out);

}  // namespace foresight
