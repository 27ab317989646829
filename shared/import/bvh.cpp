#include "import/bvh.hpp"

#include "io/text_file.hpp"

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <system_error>

namespace foresight {
namespace {

constexpr std::string_view kChannelNames[] = {"Xposition", "Yposition", "Zposition",
                                              "Xrotation", "Yrotation", "Zrotation"};
// Big enough for any real capture, small enough that reading it cannot exhaust memory.
constexpr std::uintmax_t kMaxFileBytes = 1u << 30;

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
bool is_line_end(char c) { return c == '\n' || c == '\r'; }

char lower_ascii(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (lower_ascii(a[i]) != lower_ascii(b[i])) return false;
  return true;
}

bool istarts_with(std::string_view s, std::string_view prefix) {
  return s.size() >= prefix.size() && iequals(s.substr(0, prefix.size()), prefix);
}

// A token for an error message: quoted, shortened, control bytes shown as '?', so a binary file
// cannot flood or garble the message.
std::string quoted(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < kMax; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c < 0x20 || c == 0x7f) ? '?' : static_cast<char>(c);
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

enum class NumberStatus { kOk, kNotNumber, kNotFinite, kOutOfRange };

// std::from_chars plus what BVH exporters write that it refuses: a leading '+', and values that
// underflow a float (from_chars reports those as out of range; they are just tiny).
NumberStatus parse_float(const char* first, const char* last, float& value, const char*& next) {
  if (first != last && *first == '+') {
    ++first;
    if (first != last && *first == '-') return NumberStatus::kNotNumber;
  }
  auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range) {
    double d = 0.0;
    auto [dptr, dec] = std::from_chars(first, last, d);
    ptr = dptr;
    if (dec == std::errc()) {
      if (!(std::fabs(d) <= static_cast<double>(FLT_MAX))) return NumberStatus::kOutOfRange;
      value = static_cast<float>(d);
    } else if (dec == std::errc::result_out_of_range) {
      // Beyond double too: only a negative exponent (underflow to zero) is acceptable.
      const std::string_view text(first, static_cast<size_t>(dptr - first));
      const size_t e = text.find_first_of("eE");
      if (e == std::string_view::npos || e + 1 >= text.size() || text[e + 1] != '-')
        return NumberStatus::kOutOfRange;
      value = text[0] == '-' ? -0.0f : 0.0f;
    } else {
      return NumberStatus::kNotNumber;
    }
  } else if (ec != std::errc()) {
    return NumberStatus::kNotNumber;
  }
  if (!std::isfinite(value)) return NumberStatus::kNotFinite;
  next = ptr;
  return NumberStatus::kOk;
}

struct Token {
  std::string_view text;  // empty at the end of the file (or of the line, for next_on_line)
  int line = 0;
};

// A cursor over the text that counts lines. LF, CRLF and lone CR all end a line.
class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {
    if (text_.starts_with("\xEF\xBB\xBF")) pos_ = 3;
  }

  int line() const { return line_; }
  size_t remaining() const { return text_.size() - pos_; }
  bool at_end() const { return pos_ >= text_.size(); }

