#include "scripted/recording.hpp"

#include "io/json_describe.hpp"
#include "io/json_reader.hpp"
#include "io/text_file.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

namespace foresight {
namespace {

using json = nlohmann::json;

// Samples are converted as the parser meets them and then dropped from the DOM (see
// parse_impl), so memory stays proportional to the samples kept, not to nlohmann's tree. This
// caps the values anywhere else in the file (a sample has 11 parse events).
constexpr std::size_t kMaxParseEvents = 16 * kMaxRecordingSamples + 4096;
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr double kMaxAngle_deg = 1.0e6;

// ---------------------------------------------------------------- numbers written

// The one conversion from file degrees to stored radians; the writer searches for the shortest
// text that this maps back onto the stored value.
float rad_from_deg(double deg) { return static_cast<float>(deg * kDegToRad); }

// nlohmann writes a double as the shortest text that parses back to it. A float widened to double
// would print all its binary digits (0.7071067690849304), so the writer hands over the double
// nearest to the float's own shortest text (0.70710677), checked against the parse path (text ->
// double -> float): if double rounding ever differed from the float's, the exact widened value.
// Whole numbers go out as integers ("45", where nlohmann would write 45.0), except -0, whose sign
// a direction's atan2 would see.
json double_json(double v) {
  if (!std::isfinite(v)) return nullptr;
  if (v == std::trunc(v) && std::fabs(v) < 9.0e15 && !(v == 0.0 && std::signbit(v))) return static_cast<int64_t>(v);
  return v;
}

json float_json(float v) {
  if (!std::isfinite(v)) return nullptr;
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  const double shortest = std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
  return double_json(static_cast<float>(shortest) == v ? shortest : static_cast<double>(v));
}

std::string number_text(double v) { return double_json(v).dump(); }

// The angle in degrees with the fewest decimals (0..9) whose parse gives back exactly `rad`,
// else the exact double (within 1e-16 of the float's value, far inside half a float ulp, so it
// always maps back).
json degrees_json(float rad) {
  if (!std::isfinite(rad)) return nullptr;
  const double deg = static_cast<double>(rad) / kDegToRad;
  double scale = 1.0;
  for (int decimals = 0; decimals <= 9; ++decimals, scale *= 10.0) {
    const double candidate = std::round(deg * scale) / scale;
    if (rad_from_deg(candidate) == rad) return double_json(candidate);
  }
  return double_json(deg);
}

// ---------------------------------------------------------------- reading


using json_io::Reader;

// One sample; `previous_t` is the last accepted sample's time (< 0 for the first).
bool read_sample(Reader& r, const json& j, std::size_t index, double previous_t, CommandSample& out) {
  constexpr Reader::Null kNull = Reader::Null::value;  // a null value is a type error
  const std::string path = Reader::index("samples", index);
  if (!r.require_object(j, path)) return false;
  if (!r.check_keys(j, path, {"t", "dir", "camera_yaw_deg", "camera_pos", "crouch"})) return false;
  const json* v = nullptr;
  if (!r.member(j, path, "t", true, v, kNull) ||
      !r.number(*v, Reader::child(path, "t"), 0.0, kMaxRecordingTime_s, out.t_s))
    return false;
  if (previous_t < 0 && out.t_s != 0.0)
    return r.fail(Reader::child(path, "t"),
                  "the first sample must be at t = 0, got " + number_text(out.t_s));
  if (previous_t >= 0 && !(out.t_s > previous_t))
    return r.fail(Reader::child(path, "t"),
                  number_text(out.t_s) + (out.t_s == previous_t ? " repeats" : " is before") +
                      " the previous sample's t (" + number_text(previous_t) +
                      "): times must increase strictly");
  constexpr auto kInReason = Reader::Component::in_reason;
  float dir[2] = {0, 0};
  if (!r.member(j, path, "dir", true, v, kNull) ||
      !r.numbers(*v, Reader::child(path, "dir"), 2, 1e6, "[x, y]", dir, kInReason))
    return false;
  out.input.camera_dir = vec2(dir[0], dir[1]);
  // The same test the avatar applies (control_input_valid), so every parsed sample is accepted.
  if (!(glm::dot(out.input.camera_dir, out.input.camera_dir) <= 1.0001f))
    return r.fail(Reader::child(path, "dir"),
                  "length " + float_json(glm::length(out.input.camera_dir)).dump() + " is more than 1");
  double yaw_deg = 0;
  if (!r.member(j, path, "camera_yaw_deg", true, v, kNull) ||
      !r.number(*v, Reader::child(path, "camera_yaw_deg"), -kMaxAngle_deg, kMaxAngle_deg, yaw_deg))
    return false;
  out.input.camera_yaw_rad = rad_from_deg(yaw_deg);
  out.camera_pos_m = vec3(0.0f);
  if (!r.member(j, path, "camera_pos", false, v, kNull)) return false;
  if (v != nullptr && !r.numbers(*v, Reader::child(path, "camera_pos"), 3, kMaxRecordingCoord_m,
                                 "[x, y, z]", &out.camera_pos_m.x, kInReason))
    return false;
  out.input.crouch = false;
  if (!r.member(j, path, "crouch", false, v, kNull)) return false;
  if (v != nullptr) {
    if (!v->is_boolean())
      return r.fail(Reader::child(path, "crouch"), "expected true or false, got " + json_describe(*v));
    out.input.crouch = v->get<bool>();
  }
  return true;
}

bool read_header(Reader& r, const json& root) {
  constexpr Reader::Null kNull = Reader::Null::value;
  if (!r.require_object(root, "")) return false;
  const json* v = nullptr;
  std::string format;
  if (!r.member(root, "", "format", true, v, kNull) || !r.string(*v, "format", format)) return false;
  if (format != kRecordingFormat)
    return r.fail("format", "expected \"" + std::string(kRecordingFormat) + "\", got \"" + format + "\"");
  if (!r.member(root, "", "version", true, v, kNull)) return false;
  if (!v->is_number_integer() && !v->is_number_unsigned())
    return r.fail("version", "expected an integer, got " + json_describe(*v));
  if (v->get<double>() != kRecordingVersion)
    return r.fail("version", "unsupported version " + number_text(v->get<double>()) +
                                 " (this build reads version " + std::to_string(kRecordingVersion) + ")");
  return true;
}

// A ground point "<object>.pos": [x, z].
bool read_ground_pos(Reader& r, const json& obj, const std::string& path, vec2& out) {
  const json* v = nullptr;
  return r.member(obj, path, "pos", true, v, Reader::Null::value) &&
         r.numbers(*v, Reader::child(path, "pos"), 2, kMaxRecordingCoord_m, "[x, z]", &out.x,
                   Reader::Component::in_reason);
}

bool read_body(Reader& r, const json& root, Recording& rec) {
  constexpr Reader::Null kNull = Reader::Null::value;
  if (!r.check_keys(root, "", {"format", "version", "scene", "name", "library_hash", "start", "goal", "samples"}))
    return false;
  const json* v = nullptr;
  if (!r.member(root, "", "library_hash", false, v, kNull)) return false;
  if (v != nullptr) {
    std::string hex;
    if (!r.string(*v, "library_hash", hex)) return false;
    const auto res = std::from_chars(hex.data(), hex.data() + hex.size(), rec.library_hash, 16);
    if (hex.empty() || hex.size() > 16 || res.ec != std::errc() || res.ptr != hex.data() + hex.size())
      return r.fail("library_hash", "expected 1 to 16 hexadecimal digits, got \"" + hex + "\"");
  }
  if (!r.member(root, "", "scene", true, v, kNull) || !r.string(*v, "scene", rec.scene)) return false;
  if (rec.scene.empty()) return r.fail("scene", "must not be empty");
  if (!r.member(root, "", "name", false, v, kNull)) return false;
  if (v != nullptr && !r.string(*v, "name", rec.name)) return false;

  const json* start = nullptr;
  if (!r.member(root, "", "start", true, start, kNull) || !r.require_object(*start, "start") ||
      !r.check_keys(*start, "start", {"pos", "heading_deg"}))
    return false;
  double heading_deg = 0;
  if (!read_ground_pos(r, *start, "start", rec.start_pos_m) ||
      !r.member(*start, "start", "heading_deg", true, v, kNull) ||
      !r.number(*v, "start.heading_deg", -kMaxAngle_deg, kMaxAngle_deg, heading_deg))
    return false;
  rec.start_heading_rad = rad_from_deg(heading_deg);

  const json* goal = nullptr;
  if (!r.member(root, "", "goal", true, goal, kNull) || !r.require_object(*goal, "goal") ||
      !r.check_keys(*goal, "goal", {"pos", "radius"}))
    return false;
  if (!read_ground_pos(r, *goal, "goal", rec.goal_pos_m) ||
      !r.member(*goal, "goal", "radius", false, v, kNull))
    return false;
  double radius = 0;
  if (v != nullptr) {
    if (!r.number(*v, "goal.radius", 1e-3, 1000.0, radius)) return false;
    rec.goal_radius_m = static_cast<float>(radius);
  }
  return true;
}

bool parse_impl(std::string_view text, std::string_view source, Recording& out, std::string& error) {
  if (text.size() > kMaxRecordingFileBytes) {
    error = std::string(source) + ": text is " + std::to_string(text.size()) + " bytes, more than the " +
            std::to_string(kMaxRecordingFileBytes) + " allowed";
    return false;
  }
  Recording rec;
  Reader samples_reader(source);  // the first sample error, reported after the header checks
  std::string top_key;
  int samples_keys = 0;
  bool samples_is_array = false;
  bool too_many_events = false, too_many_samples = false;
  std::size_t events = 0;
  std::size_t sample_index = 0;

  // Samples (depth 2 inside the top-level "samples" array) are read and validated as soon as
  // each one is complete, then discarded from the DOM.
  const json::parser_callback_t callback = [&](int depth, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::key) {
      if (depth == 1) {
        top_key = parsed.get<std::string>();
        if (top_key == "samples") ++samples_keys;
      }
      return !too_many_events;
    }
    if (event == json::parse_event_t::array_start && depth == 1 && top_key == "samples")
      samples_is_array = true;
    if (event == json::parse_event_t::value || event == json::parse_event_t::object_end ||
        event == json::parse_event_t::array_end)
      if (++events > kMaxParseEvents) too_many_events = true;
    if (too_many_events) return false;
    const bool in_samples = depth == 2 && top_key == "samples" && samples_is_array && samples_keys == 1;
    const bool element_end = event == json::parse_event_t::object_end ||
                             event == json::parse_event_t::array_end ||
                             event == json::parse_event_t::value;
    if (!in_samples || !element_end) return true;
    const std::size_t index = sample_index++;
    if (samples_reader.failed()) return false;
    if (rec.samples.size() >= kMaxRecordingSamples) {
      too_many_samples = true;
      return false;
    }
    CommandSample s;
    const double previous = rec.samples.empty() ? -1.0 : rec.samples.back().t_s;
    if (read_sample(samples_reader, parsed, index, previous, s)) rec.samples.push_back(s);
    return false;
  };

