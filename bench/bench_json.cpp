#include "bench_json.hpp"

#include "machine_info.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>

namespace foresight::bench {

Json rounded(double v, int decimals) {
  if (!std::isfinite(v)) return nullptr;
  if (decimals <= 0) return static_cast<std::int64_t>(std::llround(v));
  const double scale = std::pow(10.0, decimals);
  return std::round(v * scale) / scale;
}

std::string json_line(Json j) {
  j.update(machine_json());
  // A file or CPU name that is not UTF-8 gets U+FFFD rather than an exception.
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

void print_json_line(Json j) { std::printf("%s\n", json_line(std::move(j)).c_str()); }

void print_machine_line() { std::printf("machine: %s\n", machine_description().c_str()); }

}  // namespace foresight::bench