  void skip_blanks() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) ++pos_;
  }
  // After skip_blanks: true at a line end or the end of the text.
  bool at_line_end() const { return pos_ >= text_.size() || is_line_end(text_[pos_]); }

  // The next whitespace-separated token, crossing lines.
  Token next() {
    for (;;) {
      skip_blanks();
      if (at_end()) return {{}, line_};
      if (!is_line_end(text_[pos_])) break;
      consume_line_end();
    }
    return read_token();
  }
  // The next token on the current line; empty at its end.
  Token next_on_line() {
    skip_blanks();
    if (at_line_end()) return {{}, line_};
    return read_token();
  }
  // The rest of the current line without surrounding blanks (the line end is not consumed).
  std::string_view rest_of_line() {
    skip_blanks();
    const size_t start = pos_;
    while (pos_ < text_.size() && !is_line_end(text_[pos_])) ++pos_;
    size_t end = pos_;
    while (end > start && is_blank(text_[end - 1])) --end;
    return text_.substr(start, end - start);
  }
  // Moves to the start of the next line holding something; false at the end of the text.
  bool next_nonblank_line() {
    for (;;) {
      skip_blanks();
      if (at_end()) return false;
      if (!is_line_end(text_[pos_])) return true;
      consume_line_end();
    }
  }
  // Reads a number at the cursor (after skip_blanks) that must end at a blank or line end.
  NumberStatus read_float(float& value) {
    const char* first = text_.data() + pos_;
    const char* last = text_.data() + text_.size();
    const char* next = first;
    const NumberStatus status = parse_float(first, last, value, next);
    if (status != NumberStatus::kOk) return status;
    if (next != last && !is_blank(*next) && !is_line_end(*next)) return NumberStatus::kNotNumber;
    pos_ = static_cast<size_t>(next - text_.data());
    return NumberStatus::kOk;
  }
  // The token at the cursor without consuming it (for error messages).
  std::string_view peek_token() const {
    size_t end = pos_;
    while (end < text_.size() && !is_blank(text_[end]) && !is_line_end(text_[end])) ++end;
    return text_.substr(pos_, end - pos_);
  }

 private:
  void consume_line_end() {
    if (text_[pos_] == '\r' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '\n') ++pos_;
    ++pos_;
    ++line_;
  }
  Token read_token() {
    const size_t start = pos_;
    while (pos_ < text_.size() && !is_blank(text_[pos_]) && !is_line_end(text_[pos_])) ++pos_;
    return {text_.substr(start, pos_ - start), line_};
  }

  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 1;
};

std::string describe(const Token& t, bool on_line) {
  if (!t.text.empty()) return quoted(t.text);
  return on_line ? "end of line" : "end of file";
}

class Parser {
 public:
  Parser(std::string_view text, std::string_view source, BvhDocument& out, std::string& error)
      : lex_(text), source_(source.empty() ? std::string_view("bvh") : source), doc_(out),
        error_(error) {}

  bool run() {
    doc_ = BvhDocument{};
    return parse_hierarchy() && parse_motion_header() && parse_motion();
  }

 private:
  bool fail(int line, const std::string& what) {
    error_ = std::string(source_) + ":" + std::to_string(line) + ": " + what;
    return false;
  }

  bool parse_hierarchy() {
    Token t = lex_.next();
    if (t.text.empty()) return fail(t.line, "expected 'HIERARCHY', got an empty file");
    if (!iequals(t.text, "HIERARCHY"))
      return fail(t.line, "expected 'HIERARCHY', got " + describe(t, false));
    t = lex_.next();
    if (!iequals(t.text, "ROOT"))
      return fail(t.line, "expected 'ROOT' after HIERARCHY, got " + describe(t, false));
    if (!parse_joint_header(-1, "ROOT")) return false;
    // Open joints, innermost last: an explicit stack so deep nesting cannot overflow the call
    // stack.
    std::vector<int> open{0};
    while (!open.empty()) {
      t = lex_.next();
      if (t.text == "}") {
        open.pop_back();
      } else if (iequals(t.text, "JOINT")) {
        if (!parse_joint_header(open.back(), "JOINT")) return false;
        open.push_back(static_cast<int>(doc_.joints.size()) - 1);
      } else if (iequals(t.text, "End")) {
        if (!parse_end_site(open.back())) return false;
      } else if (t.text.empty()) {
        return fail(t.line, "unexpected end of file inside joint '" +
                                doc_.joints[open.back()].name + "': " +
                                std::to_string(open.size()) + " '}' missing (unbalanced braces)");
      } else {
        return fail(t.line, "expected 'JOINT', 'End Site' or '}' in joint '" +
                                doc_.joints[open.back()].name + "', got " + describe(t, false));
      }
    }
    return true;
  }

  bool add_joint(int line, BvhJoint joint) {
    if (static_cast<int>(doc_.joints.size()) >= kBvhMaxJoints)
      return fail(line, "too many joints (the limit is " + std::to_string(kBvhMaxJoints) + ")");
    doc_.joints.push_back(std::move(joint));
    return true;
  }

