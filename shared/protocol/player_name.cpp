#include "protocol/player_name.hpp"

namespace foresight::protocol {

std::string printable_name(std::string_view raw) {
  std::string name(raw.substr(0, kMaxPlayerNameBytes));
  for (char& c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) c = '?';
  }
  return name;
}

}  // namespace foresight::protocol
