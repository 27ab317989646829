#pragma once
// What a benchmark ran on, printed with its figures (numbers without the machine are noise).
#include <string>

namespace foresight::bench {

/// One line: CPU model, logical cores, compiler, build type.
std::string machine_description();
/// The same as a JSON object body fragment: "cpu":"...","cores":N,"compiler":"...","build":"...".
std::string machine_json_fields();

}  // namespace foresight::bench
