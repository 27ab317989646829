#include "lookahead/strategy.hpp"

namespace foresight {
namespace {

constexpr std::string_view kNames[kNumStrategies] = {"breadth-first", "command", "command-no-resort",
                                                     "statistic", "hybrid"};

}  // namespace

std::string_view strategy_name(Strategy s) { return kNames[static_cast<int>(s)]; }

std::optional<Strategy> strategy_from_name(std::string_view name) {
  for (int i = 0; i < kNumStrategies; ++i)
    if (name == kNames[i] || (name.size() == 1 && name[0] == static_cast<char>('0' + i)))
      return static_cast<Strategy>(i);
  return std::nullopt;
}

std::string strategy_names() {
  std::string out;
  for (int i = 0; i < kNumStrategies; ++i) out += (i ? "|" : "") + std::string(kNames[i]);
  return out;
}

bool strategy_parse(std::string_view name, Strategy& out, std::string& error) {
  const auto s = strategy_from_name(name);
  if (!s) return error = "unknown strategy '" + std::string(name) + "' (" + strategy_names() + ")", false;
  out = *s;
  return true;
}

}  // namespace foresight
