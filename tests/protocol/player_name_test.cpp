// Player names come from untrusted ConnectRequests and end up in log lines (issue 19).
#include "protocol/player_name.hpp"

#include <gtest/gtest.h>

namespace foresight::protocol {
namespace {

TEST(PlayerName, ControlCharactersBecomeQuestionMarksAndLettersStay) {
  EXPECT_EQ(printable_name("ann"), "ann");
  EXPECT_EQ(printable_name("evil\nforesight-server: player 1 left"), "evil?foresight-server: player 1 left");
  EXPECT_EQ(printable_name(std::string_view("a\0b\r\t\x1b[31m\x7f", 11)), "a?b???[31m?");
  EXPECT_EQ(printable_name("Zoë 李"), "Zoë 李");  // UTF-8 letters are not control characters
  EXPECT_EQ(printable_name(std::string(100, 'x')).size(), kMaxPlayerNameBytes);
}

}  // namespace
}  // namespace foresight::protocol