  // After ROOT/JOINT: "<name> [{]", "{", OFFSET, optional CHANNELS.
  bool parse_joint_header(int parent, std::string_view keyword) {
    const int name_line = lex_.line();
    std::string_view name = lex_.rest_of_line();
    bool brace = false;
    // "JOINT Hips {" on one line: the brace is not part of the name.
    if (name.ends_with("{") && (name.size() == 1 || is_blank(name[name.size() - 2]))) {
      brace = true;
      name.remove_suffix(1);
      while (!name.empty() && is_blank(name.back())) name.remove_suffix(1);
    }
    if (name.empty())
      return fail(name_line, "expected a joint name after " + std::string(keyword) +
                                 ", got end of line");
    // Braces inside a name would make the written file ambiguous; no exporter produces them.
    if (name.find_first_of("{}") != std::string_view::npos)
      return fail(name_line, "expected a joint name without braces after " +
                                 std::string(keyword) + ", got " + quoted(name));
    BvhJoint joint;
    joint.name = std::string(name);
    joint.parent = parent;
    if (!brace) {
      const Token t = lex_.next();
      if (t.text != "{")
        return fail(t.line, "expected '{' after " + std::string(keyword) + " name, got " +
                                describe(t, false));
    }
    if (!parse_offset(joint.name, joint.offset)) return false;
    Lexer peek = lex_;
    if (iequals(peek.next().text, "CHANNELS")) {
      lex_ = peek;
      if (!parse_channels(joint)) return false;
    }
    return add_joint(name_line, std::move(joint));
  }

  // "End Site { OFFSET x y z }" ("End" already read).
  bool parse_end_site(int parent) {
    Token t = lex_.next_on_line();
    if (!iequals(t.text, "Site"))
      return fail(t.line, "expected 'Site' after 'End', got " + describe(t, true));
    const int line = t.line;
    t = lex_.next();
    if (t.text != "{") return fail(t.line, "expected '{' after End Site, got " + describe(t, false));
    BvhJoint joint;
    joint.name = doc_.joints[parent].name + "_End";
    joint.parent = parent;
    joint.end_site = true;
    if (!parse_offset("End Site", joint.offset)) return false;
    t = lex_.next();
    if (t.text != "}")
      return fail(t.line, "expected '}' closing End Site, got " + describe(t, false));
    return add_joint(line, std::move(joint));
  }

  bool parse_offset(const std::string& owner, vec3& offset) {
    const Token t = lex_.next();
    if (!iequals(t.text, "OFFSET"))
      return fail(t.line, "expected 'OFFSET' in '" + owner + "', got " + describe(t, false));
    for (int axis = 0; axis < 3; ++axis) {
      if (!read_number_on_line(t.line, "OFFSET value", offset[axis])) return false;
    }
    return expect_line_end(t.line, "after the 3 OFFSET values");
  }

  bool parse_channels(BvhJoint& joint) {
    const Token count_token = lex_.next_on_line();
    const int line = count_token.line;
    int count = -1;
    const char* end = count_token.text.data() + count_token.text.size();
    auto [ptr, ec] = std::from_chars(count_token.text.data(), end, count);
    if (count_token.text.empty() || ec != std::errc() || ptr != end || count < 0 ||
        count > kBvhMaxChannelsPerJoint)
      return fail(line, "expected a channel count 0.." + std::to_string(kBvhMaxChannelsPerJoint) +
                            " after CHANNELS, got " + describe(count_token, true));
    for (int i = 0; i < count; ++i) {
      const Token t = lex_.next_on_line();
      if (t.text.empty())
        return fail(line, "CHANNELS declares " + std::to_string(count) + " channels but lists " +
                              std::to_string(i));
      int kind = -1;
      for (int k = 0; k < 6; ++k)
        if (iequals(t.text, kChannelNames[k])) kind = k;
      if (kind < 0)
        return fail(line, "expected a channel name (Xposition, Yposition, Zposition, Xrotation, "
                          "Yrotation, Zrotation), got " + quoted(t.text));
      const BvhChannel channel = static_cast<BvhChannel>(kind);
      if (std::find(joint.channels.begin(), joint.channels.end(), channel) != joint.channels.end())
        return fail(line, "channel " + quoted(t.text) + " listed twice in joint '" + joint.name +
                              "'");
      joint.channels.push_back(channel);
    }
    const Token extra = lex_.next_on_line();
    if (!extra.text.empty())
      return fail(line, "CHANNELS declares " + std::to_string(count) +
                            " channels but lists more: " + quoted(extra.text));
    return true;
  }

