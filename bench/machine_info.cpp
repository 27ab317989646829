#include "machine_info.hpp"

#include <fstream>
#include <thread>

namespace foresight::bench {
namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  return "unknown cpu";
}

std::string compiler() {
#if defined(__clang__)
  return "clang " __clang_version__;
#elif defined(__GNUC__)
  return "g++ " __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string build_type() {
#ifdef NDEBUG
  return "release";
#else
  return "debug";
#endif
}

}  // namespace

std::string machine_description() {
  return cpu_model() + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " logical cores, " + compiler() + ", " + build_type() + " build";
}

nlohmann::ordered_json machine_json() {
  return {{"cpu", cpu_model()},
          {"cores", std::thread::hardware_concurrency()},
          {"compiler", compiler()},
          {"build", build_type()}};
}

}  // namespace foresight::bench