  json root;
  if (!json_io::parse(text, source, root, error, callback)) return false;
  if (too_many_events) {
    error = std::string(source) + ": more than " + std::to_string(kMaxParseEvents) + " JSON values";
    return false;
  }
  Reader r(source);
  if (!read_header(r, root)) {
    error = r.error();
    return false;
  }
  if (samples_keys > 1) {
    error = std::string(source) + ": samples: appears more than once";
    return false;
  }
  if (samples_reader.failed()) {
    error = samples_reader.error();
    return false;
  }
  if (too_many_samples) {
    error = std::string(source) + ": samples: more than the " + std::to_string(kMaxRecordingSamples) +
            " samples allowed";
    return false;
  }
  if (!read_body(r, root, rec)) {
    error = r.error();
    return false;
  }
  const json* samples = nullptr;
  if (!r.member(root, "", "samples", true, samples, Reader::Null::value)) {
    error = r.error();
    return false;
  }
  if (!samples_is_array) {
    r.fail("samples", "expected an array, got " + json_describe(*samples));
    error = r.error();
    return false;
  }
  if (rec.samples.empty()) {
    error = std::string(source) + ": samples: needs at least one sample";
    return false;
  }
  out = std::move(rec);
  return true;
}

}  // namespace

bool recording_parse(std::string_view json_text, std::string_view source_name, Recording& recording,
                     std::string& error) {
  return json_io::guarded(source_name, "recording", error, [&] {
    return parse_impl(json_text, source_name, recording, error);
  });
}

