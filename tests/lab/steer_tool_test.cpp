// foresight-motion steer, run as a user runs it: strategies 3 and 4 learn their statistics from a
// training recording (as the lab does), and the run ends the documented grace after the last key.
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

namespace foresight {
namespace {

std::string run(const std::string& args) {
  const std::string cmd = std::string(FORESIGHT_BIN_DIR) + "/foresight-motion steer --recording " +
                          std::string(FORESIGHT_SOURCE_DIR) + "/data/recordings/" + args + " 2>&1";
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return out;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), p) != nullptr) out += buf.data();
  pclose(p);
  return out;
}

std::string last_line(const std::string& s) {
  const size_t end = s.find_last_not_of('\n');
  const size_t start = s.rfind('\n', end);
  return s.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1) + 1);
}

TEST(SteerTool, StatisticStrategiesLearnFromTheTrainingRecordingAndHonourTheGrace) {
  const std::string statistic = run("obstacles_eval.json --strategy statistic");
  EXPECT_NE(statistic.find("statistics learned from"), std::string::npos) << statistic;
  EXPECT_NE(statistic.find("obstacles_train.json"), std::string::npos) << statistic;
  const std::string breadth = run("obstacles_eval.json --strategy breadth-first");
  EXPECT_EQ(breadth.find("statistics learned"), std::string::npos);
  // Learned statistics order the tree differently from first come first served.
  EXPECT_NE(last_line(statistic), last_line(breadth));
  // A run that misses the goal stops 10 s after the recording's last sample (24.3 s here), not
  // at --max-seconds (300 s).
  const std::string stalled = run("obstacles_eval.json --strategy breadth-first --expansions 1");
  const std::string end = last_line(stalled);
  ASSERT_NE(end.find("goal NOT reached after "), std::string::npos) << end;
  EXPECT_LT(std::stod(end.substr(end.find("after ") + 6)), 40.0) << end;
}

}  // namespace
}  // namespace foresight
