#pragma once
// Typed access to nlohmann::json values for the file readers (scenes, recordings) that records
// the first error as "<source>: <json.path>: <reason>" ("<source>: <reason>" for an empty path).
// Every accessor returns false after a failure so callers can chain them with &&. Never throws
// for wrong types or ranges. Numbers in messages are quoted in the shortest text that reads back
// as the destination type: fmt() for float fields, shortest() for double fields.
#include "math/types.hpp"

#include "io/json_describe.hpp"

#include <nlohmann/json.hpp>

#include <exception>
#include <initializer_list>
#include <new>
#include <string>
#include <string_view>
#include <vector>

namespace foresight::json_io {

class Reader {
 public:
  using json = nlohmann::json;

  /// How member() treats a member whose value is null.
  enum class Null { absent, value };
  /// Where numbers() reports a bad component: at "path[i]" (numbers quoted by fmt()), or at
  /// "path" as "component i: ..." (numbers quoted by shortest()).
  enum class Component { indexed, in_reason };

  explicit Reader(std::string_view source) : source_(source) {}

  const std::string& error() const { return error_; }
  bool failed() const { return !error_.empty(); }
  /// Records "<source>: <path>: <reason>" (no path part when empty) and returns false.
  bool fail(std::string_view path, std::string_view reason);

  static std::string child(const std::string& path, std::string_view key);
  static std::string index(const std::string& path, std::size_t i);
  /// Shortest decimal form that reads back as the same float ("0.2", "1e+30").
  static std::string fmt(double v);
  /// Shortest decimal form that reads back as the same double ("0.30000001", "1e+05").
  static std::string shortest(double v);
  /// Checks type, range and finiteness; on failure sets `reason` and returns false.
  static bool number_in_range(const json& j, double lo, double hi, float& out, std::string& reason);

  bool require_object(const json& j, const std::string& path);
  /// Fails on keys not in `allowed`, naming up to 8 of them; keys starting with '_' are
  /// comments and always allowed.
  bool check_keys(const json& obj, const std::string& path,
                  std::initializer_list<std::string_view> allowed);
  /// Finds obj[key]. A missing member (or null one, with Null::absent) is an error when
  /// `required`, else out = nullptr.
  bool member(const json& obj, const std::string& path, std::string_view key, bool required,
              const json*& out, Null null = Null::absent);

  bool number(const json& j, const std::string& path, double lo, double hi, float& out);
  bool number(const json& j, const std::string& path, double lo, double hi, double& out);
  bool integer(const json& j, const std::string& path, int lo, int hi, int& out);
  bool required_number(const json& obj, const std::string& path, std::string_view key, double lo,
                       double hi, float& out);
  /// Leaves `out` unchanged when absent.
  bool optional_number(const json& obj, const std::string& path, std::string_view key, double lo,
                       double hi, float& out);
  /// Any string value, of any length.
  bool string(const json& j, const std::string& path, std::string& out);
  /// At most 256 characters.
  bool required_string(const json& obj, const std::string& path, std::string_view key,
                       std::string& out);
  bool optional_string(const json& obj, const std::string& path, std::string_view key,
                       std::string& out);
  /// An array of n numbers within [-limit, limit]; `shape` names it in messages ("[x, y]").
  bool numbers(const json& j, const std::string& path, std::size_t n, double limit,
               std::string_view shape, float* out, Component where = Component::indexed);
  /// [x, z] on the ground plane.
  bool required_vec2(const json& obj, const std::string& path, std::string_view key, double limit,
                     vec2& out);
  /// [x, y, z].
  bool required_vec3(const json& obj, const std::string& path, std::string_view key, double limit,
                     vec3& out);
  /// "max.y (0.2) must be > min.y (0.5)"; vec2 components are named x and z.
  bool check_min_less_max(const std::string& max_path, vec2 min, vec2 max);
  bool check_min_less_max(const std::string& max_path, vec3 min, vec3 max);

  /// Optional array member: absent or null gives an empty vector. Each element is read by
  /// read(Reader&, const json&, const std::string& path, T&).
  template <typename T, typename ReadFn>
  bool array_of(const json& obj, const std::string& path, std::string_view key,
                std::size_t max_count, std::vector<T>& out, ReadFn read) {
    out.clear();
    const json* arr = nullptr;
    if (!member(obj, path, key, false, arr)) return false;
    if (arr == nullptr) return true;
    const std::string arr_path = child(path, key);
    if (!arr->is_array()) return fail(arr_path, "expected an array, got " + json_describe(*arr));
    if (arr->size() > max_count)
      return fail(arr_path, "has " + std::to_string(arr->size()) + " entries, more than the " +
                                std::to_string(max_count) + " allowed");
    out.resize(arr->size());
    for (std::size_t i = 0; i < arr->size(); ++i)
      if (!read(*this, (*arr)[i], index(arr_path, i), out[i])) return false;
    return true;
  }

 private:
  std::string source_;
  std::string error_;
};

/// Parses `text` into `out`. A syntax error, or a number too large for a double, sets `error` to
/// "<source>: invalid JSON at line L, column C: <what>" (1-based, as editors count) and returns
/// false. `callback` is nlohmann's parser callback (keep, drop or stop at each value).
bool parse(std::string_view text, std::string_view source, nlohmann::json& out, std::string& error,
           const nlohmann::json::parser_callback_t& callback = nullptr);

/// Returns read(), turning anything it throws (allocation failure on a huge file, an exception
/// nobody foresaw) into "<source>: ..." in `error`: a broken file must never take a program
/// down. `kind` names the file in messages ("scene").
template <typename ReadFn>
bool guarded(std::string_view source, std::string_view kind, std::string& error, ReadFn read) {
  try {
    return read();
  } catch (const std::bad_alloc&) {
    error = std::string(source) + ": out of memory while reading the " + std::string(kind);
  } catch (const std::exception& e) {
    error = std::string(source) + ": " + e.what();
  } catch (...) {
    error = std::string(source) + ": unknown error while reading the " + std::string(kind);
  }
  return false;
}

}  // namespace foresight::json_io
