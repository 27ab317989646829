#pragma once
// The one way the benchmarks and the lab write JSON: nlohmann::ordered_json (keys stay in the order
// they are written), numbers rounded to the places they mean, where it ran appended last.
#include <nlohmann/json.hpp>

#include <string>

namespace foresight::bench {

using Json = nlohmann::ordered_json;

/// `v` rounded to `decimals` places, as a JSON number: 0.64739 at 4 is 0.6474, not 17 significant
/// digits; a whole number (integer) when `decimals` is 0; null when `v` is NaN or infinite.
Json rounded(double v, int decimals);

/// `j` with where it ran (machine_json()'s fields) appended, on one line, no trailing newline.
std::string json_line(Json j);

/// Prints json_line(j) and a newline on stdout: a benchmark's last line with --json.
void print_json_line(Json j);

/// Prints "machine: " and machine_description() on stdout: a benchmark's first line.
void print_machine_line();

}  // namespace foresight::bench
