#pragma once
// What a benchmark ran on, printed with its figures (numbers without the machine are noise).
#include <nlohmann/json.hpp>

#include <string>

namespace foresight::bench {

/// One line: CPU model, logical cores, compiler, build type.
std::string machine_description();
/// The same as a JSON object: {"cpu":"...","cores":N,"compiler":"...","build":"..."}.
nlohmann::ordered_json machine_json();

}  // namespace foresight::bench
