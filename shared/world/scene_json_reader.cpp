#include "world/scene_json_reader.hpp"

#include "io/json_describe.hpp"

#include "world/scene.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace foresight::scene_json {

bool Reader::fail(std::string_view path, std::string_view reason) {
  // Keep the first error: it is the cause, later ones are usually consequences.
  if (error_.empty()) error_ = source_ + ": " + std::string(path) + ": " + std::string(reason);
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


bool Reader::number_in_range(const json& j, double lo, double hi, float& out, std::string& reason) {
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
    reason = fmt(v) + " is out of range [" + fmt(lo) + ", " + fmt(hi) + "]";
    return false;
  }
  out = static_cast<float>(v);
  return true;
}

bool Reader::require_object(const json& j, const std::string& path) {
  if (j.is_object()) return true;
  return fail(path, "expected an object, got " + json_describe(j));
}

bool Reader::check_keys(const json& obj, const std::string& path,
                        std::initializer_list<std::string_view> allowed) {
  for (const auto& item : obj.items()) {
    const std::string& key = item.key();
    if (!key.empty() && key[0] == '_') continue;
    bool known = false;
    for (std::string_view a : allowed) known = known || a == key;
    if (known) continue;
    std::string list;
    for (std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    return fail(path.empty() ? "(root)" : path,
                "unknown field \"" + key + "\" (expected: " + list + ")");
  }
  return true;
}

bool Reader::member(const json& obj, const std::string& path, std::string_view key, bool required,
                    const json*& out) {
  out = nullptr;
  const auto it = obj.find(key);
  if (it == obj.end() || it->is_null()) {
    if (required) return fail(child(path, key), "missing required field");
    return true;
  }
  out = &*it;
  return true;
}

bool Reader::number(const json& j, const std::string& path, double lo, double hi, float& out) {
  std::string reason;
  if (number_in_range(j, lo, hi, out, reason)) return true;
  return fail(path, reason);
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

bool Reader::required_string(const json& obj, const std::string& path, std::string_view key,
                             std::string& out) {
  const json* j = nullptr;
  if (!member(obj, path, key, true, j)) return false;
  if (!j->is_string()) return fail(child(path, key), "expected a string, got " + json_describe(*j));
  out = j->get<std::string>();
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

bool Reader::vec_components(const json& obj, const std::string& path, std::string_view key,
                            std::size_t n, float* out) {
  const json* j = nullptr;
  if (!member(obj, path, key, true, j)) return false;
  const std::string p = child(path, key);
  if (!j->is_array() || j->size() != n)
    return fail(p, "expected an array of " + std::to_string(n) + " numbers " +
                       (n == 2 ? "[x, z]" : "[x, y, z]") + ", got " + json_describe(*j));
  for (std::size_t i = 0; i < n; ++i)
    if (!number((*j)[i], index(p, i), -kMaxSceneCoord_m, kMaxSceneCoord_m, out[i])) return false;
  return true;
}

bool Reader::required_vec2(const json& obj, const std::string& path, std::string_view key,
                           vec2& out) {
  float v[2] = {0.0f, 0.0f};
  if (!vec_components(obj, path, key, 2, v)) return false;
  out = {v[0], v[1]};
  return true;
}

bool Reader::required_vec3(const json& obj, const std::string& path, std::string_view key,
                           vec3& out) {
  float v[3] = {0.0f, 0.0f, 0.0f};
  if (!vec_components(obj, path, key, 3, v)) return false;
  out = {v[0], v[1], v[2]};
  return true;
}

namespace {

std::string min_max_reason(char axis, float min, float max) {
  return std::string("max.") + axis + " (" + Reader::fmt(max) + ") must be > min." + axis + " (" +
         Reader::fmt(min) + ")";
}

}  // namespace

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

}  // namespace foresight::scene_json