  bool parse_motion_header() {
    Token t = lex_.next();
    if (!iequals(t.text, "MOTION")) {
      if (t.text == "}") return fail(t.line, "'}' without a matching '{' (unbalanced braces)");
      if (iequals(t.text, "ROOT")) return fail(t.line, "only one ROOT is supported");
      return fail(t.line, "expected 'MOTION' after the hierarchy, got " + describe(t, false));
    }
    // "Frames:" then the count, with or without blanks between.
    t = lex_.next();
    if (!istarts_with(t.text, "Frames:"))
      return fail(t.line, "expected 'Frames:' after MOTION, got " + describe(t, false));
    const int frames_line = t.line;
    Token count = {t.text.substr(7), t.line};
    if (count.text.empty()) count = lex_.next_on_line();
    int64_t frames = -1;
    {
      const char* end = count.text.data() + count.text.size();
      auto [ptr, ec] = std::from_chars(count.text.data(), end, frames);
      if (count.text.empty() || ec != std::errc() || ptr != end || frames < 0 ||
          frames > std::numeric_limits<int>::max())
        return fail(frames_line, "expected a frame count 0.." +
                                     std::to_string(std::numeric_limits<int>::max()) +
                                     " after 'Frames:', got " + describe(count, true));
    }
    if (!expect_line_end(frames_line, "after the frame count")) return false;

    // "Frame Time:" then seconds.
    t = lex_.next();
    const int time_line = t.line;
    Token seconds{{}, t.line};
    if (istarts_with(t.text, "FrameTime:")) {
      seconds.text = t.text.substr(10);
    } else if (iequals(t.text, "Frame")) {
      const Token t2 = lex_.next_on_line();
      if (!istarts_with(t2.text, "Time:"))
        return fail(time_line, "expected 'Frame Time:' after the frame count, got " +
                                   describe(t2, true));
      seconds.text = t2.text.substr(5);
    } else {
      return fail(time_line, "expected 'Frame Time:' after the frame count, got " +
                                 describe(t, false));
    }
    if (seconds.text.empty()) seconds = lex_.next_on_line();
    double frame_time = 0.0;
    const char* end = seconds.text.data() + seconds.text.size();
    auto [ptr, ec] = std::from_chars(seconds.text.data(), end, frame_time);
    if (seconds.text.empty() || ec != std::errc() || ptr != end || !std::isfinite(frame_time) ||
        frame_time <= 0.0)
      return fail(time_line, "expected a frame time in seconds > 0 after 'Frame Time:', got " +
                                 describe(seconds, true));
    if (!expect_line_end(time_line, "after the frame time")) return false;

    if (doc_.num_channels() == 0) return fail(frames_line, "the hierarchy declares no channels");
    doc_.num_frames = static_cast<int>(frames);
    doc_.frame_time_s = frame_time;
    return true;
  }

  bool parse_motion() {
    const int channels = doc_.num_channels();
    const int frames = doc_.num_frames;
    // Every value takes at least 2 bytes (a digit and a separator), so never reserve more than
    // the rest of the text can hold: a hostile or truncated header cannot make us allocate, and
    // the loop below still reports exactly where the text runs out.
    const size_t can_hold = (lex_.remaining() + 1) / 2;
    const size_t declared = static_cast<size_t>(frames) * static_cast<size_t>(channels);
    doc_.values.reserve(std::min(declared, can_hold));
    for (int f = 0; f < frames; ++f) {
      if (!lex_.next_nonblank_line())
        return fail(lex_.line(), "expected motion line " + std::to_string(f + 1) + " of " +
                                     std::to_string(frames) + ", got end of file (truncated?)");
      const int line = lex_.line();
      for (int c = 0; c < channels; ++c) {
        lex_.skip_blanks();
        if (lex_.at_line_end())
          return fail(line, "expected " + std::to_string(channels) + " values on motion line " +
                                std::to_string(f + 1) + ", got " + std::to_string(c));
        float value = 0.0f;
        const NumberStatus status = lex_.read_float(value);
        if (status != NumberStatus::kOk) return number_error(line, status, lex_.peek_token());
        doc_.values.push_back(value);
      }
      lex_.skip_blanks();
      if (!lex_.at_line_end())
        return fail(line, "expected " + std::to_string(channels) + " values on motion line " +
                              std::to_string(f + 1) + ", got more: " +
                              quoted(lex_.peek_token()));
    }
    if (lex_.next_nonblank_line())
      return fail(lex_.line(), "unexpected " + quoted(lex_.peek_token()) + " after the last of " +
                                   std::to_string(frames) + " frames");
    return true;
  }

