#include "io/json_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace foresight::json_io {
namespace {

// The checks of number(): type, finiteness, range. `text` formats numbers for the message.
template <typename Out>
bool checked_number(const nlohmann::json& j, double lo, double hi, Out& out, std::string& reason,
                    std::string (*text)(double)) {
  if (!j.is_number()) {
    reason = "expected a number, got " + json_describe(j);
    return false;
  }
  const double v = j.get<double>();
  if (!std::isfinite(v)) {
    reason = "is not a finite number";
    return false;
  }
  if (v < lo || v > hi) {
    reason = text(v) + " is out of range [" + text(lo) + ", " + text(hi) + "]";
    return false;
  }
  out = static_cast<Out>(v);
  return true;
}

/// 1-based line and column of a byte offset, as editors count them.
void line_column(std::string_view text, std::size_t byte, std::size_t& line, std::size_t& column) {
  line = 1;
  column = 1;
  const std::size_t end = std::min(byte, text.size());
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

std::string min_max_reason(char axis, float min, float max) {
  return std::string("max.") + axis + " (" + Reader::fmt(max) + ") must be > min." + axis + " (" +
         Reader::fmt(min) + ")";
}

}  // namespace

bool Reader::fail(std::string_view path, std::string_view reason) {
  // Keep the first error: it is the cause, later ones are usually consequences.
  if (error_.empty())
    error_ = source_ + ": " + (path.empty() ? "" : std::string(path) + ": ") + std::string(reason);
  return false;
}

std::string Reader::child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string Reader::index(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

std::string Reader::fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  // %.9g prints floats exactly but noisily (0.200000003); prefer the short form when it
  // round-trips to the same float, which is what the author typed.
  char short_buf[32];
  std::snprintf(short_buf, sizeof short_buf, "%g", v);
  if (static_cast<float>(std::strtod(short_buf, nullptr)) == static_cast<float>(v)) return short_buf;
  return buf;
}

std::string Reader::shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

bool Reader::number_in_range(const json& j, double lo, double hi, float& out, std::string& reason) {
  return checked_number(j, lo, hi, out, reason, &Reader::fmt);
}

bool Reader::require_object(const json& j, const std::string& path) {
  if (j.is_object()) return true;
  return fail(path, "expected an object, got " + json_describe(j));
}

bool Reader::check_keys(const json& obj, const std::string& path,
                        std::initializer_list<std::string_view> allowed) {
  std::string unknown;
  int count = 0;
  for (const auto& item : obj.items()) {
    const std::string& key = item.key();
    if (!key.empty() && key[0] == '_') continue;
    bool known = false;
    for (std::string_view a : allowed) known = known || a == key;
    if (known) continue;
    if (count < 8) unknown += (unknown.empty() ? "\"" : ", \"") + key + "\"";
    ++count;
  }
  if (count == 0) return true;
  std::string names;
  for (std::string_view a : allowed) names += (names.empty() ? "" : ", ") + std::string(a);
  return fail(path, std::string(count == 1 ? "unknown field " : "unknown fields ") + unknown +
                        (count > 8 ? " and " + std::to_string(count - 8) + " more" : "") +
                        " (allowed: " + names + ")");
}

bool Reader::member(const json& obj, const std::string& path, std::string_view key, bool required,
                    const json*& out, Null null) {
  out = nullptr;
  const auto it = obj.find(key);
  if (it == obj.end() || (null == Null::absent && it->is_null())) {
    if (required) return fail(child(path, key), "missing required field");
    return true;
  }
  out = &*it;
  return true;
}

bool Reader::number(const json& j, const std::string& path, double lo, double hi, float& out) {
  std::string reason;
  return checked_number(j, lo, hi, out, reason, &Reader::fmt) || fail(path, reason);
}

bool Reader::number(const json& j, const std::string& path, double lo, double hi, double& out) {
  std::string reason;
  return checked_number(j, lo, hi, out, reason, &Reader::shortest) || fail(path, reason);
}

bool Reader::integer(const json& j, const std::string& path, int lo, int hi, int& out) {
  if (!j.is_number_integer()) return fail(path, "expected an integer, got " + json_describe(j));
  // Compare as double so a huge unsigned or negative value cannot wrap into range.
  const double v = j.get<double>();
  if (v < lo || v > hi)
    return fail(path, fmt(v) + " is out of range [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "]");
  out = static_cast<int>(v);
  return true;
}

bool Reader::required_number(const json& obj, const std::string& path, std::string_view key,
                             double lo, double hi, float& out) {
  const json* j = nullptr;
  return member(obj, path, key, true, j) && number(*j, child(path, key), lo, hi, out);
}

bool Reader::optional_number(const json& obj, const std::string& path, std::string_view key,
                             double lo, double hi, float& out) {
  const json* j = nullptr;
  if (!member(obj, path, key, false, j)) return false;
  return j == nullptr || number(*j, child(path, key), lo, hi, out);
}

bool Reader::string(const json& j, const std::string& path, std::string& out) {
  if (!j.is_string()) return fail(path, "expected a string, got " + json_describe(j));
  out = j.get<std::string>();
  return true;
}

bool Reader::required_string(const json& obj, const std::string& path, std::string_view key,
                             std::string& out) {
  const json* j = nullptr;
  if (!member(obj, path, key, true, j) || !string(*j, child(path, key), out)) return false;
  if (out.size() > 256) return fail(child(path, key), "is longer than 256 characters");
  return true;
}

bool Reader::optional_string(const json& obj, const std::string& path, std::string_view key,
                             std::string& out) {
  const json* j = nullptr;
  if (!member(obj, path, key, false, j)) return false;
  if (j == nullptr) return true;
  return required_string(obj, path, key, out);
}

bool Reader::numbers(const json& j, const std::string& path, std::size_t n, double limit,
                     std::string_view shape, float* out, Component where) {
  if (!j.is_array() || j.size() != n)
    return fail(path, "expected an array of " + std::to_string(n) + " numbers " +
                          std::string(shape) + ", got " + json_describe(j));
  for (std::size_t i = 0; i < n; ++i) {
    if (where == Component::indexed) {
      if (!number(j[i], index(path, i), -limit, limit, out[i])) return false;
      continue;
    }
    std::string reason;
    if (!checked_number(j[i], -limit, limit, out[i], reason, &Reader::shortest))
      return fail(path, "component " + std::to_string(i) + ": " + reason);
  }
  return true;
}

bool Reader::required_vec2(const json& obj, const std::string& path, std::string_view key,
                           double limit, vec2& out) {
  const json* j = nullptr;
  float v[2] = {0.0f, 0.0f};
  if (!member(obj, path, key, true, j) || !numbers(*j, child(path, key), 2, limit, "[x, z]", v))
    return false;
  out = {v[0], v[1]};
  return true;
}

bool Reader::required_vec3(const json& obj, const std::string& path, std::string_view key,
                           double limit, vec3& out) {
  const json* j = nullptr;
  float v[3] = {0.0f, 0.0f, 0.0f};
  if (!member(obj, path, key, true, j) || !numbers(*j, child(path, key), 3, limit, "[x, y, z]", v))
    return false;
  out = {v[0], v[1], v[2]};
  return true;
}

bool Reader::check_min_less_max(const std::string& max_path, vec2 min, vec2 max) {
  if (!(max.x > min.x)) return fail(max_path, min_max_reason('x', min.x, max.x));
  if (!(max.y > min.y)) return fail(max_path, min_max_reason('z', min.y, max.y));
  return true;
}

bool Reader::check_min_less_max(const std::string& max_path, vec3 min, vec3 max) {
  if (!(max.x > min.x)) return fail(max_path, min_max_reason('x', min.x, max.x));
  if (!(max.y > min.y)) return fail(max_path, min_max_reason('y', min.y, max.y));
  if (!(max.z > min.z)) return fail(max_path, min_max_reason('z', min.z, max.z));
  return true;
}

bool parse(std::string_view text, std::string_view source, nlohmann::json& out, std::string& error,
           const nlohmann::json::parser_callback_t& callback) {
  using json = nlohmann::json;
  try {
    out = json::parse(text.begin(), text.end(), callback);
    return true;
  } catch (const json::parse_error& e) {
    // nlohmann reports the offset of the byte after the error; point at the byte itself.
    std::size_t line = 0, column = 0;
    line_column(text, e.byte > 0 ? e.byte - 1 : 0, line, column);
    std::string what = e.what();
    // Drop nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 2: " prefix;
    // we print our own position.
    if (const std::size_t colon = what.find(": "); colon != std::string::npos)
      what = what.substr(colon + 2);
    error = std::string(source) + ": invalid JSON at line " + std::to_string(line) + ", column " +
            std::to_string(column) + ": " + what;
  } catch (const json::out_of_range& e) {
    // A number literal too large for a double ("1e400"): nlohmann gives no position, but it
    // quotes the literal, so find it in the text.
    std::string what = e.what();
    if (const std::size_t p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    std::string where;
    const std::size_t q0 = what.find('\'');
    const std::size_t q1 = q0 == std::string::npos ? q0 : what.find('\'', q0 + 1);
    if (q1 != std::string::npos) {
      const std::size_t at = text.find(what.substr(q0 + 1, q1 - q0 - 1));
      if (at != std::string_view::npos) {
        std::size_t line = 0, column = 0;
        line_column(text, at, line, column);
        where = " at line " + std::to_string(line) + ", column " + std::to_string(column);
      }
    }
    error = std::string(source) + ": invalid JSON" + where + ": " + what + " (not a finite number)";
  }
  return false;
}

}  // namespace foresight::json_io