bool recording_load(const std::filesystem::path& path, Recording& recording, std::string& error) {
  std::string text;
  return text_file_read(path, kMaxRecordingFileBytes, text, error) &&
         recording_parse(text, path.filename().string(), recording, error);
}

std::string recording_write(const Recording& rec) {
  // Every value is written by nlohmann (numbers, strings and their escapes); the layout is a key
  // per line and a sample per line, so a changed recording diffs line by line.
  using ojson = nlohmann::ordered_json;
  ojson head;
  head["format"] = kRecordingFormat;
  head["version"] = kRecordingVersion;
  head["scene"] = rec.scene;
  head["name"] = rec.name;
  if (rec.library_hash != 0) {
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(rec.library_hash));
    head["library_hash"] = hex;
  }
  head["start"] = {{"pos", {float_json(rec.start_pos_m.x), float_json(rec.start_pos_m.y)}},
                   {"heading_deg", degrees_json(rec.start_heading_rad)}};
  head["goal"] = {{"pos", {float_json(rec.goal_pos_m.x), float_json(rec.goal_pos_m.y)}},
                  {"radius", float_json(rec.goal_radius_m)}};
  const auto dump = [](const ojson& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); };
  std::string s = "{\n";
  for (const auto& [key, value] : head.items()) s += "  " + dump(key) + ": " + dump(value) + ",\n";
  s += "  \"samples\": [";
  for (std::size_t i = 0; i < rec.samples.size(); ++i) {
    const CommandSample& c = rec.samples[i];
    const ojson sample = {
        {"t", double_json(c.t_s)},
        {"dir", {float_json(c.input.camera_dir.x), float_json(c.input.camera_dir.y)}},
        {"camera_yaw_deg", degrees_json(c.input.camera_yaw_rad)},
        {"camera_pos", {float_json(c.camera_pos_m.x), float_json(c.camera_pos_m.y), float_json(c.camera_pos_m.z)}},
        {"crouch", c.input.crouch}};
    s += (i == 0 ? "\n    " : ",\n    ") + dump(sample);
  }
  s += rec.samples.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return s;
}

bool recording_save(const std::filesystem::path& path, const Recording& recording, std::string& error) {
  std::string text;
  try {
    text = recording_write(recording);
  } catch (const std::exception& e) {
    error = path.string() + ": " + e.what();
    return false;
  }
  return file_write_atomic(path, text, error);
}

ControlInput recording_input_at(const Recording& recording, double t_s) {
  const auto& s = recording.samples;
  // First sample with t_s > t; the one before it holds.
  const auto it = std::upper_bound(s.begin(), s.end(), t_s,
                                   [](double t, const CommandSample& c) { return t < c.t_s; });
  if (it == s.begin()) return ControlInput{};
  return std::prev(it)->input;
}

}  // namespace foresight