  bool read_number_on_line(int line, std::string_view what, float& value) {
    lex_.skip_blanks();
    if (lex_.at_line_end())
      return fail(line, "expected " + std::string(what) + ", got end of line");
    const NumberStatus status = lex_.read_float(value);
    if (status != NumberStatus::kOk) return number_error(line, status, lex_.peek_token());
    return true;
  }

  bool number_error(int line, NumberStatus status, std::string_view token) {
    switch (status) {
      case NumberStatus::kNotFinite:
        return fail(line, "expected a finite number, got " + quoted(token));
      case NumberStatus::kOutOfRange:
        return fail(line, "number out of float range: " + quoted(token));
      default:
        return fail(line, "expected a number, got " + quoted(token));
    }
  }

  bool expect_line_end(int line, std::string_view where) {
    const Token t = lex_.next_on_line();
    if (t.text.empty()) return true;
    return fail(line, "unexpected " + quoted(t.text) + " " + std::string(where));
  }

  Lexer lex_;
  std::string_view source_;
  BvhDocument& doc_;
  std::string& error_;
};

void append_float(std::string& s, float v) {
  char buf[32];
  // Shortest representation that reads back to the same float: writing then parsing is exact.
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  s.append(buf, ec == std::errc() ? ptr : buf);
}

void append_double(std::string& s, double v) {
  char buf[40];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  s.append(buf, ec == std::errc() ? ptr : buf);
}

bool valid_name(std::string_view name) {
  if (name.empty() || is_blank(name.front()) || is_blank(name.back())) return false;
  return name.find_first_of("{}\r\n") == std::string_view::npos;
}

}  // namespace

std::string_view bvh_channel_name(BvhChannel channel) {
  const auto i = static_cast<size_t>(channel);
  return i < 6 ? kChannelNames[i] : std::string_view("?");
}

int BvhDocument::num_channels() const {
  int n = 0;
  for (const BvhJoint& j : joints) n += static_cast<int>(j.channels.size());
  return n;
}

int BvhDocument::channel_offset(int joint) const {
  int n = 0;
  for (int j = 0; j < joint && j < static_cast<int>(joints.size()); ++j)
    n += static_cast<int>(joints[j].channels.size());
  return n;
}

bool bvh_parse(std::string_view text, std::string_view source_name, BvhDocument& out,
               std::string& error) {
  try {
    return Parser(text, source_name, out, error).run();
  } catch (const std::exception& e) {  // bad_alloc only: every size is checked beforehand
    error = std::string(source_name) + ": " + e.what();
    return false;
  }
}

bool bvh_load(const std::filesystem::path& path, BvhDocument& out, std::string& error) {
  std::string text;
  return text_file_read(path, kMaxFileBytes, text, error) &&
         bvh_parse(text, path.string(), out, error);
}

