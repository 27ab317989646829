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

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string machine_description() {
  return cpu_model() + ", " + std::to_string(std::thread::hardware_concurrency()) +
         " logical cores, " + compiler() + ", " + build_type() + " build";
}

std::string machine_json_fields() {
  return "\"cpu\":\"" + escaped(cpu_model()) + "\",\"cores\":" +
         std::to_string(std::thread::hardware_concurrency()) + ",\"compiler\":\"" +
         escaped(compiler()) + "\",\"build\":\"" + build_type() + "\"";
}

}  // namespace foresight::bench
