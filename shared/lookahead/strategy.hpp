#pragma once
// The five exploration strategies of the paper (section 4.2, experiments 5.2).
#include <optional>
#include <string>
#include <string_view>

namespace foresight {

enum class Strategy : int {
  kBreadthFirst = 0,       ///< Type 0: shallowest leaf first (first come first served).
  kCommand = 1,            ///< Type 1: command matching, leaf priorities re-sorted every frame.
  kCommandNoResort = 2,    ///< Type 2: command matching, priorities fixed when a node is added.
  kStatistic = 3,          ///< Type 3: child-choice frequencies learned from a recording.
  kHybrid = 4,             ///< Type 4: product of types 1 and 3 (re-sorted every frame).
};
inline constexpr int kNumStrategies = 5;

/// Strategies 3 and 4 read statistics learned from a training recording (learn_statistics).
inline bool uses_statistics(Strategy s) { return s == Strategy::kStatistic || s == Strategy::kHybrid; }

/// "breadth-first", "command", "command-no-resort", "statistic", "hybrid".
std::string_view strategy_name(Strategy s);
/// Accepts the names above or the paper's numbers "0".."4"; nullopt otherwise.
std::optional<Strategy> strategy_from_name(std::string_view name);
/// The accepted names, for error messages: "breadth-first|command|...".
std::string strategy_names();
/// strategy_from_name with the error every CLI prints: "unknown strategy 'x' (breadth-first|...)".
bool strategy_parse(std::string_view name, Strategy& out, std::string& error);

}  // namespace foresight