bool bvh_validate(const BvhDocument& doc, std::string& error) {
  const int n = static_cast<int>(doc.joints.size());
  if (n == 0) return error = "BVH document has no joints", false;
  if (n > kBvhMaxJoints) return error = "BVH document has more than 1024 joints", false;
  // Ancestors still open while walking the joints in order: a parent must be one of them,
  // otherwise the file order would not be depth-first and could not be written as nesting.
  std::vector<int> open;
  for (int i = 0; i < n; ++i) {
    const BvhJoint& j = doc.joints[i];
    const std::string at = "BVH joint " + std::to_string(i) + " ('" + j.name + "'): ";
    if (i == 0 && (j.parent != -1 || j.end_site))
      return error = at + "joint 0 must be the ROOT (parent -1, not an End Site)", false;
    if (i > 0) {
      if (j.parent < 0 || j.parent >= i) return error = at + "parent must be in [0, index)", false;
      if (doc.joints[j.parent].end_site) return error = at + "parent is an End Site", false;
      while (!open.empty() && open.back() != j.parent) open.pop_back();
      if (open.empty()) return error = at + "joints are not in depth-first order", false;
    }
    if (!j.end_site && !valid_name(j.name))
      return error = at + "name must be non-empty, without braces, line breaks or outer blanks",
             false;
    if (j.end_site && !j.channels.empty()) return error = at + "End Site with channels", false;
    if (j.channels.size() > kBvhMaxChannelsPerJoint) return error = at + "too many channels", false;
    for (size_t a = 0; a < j.channels.size(); ++a) {
      if (static_cast<int>(j.channels[a]) > 5) return error = at + "unknown channel", false;
      for (size_t b = 0; b < a; ++b)
        if (j.channels[a] == j.channels[b]) return error = at + "channel listed twice", false;
    }
    if (!std::isfinite(j.offset.x) || !std::isfinite(j.offset.y) || !std::isfinite(j.offset.z))
      return error = at + "non-finite OFFSET", false;
    if (!j.end_site) open.push_back(i);
  }
  if (!std::isfinite(doc.frame_time_s) || doc.frame_time_s <= 0.0)
    return error = "BVH document: frame time must be > 0", false;
  if (doc.num_frames < 0) return error = "BVH document: negative frame count", false;
  // The parser refuses a channel-less hierarchy (its motion lines would be empty), so the
  // writer must not produce one.
  if (doc.num_channels() == 0) return error = "BVH document: no joint has channels", false;
  if (doc.values.size() != static_cast<size_t>(doc.num_frames) * doc.num_channels())
    return error = "BVH document: values.size() != num_frames * num_channels()", false;
  for (float v : doc.values)
    if (!std::isfinite(v)) return error = "BVH document: non-finite motion value", false;
  return true;
}

std::string bvh_write(const BvhDocument& doc) {
  std::string error;
  if (!bvh_validate(doc, error)) return {};
  std::string s;
  s.reserve(256 + doc.joints.size() * 96 + doc.values.size() * 12);
  s += "HIERARCHY\n";
  std::vector<int> open;
  auto indent = [&s](size_t depth) { s.append(depth, '\t'); };
  auto close_until = [&](int parent) {
    while (!open.empty() && open.back() != parent) {
      open.pop_back();
      indent(open.size());
      s += "}\n";
    }
  };
  auto offset_line = [&](size_t depth, vec3 o) {
    indent(depth);
    s += "OFFSET ";
    append_float(s, o.x);
    s += ' ';
    append_float(s, o.y);
    s += ' ';
    append_float(s, o.z);
    s += '\n';
  };
  for (size_t i = 0; i < doc.joints.size(); ++i) {
    const BvhJoint& j = doc.joints[i];
    close_until(j.parent);
    const size_t depth = open.size();
    if (j.end_site) {
      indent(depth);
      s += "End Site\n";
      indent(depth);
      s += "{\n";
      offset_line(depth + 1, j.offset);
      indent(depth);
      s += "}\n";
      continue;
    }
    indent(depth);
    s += i == 0 ? "ROOT " : "JOINT ";
    s += j.name;
    s += '\n';
    indent(depth);
    s += "{\n";
    offset_line(depth + 1, j.offset);
    if (!j.channels.empty()) {
      indent(depth + 1);
      s += "CHANNELS " + std::to_string(j.channels.size());
      for (BvhChannel c : j.channels) {
        s += ' ';
        s += bvh_channel_name(c);
      }
      s += '\n';
    }
    open.push_back(static_cast<int>(i));
  }
  close_until(-1);
  s += "MOTION\nFrames: " + std::to_string(doc.num_frames) + "\nFrame Time: ";
  append_double(s, doc.frame_time_s);
  s += '\n';
  const size_t channels = static_cast<size_t>(doc.num_channels());
  for (int f = 0; f < doc.num_frames; ++f) {
    const float* v = doc.values.data() + static_cast<size_t>(f) * channels;
    for (size_t c = 0; c < channels; ++c) {
      if (c) s += ' ';
      append_float(s, v[c]);
    }
    s += '\n';
  }
  return s;
}

bool bvh_save(const std::filesystem::path& path, const BvhDocument& doc, std::string& error) {
  try {
    if (!bvh_validate(doc, error)) return false;
    const std::string text = bvh_write(doc);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) {
      error = path.string() + ": cannot open for writing";
      return false;
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      error = path.string() + ": write failed";
      return false;
    }
    return true;
  } catch (const std::exception& e) {
    error = path.string() + ": " + e.what();
    return false;
  }
}

}  // namespace foresight
