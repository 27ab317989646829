#include "fighter/strike_kind.hpp"

namespace foresight {

std::string_view strike_kind_name(StrikeKind kind) { return kind == StrikeKind::kKick ? "kick" : "punch"; }
std::string_view strike_side_name(StrikeSide side) { return side == StrikeSide::kRight ? "right" : "left"; }
std::string_view strike_height_name(StrikeHeight height) {
  switch (height) {
    case StrikeHeight::kLow: return "low";
    case StrikeHeight::kMid: return "mid";
    case StrikeHeight::kHigh: return "high";
  }
  return "mid";
}

bool strike_kind_parse(std::string_view text, StrikeKind& out) {
  if (text == "punch") out = StrikeKind::kPunch;
  else if (text == "kick") out = StrikeKind::kKick;
  else return false;
  return true;
}
bool strike_side_parse(std::string_view text, StrikeSide& out) {
  if (text == "left") out = StrikeSide::kLeft;
  else if (text == "right") out = StrikeSide::kRight;
  else return false;
  return true;
}
bool strike_height_parse(std::string_view text, StrikeHeight& out) {
  if (text == "low") out = StrikeHeight::kLow;
  else if (text == "mid") out = StrikeHeight::kMid;
  else if (text == "high") out = StrikeHeight::kHigh;
  else return false;
  return true;
}

}  // namespace foresight
