#include "io/json_describe.hpp"

#include <charconv>

namespace foresight {

std::string json_describe(const nlohmann::json& j) {
  using value_t = nlohmann::json::value_t;
  switch (j.type()) {
    case value_t::null: return "null";
    case value_t::boolean: return std::string("a boolean (") + (j.get<bool>() ? "true" : "false") + ")";
    case value_t::string: {
      std::string s = j.get_ref<const std::string&>();
      if (s.size() > 40) s = s.substr(0, 40) + "...";
      return "a string (\"" + s + "\")";
    }
    case value_t::number_integer:
    case value_t::number_unsigned:
    case value_t::number_float: {
      char buf[32];
      const auto end = std::to_chars(buf, buf + sizeof buf, j.get<double>()).ptr;  // shortest form
      return "a number (" + std::string(buf, end) + ")";
    }
    case value_t::object: return "an object";
    case value_t::array: return "an array of " + std::to_string(j.size());
    default: return "an unsupported value";
  }
}

}  // namespace foresight
