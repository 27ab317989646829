#pragma once
// Internal to the scene loader: typed access to nlohmann::json values that records the first
// error as "<source>: <json.path>: <reason>". Every accessor returns false after a failure so
// callers can chain them with &&. Never throws for wrong types or ranges.
#include "math/types.hpp"

#include "io/json_describe.hpp"

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace foresight::scene_json {

class Reader {
 public:
  using json = nlohmann::json;

  explicit Reader(std::string_view source) : source_(source) {}

  const std::string& error() const { return error_; }
  /// Records "<source>: <path>: <reason>" and returns false.
  bool fail(std::string_view path, std::string_view reason);

  static std::string child(const std::string& path, std::string_view key);
  static std::string index(const std::string& path, std::size_t i);
  /// Shortest faithful decimal form ("0.2", "1e+30").
  static std::string fmt(double v);
  /// "a string (\"abc\")", "a number (3)", "an object", ... for error messages.
  /// Checks range and finiteness; on failure sets `reason` and returns false.
  static bool number_in_range(const json& j, double lo, double hi, float& out, std::string& reason);

  bool require_object(const json& j, const std::string& path);
  /// Fails on a key not in `allowed`; keys starting with '_' are comments and always allowed.
  bool check_keys(const json& obj, const std::string& path,
                  std::initializer_list<std::string_view> allowed);
  /// Finds obj[key]. A missing or null member is an error when `required`, else out = nullptr.
  bool member(const json& obj, const std::string& path, std::string_view key, bool required,
              const json*& out);

  bool number(const json& j, const std::string& path, double lo, double hi, float& out);
  bool integer(const json& j, const std::string& path, int lo, int hi, int& out);
  bool required_number(const json& obj, const std::string& path, std::string_view key, double lo,
                       double hi, float& out);
  /// Leaves `out` unchanged when absent.
  bool optional_number(const json& obj, const std::string& path, std::string_view key, double lo,
                       double hi, float& out);
  bool required_string(const json& obj, const std::string& path, std::string_view key,
                       std::string& out);
  bool optional_string(const json& obj, const std::string& path, std::string_view key,
                       std::string& out);
  /// [x, z] on the ground plane.
  bool required_vec2(const json& obj, const std::string& path, std::string_view key, vec2& out);
  /// [x, y, z].
  bool required_vec3(const json& obj, const std::string& path, std::string_view key, vec3& out);
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
  bool vec_components(const json& obj, const std::string& path, std::string_view key,
                      std::size_t n, float* out);

  std::string source_;
  std::string error_;
};

}  // namespace foresight::scene_json
