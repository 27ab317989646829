#include "fighter_build/strike_annotation.hpp"

#include "io/json_reader.hpp"
#include "io/text_file.hpp"

#include <algorithm>

namespace foresight {
namespace {

using json = nlohmann::json;
using json_io::Reader;

constexpr int kMaxFrame = 10'000'000;
constexpr std::size_t kMaxStrikesPerClip = 4096;
constexpr std::uintmax_t kMaxSidecarBytes = 16u << 20;

bool read_enum_string(Reader& r, const json& obj, const std::string& path, std::string_view key,
                      bool required, std::string& out) {
  const json* j = nullptr;
  if (!r.member(obj, path, key, required, j)) return false;
  if (j == nullptr) return true;
  return r.string(*j, Reader::child(path, key), out);
}

bool read_strike(Reader& r, const json& j, const std::string& path, StrikeMark& out) {
  out = StrikeMark{};
  if (!r.require_object(j, path) ||
      !r.check_keys(j, path, {"hit_joint", "kind", "side", "height", "hit_frame", "start_frame", "end_frame"}))
    return false;
  if (!r.required_string(j, path, "hit_joint", out.hit_joint)) return false;
  if (out.hit_joint.empty()) return r.fail(Reader::child(path, "hit_joint"), "is empty");
  std::string text;
  if (!read_enum_string(r, j, path, "kind", true, text)) return false;
  if (!strike_kind_parse(text, out.kind))
    return r.fail(Reader::child(path, "kind"), "\"" + text + "\" is not \"punch\" or \"kick\"");
  if (!read_enum_string(r, j, path, "side", true, text)) return false;
  if (!strike_side_parse(text, out.side))
    return r.fail(Reader::child(path, "side"), "\"" + text + "\" is not \"left\" or \"right\"");
  text.clear();
  if (!read_enum_string(r, j, path, "height", false, text)) return false;
  if (!text.empty()) {
    StrikeHeight h{};
    if (!strike_height_parse(text, h))
      return r.fail(Reader::child(path, "height"), "\"" + text + "\" is not \"low\", \"mid\" or \"high\"");
    out.height = h;
  }
  const json* f = nullptr;
  if (!r.member(j, path, "hit_frame", true, f) ||
      !r.integer(*f, Reader::child(path, "hit_frame"), 0, kMaxFrame, out.hit_frame))
    return false;
  if (!r.member(j, path, "start_frame", false, f)) return false;
  if (f != nullptr && !r.integer(*f, Reader::child(path, "start_frame"), 0, kMaxFrame, out.start_frame))
    return false;
  if (!r.member(j, path, "end_frame", false, f)) return false;
  if (f != nullptr && !r.integer(*f, Reader::child(path, "end_frame"), 0, kMaxFrame, out.end_frame))
    return false;
  if (out.start_frame >= 0 && out.start_frame > out.hit_frame)
    return r.fail(Reader::child(path, "start_frame"), std::to_string(out.start_frame) +
                      " is after hit_frame " + std::to_string(out.hit_frame));
  if (out.end_frame >= 0 && out.end_frame < out.hit_frame)
    return r.fail(Reader::child(path, "end_frame"), std::to_string(out.end_frame) +
                      " is before hit_frame " + std::to_string(out.hit_frame));
  return true;
}

// The clip object; `extra` are the keys a per-clip file adds at its top level.
bool read_clip(Reader& r, const json& j, const std::string& path, std::string_view clip,
               std::initializer_list<std::string_view> keys, ClipStrikes& out) {
  out = ClipStrikes{};
  out.clip = std::string(clip);
  if (!r.require_object(j, path) || !r.check_keys(j, path, keys)) return false;
  const json* skip = nullptr;
  if (!r.member(j, path, "skip", false, skip)) return false;
  if (skip != nullptr) {
    if (!skip->is_boolean()) return r.fail(Reader::child(path, "skip"), "expected true or false, got " + json_describe(*skip));
    out.skip = skip->get<bool>();
  }
  return r.array_of(j, path, "strikes", kMaxStrikesPerClip, out.strikes, read_strike);
}

bool read_header(Reader& r, const json& j) {
  if (!r.require_object(j, "")) return false;
  std::string format;
  if (!r.required_string(j, "", "format", format)) return false;
  if (format != kStrikeSidecarFormat)
    return r.fail("format", "\"" + format + "\" is not \"" + std::string(kStrikeSidecarFormat) + "\"");
  const json* v = nullptr;
  int version = 0;
  if (!r.member(j, "", "version", true, v) || !r.integer(*v, "version", 0, 1'000'000, version)) return false;
  if (version != kStrikeSidecarVersion)
    return r.fail("version", "version " + std::to_string(version) + " is not supported (this build reads " +
                                 std::to_string(kStrikeSidecarVersion) + ")");
  return true;
}

json strike_to_json(const StrikeMark& m) {
  json s = json::object();
  s["hit_joint"] = m.hit_joint;
  s["kind"] = std::string(strike_kind_name(m.kind));
  s["side"] = std::string(strike_side_name(m.side));
  if (m.height) s["height"] = std::string(strike_height_name(*m.height));
  s["hit_frame"] = m.hit_frame;
  if (m.start_frame >= 0) s["start_frame"] = m.start_frame;
  if (m.end_frame >= 0) s["end_frame"] = m.end_frame;
  return s;
}

}  // namespace

const ClipStrikes* StrikeSidecar::find(std::string_view clip) const {
  for (const ClipStrikes& c : clips)
    if (c.clip == clip) return &c;
  return nullptr;
}

bool strike_sidecar_parse(std::string_view text, std::string_view source, StrikeSidecar& out,
                          std::string& error) {
  out = StrikeSidecar{};
  return json_io::guarded(source, "strike sidecar", error, [&] {
    json doc;
    if (!json_io::parse(text, source, doc, error)) return false;
    Reader r(source);
    if (!read_header(r, doc) || !r.check_keys(doc, "", {"format", "version", "clips"})) {
      error = r.error();
      return false;
    }
    const json* clips = nullptr;
    if (!r.member(doc, "", "clips", true, clips)) {
      error = r.error();
      return false;
    }
    if (!clips->is_object()) {
      r.fail("clips", "expected an object (clip file name -> strikes), got " + json_describe(*clips));
      error = r.error();
      return false;
    }
    for (auto it = clips->begin(); it != clips->end(); ++it) {
      if (!it.key().empty() && it.key()[0] == '_') continue;  // a comment
      ClipStrikes c;
      if (!read_clip(r, it.value(), Reader::child("clips", it.key()), it.key(), {"skip", "strikes"}, c)) {
        error = r.error();
        return false;
      }
      out.clips.push_back(std::move(c));
    }
    // nlohmann's objects iterate in key order already; sort anyway so find() and write() never
    // depend on that.
    std::sort(out.clips.begin(), out.clips.end(),
              [](const ClipStrikes& a, const ClipStrikes& b) { return a.clip < b.clip; });
    return true;
  });
}

bool strike_clip_sidecar_parse(std::string_view text, std::string_view source, std::string_view clip,
                               ClipStrikes& out, std::string& error) {
  out = ClipStrikes{};
  return json_io::guarded(source, "strike sidecar", error, [&] {
    json doc;
    if (!json_io::parse(text, source, doc, error)) return false;
    Reader r(source);
    if (!read_header(r, doc) || !read_clip(r, doc, "", clip, {"format", "version", "skip", "strikes"}, out)) {
      error = r.error();
      return false;
    }
    return true;
  });
}

bool strike_sidecar_load(const std::filesystem::path& path, StrikeSidecar& out, std::string& error) {
  std::string text;
  if (!text_file_read(path, kMaxSidecarBytes, text, error)) return false;
  return strike_sidecar_parse(text, path.string(), out, error);
}

bool strike_clip_sidecar_load(const std::filesystem::path& path, std::string_view clip, ClipStrikes& out,
                              std::string& error) {
  std::string text;
  if (!text_file_read(path, kMaxSidecarBytes, text, error)) return false;
  return strike_clip_sidecar_parse(text, path.string(), clip, out, error);
}

bool strike_marks_check(const ClipStrikes& marks, const Skeleton& skeleton, int num_frames,
                        std::string_view source, std::string& error) {
  for (std::size_t i = 0; i < marks.strikes.size(); ++i) {
    const StrikeMark& m = marks.strikes[i];
    const std::string where = std::string(source) + ": " + marks.clip + ": strikes[" + std::to_string(i) + "]";
    const int joint = skeleton.find_joint(m.hit_joint);
    if (joint < 0 || skeleton.is_end_site[static_cast<std::size_t>(joint)]) {
      error = where + ".hit_joint: no joint \"" + m.hit_joint + "\" in the clip's skeleton";
      return false;
    }
    const auto check_frame = [&](const char* field, int frame) {
      if (frame < num_frames) return true;
      error = where + "." + field + ": " + std::to_string(frame) + " is out of range: the clip has " +
              std::to_string(num_frames) + " frames (0.." + std::to_string(num_frames - 1) + ")";
      return false;
    };
    if (!check_frame("hit_frame", m.hit_frame) || !check_frame("start_frame", m.start_frame) ||
        !check_frame("end_frame", m.end_frame))
      return false;
  }
  return true;
}

std::string strike_sidecar_write(const StrikeSidecar& sidecar) {
  json doc = json::object();
  doc["format"] = std::string(kStrikeSidecarFormat);
  doc["version"] = kStrikeSidecarVersion;
  json clips = json::object();
  for (const ClipStrikes& c : sidecar.clips) {
    json o = json::object();
    if (c.skip) o["skip"] = true;
    if (!c.strikes.empty() || !c.skip) {
      json list = json::array();
      for (const StrikeMark& m : c.strikes) list.push_back(strike_to_json(m));
      o["strikes"] = std::move(list);
    }
    clips[c.clip] = std::move(o);
  }
  doc["clips"] = std::move(clips);
  return doc.dump(2) + "\n";
}

bool strike_sidecar_save(const std::filesystem::path& path, const StrikeSidecar& sidecar, std::string& error) {
  return file_write_atomic(path, strike_sidecar_write(sidecar), error);
}

}  // namespace foresight
