// bvh_parse / bvh_write / bvh_load / bvh_save: accepted syntax, every rejection path with its line
// number, exact write -> read round trips, and no crash on truncated or mutated input.
#include "import/bvh.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

namespace foresight {
namespace {

// Line numbers are part of the expectations below: keep this text as is.
const char* const kSmall =
    "HIERARCHY\n"                                                                   // 1
    "ROOT Hips\n"                                                                   // 2
    "{\n"                                                                           // 3
    "  OFFSET 0 0 0\n"                                                              // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"    // 5
    "  JOINT Spine\n"                                                               // 6
    "  {\n"                                                                         // 7
    "    OFFSET 0 10 0\n"                                                           // 8
    "    CHANNELS 3 Zrotation Xrotation Yrotation\n"                                // 9
    "    End Site\n"                                                                // 10
    "    {\n"                                                                       // 11
    "      OFFSET 0 5 0\n"                                                          // 12
    "    }\n"                                                                       // 13
    "  }\n"                                                                         // 14
    "}\n"                                                                           // 15
    "MOTION\n"                                                                      // 16
    "Frames: 2\n"                                                                   // 17
    "Frame Time: 0.0333333\n"                                                       // 18
    "0 90 0 0 0 0 10 0 0\n"                                                         // 19
    "1 90 0 0 0 0 20 0 0\n";                                                        // 20

// kSmall with line `line` (1-based) replaced by `text` (which may hold several lines or none).
std::string with_line(int line, const std::string& text) {
  std::string s = kSmall, out;
  size_t start = 0;
  for (int l = 1; start < s.size(); ++l) {
    const size_t end = s.find('\n', start);
    if (l == line) {
      out += text;
    } else {
      out += s.substr(start, end - start + 1);
    }
    start = end + 1;
  }
  return out;
}

std::string first_lines(int lines) {
  std::string s = kSmall;
  size_t pos = 0;
  for (int l = 0; l < lines; ++l) pos = s.find('\n', pos) + 1;
  return s.substr(0, pos);
}

TEST(BvhParse, ReadsHierarchyChannelsAndMotion) {
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(kSmall, "small.bvh", doc, error)) << error;
  ASSERT_EQ(doc.joints.size(), 3u);
  EXPECT_EQ(doc.joints[0].name, "Hips");
  EXPECT_EQ(doc.joints[0].parent, -1);
  EXPECT_EQ(doc.joints[1].name, "Spine");
  EXPECT_EQ(doc.joints[1].parent, 0);
  EXPECT_EQ(doc.joints[1].offset, vec3(0, 10, 0));
  EXPECT_EQ(doc.joints[1].channels,
            (std::vector{BvhChannel::kZrotation, BvhChannel::kXrotation, BvhChannel::kYrotation}));
  EXPECT_TRUE(doc.joints[2].end_site);
  EXPECT_EQ(doc.joints[2].parent, 1);
  EXPECT_EQ(doc.joints[2].name, "Spine_End");
  EXPECT_EQ(doc.joints[2].offset, vec3(0, 5, 0));
  EXPECT_TRUE(doc.joints[2].channels.empty());
  EXPECT_EQ(doc.num_channels(), 9);
  EXPECT_EQ(doc.channel_offset(1), 6);
  EXPECT_EQ(doc.num_frames, 2);
  EXPECT_DOUBLE_EQ(doc.frame_time_s, 0.0333333);
  ASSERT_EQ(doc.values.size(), 18u);
  EXPECT_EQ(doc.values[1], 90.0f);
  EXPECT_EQ(doc.values[9], 1.0f);
  EXPECT_EQ(doc.values[15], 20.0f);
}

TEST(BvhParse, AcceptsCrlfTabsExponentsNegativeZeroAndCompactHeaders) {
  const std::string text =
      "\xEF\xBB\xBFhierarchy\r\n"
      "ROOT\tjoint Root  \r\n"
      "{\r\n"
      "\tOFFSET\t-0\t1.5e+1 2E-3 \r\n"
      "\tCHANNELS 3 Yrotation Xposition zROTATION \r\n"
      "\tJOINT Arm {\r\n"
      "\t\tOFFSET .5 0 -0\r\n"
      "\t\tCHANNELS 2 Yposition Xrotation\r\n"
      "\t\tEnd Site\r\n"
      "\t\t{\r\n"
      "\t\t\tOFFSET 0 0 0\r\n"
      "\t\t}\r\n"
      "\t}\r\n"
      "}\r\n"
      "MOTION\r\n"
      "Frames:2\r\n"
      "Frame Time:\t0.04\r\n"
      "\r\n"
      "5.1072e-06\t-0 +3 1e-50 -2.5 \r\n"
      "  1 2 3 4 5\t\r\n"
      "\r\n  \r\n";
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(text, "crlf.bvh", doc, error)) << error;
  ASSERT_EQ(doc.joints.size(), 3u);
  EXPECT_EQ(doc.joints[0].name, "joint Root");  // names are the rest of the line
  EXPECT_EQ(doc.joints[1].name, "Arm");         // the brace on the name line is not part of it
  EXPECT_EQ(doc.joints[0].offset, vec3(0.0f, 15.0f, 0.002f));
  EXPECT_TRUE(std::signbit(doc.joints[0].offset.x));
  EXPECT_EQ(doc.joints[1].offset, vec3(0.5f, 0.0f, 0.0f));
  EXPECT_EQ(doc.joints[0].channels, (std::vector{BvhChannel::kYrotation, BvhChannel::kXposition,
                                                 BvhChannel::kZrotation}));
  EXPECT_EQ(doc.joints[1].channels,
            (std::vector{BvhChannel::kYposition, BvhChannel::kXrotation}));
  EXPECT_EQ(doc.num_frames, 2);
  EXPECT_DOUBLE_EQ(doc.frame_time_s, 0.04);
  ASSERT_EQ(doc.values.size(), 10u);
  EXPECT_FLOAT_EQ(doc.values[0], 5.1072e-06f);
  EXPECT_EQ(doc.values[1], 0.0f);
  EXPECT_TRUE(std::signbit(doc.values[1]));
  EXPECT_EQ(doc.values[2], 3.0f);
  EXPECT_EQ(doc.values[3], 0.0f);  // underflows a float: zero, not an error
  EXPECT_EQ(doc.values[4], -2.5f);
  EXPECT_EQ(doc.values[9], 5.0f);
}

TEST(BvhParse, AcceptsLoneCrLineEndsAndNoFinalNewline) {
  std::string text = kSmall;
  for (char& c : text)
    if (c == '\n') c = '\r';
  text.pop_back();
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(text, "cr.bvh", doc, error)) << error;
  EXPECT_EQ(doc.num_frames, 2);
  EXPECT_EQ(doc.values[15], 20.0f);
}

TEST(BvhParse, PositionChannelsOnAnyJointAndChannelLessJoints) {
  std::string text = with_line(9, "    CHANNELS 6 Zposition Yrotation Yposition Xrotation "
                                  "Xposition Zrotation\n");
  text = text.substr(0, text.find("MOTION")) +
         "MOTION\nFrames: 1\nFrame Time: 0.01\n1 2 3 4 5 6 7 8 9 10 11 12\n";
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(text, "six.bvh", doc, error)) << error;
  using C = BvhChannel;
  EXPECT_EQ(doc.joints[1].channels, (std::vector{C::kZposition, C::kYrotation, C::kYposition,
                                                 C::kXrotation, C::kXposition, C::kZrotation}));
  EXPECT_EQ(doc.values[6], 7.0f);

  // Without its CHANNELS line the Spine has no channels: 6 values per frame.
  text = with_line(9, "");
  text = text.substr(0, text.find("MOTION")) + "MOTION\nFrames: 1\nFrame Time: 0.01\n1 2 3 4 5 6\n";
  ASSERT_TRUE(bvh_parse(text, "none.bvh", doc, error)) << error;
  EXPECT_TRUE(doc.joints[1].channels.empty());
  EXPECT_EQ(doc.num_channels(), 6);
}

struct BadCase {
  const char* label;
  std::string text;
  int line;
  const char* expected;
};

std::vector<BadCase> bad_cases() {
  return {
      {"empty file", "", 1, "expected 'HIERARCHY', got an empty file"},
      {"blank file", "\n  \n\t\n", 4, "expected 'HIERARCHY', got an empty file"},
      {"not bvh", "hello world\n", 1, "expected 'HIERARCHY', got 'hello'"},
      {"no ROOT", "HIERARCHY\nJOINT x\n", 2, "expected 'ROOT' after HIERARCHY, got 'JOINT'"},
      {"truncated hierarchy", first_lines(9), 10, "unexpected end of file inside joint 'Spine'"},
      {"truncated in OFFSET", first_lines(7) + "    OFFSET 0 10", 8,
       "expected OFFSET value, got end of line"},
      {"missing brace after JOINT", with_line(7, ""), 7,
       "expected '{' after JOINT name, got 'OFFSET'"},
      {"missing OFFSET", with_line(8, ""), 8, "expected 'OFFSET' in 'Spine', got 'CHANNELS'"},
      {"missing joint name", with_line(6, "  JOINT\n"), 6, "expected a joint name after JOINT"},
      {"brace in joint name", with_line(6, "  JOINT Sp{ine\n"), 6,
       "expected a joint name without braces after JOINT, got 'Sp{ine'"},
      {"junk after OFFSET", with_line(8, "    OFFSET 0 10 0 7\n"), 8,
       "unexpected '7' after the 3 OFFSET values"},
      {"non-number OFFSET", with_line(8, "    OFFSET 0 ten 0\n"), 8,
       "expected a number, got 'ten'"},
      {"CHANNELS lists too few", with_line(9, "    CHANNELS 6 Zrotation Xrotation Yrotation\n"),
       9, "CHANNELS declares 6 channels but lists 3"},
      {"CHANNELS lists too many", with_line(9, "    CHANNELS 2 Zrotation Xrotation Yrotation\n"),
       9, "CHANNELS declares 2 channels but lists more: 'Yrotation'"},
      {"CHANNELS count 7", with_line(9, "    CHANNELS 7 Zrotation Xrotation Yrotation\n"), 9,
       "expected a channel count 0..6 after CHANNELS, got '7'"},
      {"CHANNELS count missing", with_line(9, "    CHANNELS\n"), 9,
       "expected a channel count 0..6 after CHANNELS, got end of line"},
      {"channel twice", with_line(9, "    CHANNELS 3 Zrotation Xrotation Zrotation\n"), 9,
       "channel 'Zrotation' listed twice in joint 'Spine'"},
      {"unknown channel", with_line(9, "    CHANNELS 3 Zrotation Wrotation Yrotation\n"), 9,
       "expected a channel name (Xposition, Yposition, Zposition, Xrotation, Yrotation, "
       "Zrotation), got 'Wrotation'"},
      {"End without Site", with_line(10, "    End\n"), 10, "expected 'Site' after 'End'"},
      {"End Site with channels", with_line(12, "      CHANNELS 3 Zrotation Xrotation Yrotation\n"),
       12, "expected 'OFFSET' in 'End Site', got 'CHANNELS'"},
      // The Spine's brace closes the End Site, so MOTION is met inside Hips.
      {"End Site not closed", with_line(13, ""), 15,
       "expected 'JOINT', 'End Site' or '}' in joint 'Hips', got 'MOTION'"},
      {"missing closing brace", with_line(15, ""), 15,
       "expected 'JOINT', 'End Site' or '}' in joint 'Hips', got 'MOTION'"},
      {"extra closing brace", with_line(15, "}\n}\n"), 16,
       "'}' without a matching '{' (unbalanced braces)"},
      {"missing braces at end of file", first_lines(13), 14,
       "unexpected end of file inside joint 'Spine': 2 '}' missing (unbalanced braces)"},
      {"second ROOT", with_line(16, "ROOT Other\n"), 16, "only one ROOT is supported"},
      {"missing MOTION", first_lines(15), 16,
       "expected 'MOTION' after the hierarchy, got end of file"},
      {"missing Frames", with_line(17, "Frame: 2\n"), 17,
       "expected 'Frames:' after MOTION, got 'Frame:'"},
      {"non-number frame count", with_line(17, "Frames: two\n"), 17,
       "expected a frame count 0..2147483647 after 'Frames:', got 'two'"},
      {"fractional frame count", with_line(17, "Frames: 2.5\n"), 17,
       "expected a frame count 0..2147483647 after 'Frames:', got '2.5'"},
      {"negative frame count", with_line(17, "Frames: -1\n"), 17, "expected a frame count"},
      {"frame count 2^31", with_line(17, "Frames: 2147483648\n"), 17,
       "expected a frame count 0..2147483647 after 'Frames:', got '2147483648'"},
      {"huge frame count", with_line(17, "Frames: 99999999999999999999999\n"), 17,
       "expected a frame count"},
      {"frame count beyond the file", with_line(17, "Frames: 2000000000\n"), 21,
       "expected motion line 3 of 2000000000, got end of file (truncated?)"},
      {"missing Frame Time", with_line(18, ""), 18,
       "expected 'Frame Time:' after the frame count, got '0'"},
      {"zero frame time", with_line(18, "Frame Time: 0\n"), 18,
       "expected a frame time in seconds > 0 after 'Frame Time:', got '0'"},
      {"negative frame time", with_line(18, "Frame Time: -0.03\n"), 18,
       "expected a frame time in seconds > 0"},
      {"NaN frame time", with_line(18, "Frame Time: nan\n"), 18,
       "expected a frame time in seconds > 0"},
      {"junk after frame time", with_line(18, "Frame Time: 0.03 s\n"), 18,
       "unexpected 's' after the frame time"},
      {"truncated mid-motion", first_lines(19), 20,
       "expected motion line 2 of 2, got end of file (truncated?)"},
      {"truncated inside a motion line", first_lines(19) + "1 90 0 0", 20,
       "expected 9 values on motion line 2, got 4"},
      {"no motion lines", first_lines(18), 19, "expected motion line 1 of 2, got end of file"},
      {"too few values", with_line(19, "0 90 0 0 0 0 10 0\n"), 19,
       "expected 9 values on motion line 1, got 8"},
      {"too many values", with_line(20, "1 90 0 0 0 0 20 0 0 4\n"), 20,
       "expected 9 values on motion line 2, got more: '4'"},
      {"non-number value", with_line(20, "1 90 0 abc 0 0 20 0 0\n"), 20,
       "expected a number, got 'abc'"},
      {"number with junk", with_line(20, "1 90 0 1.5x 0 0 20 0 0\n"), 20,
       "expected a number, got '1.5x'"},
      {"hex value", with_line(20, "1 90 0 0x10 0 0 20 0 0\n"), 20,
       "expected a number, got '0x10'"},
      {"NaN value", with_line(19, "0 90 nan 0 0 0 10 0 0\n"), 19,
       "expected a finite number, got 'nan'"},
      {"infinite value", with_line(19, "0 90 -inf 0 0 0 10 0 0\n"), 19,
       "expected a finite number, got '-inf'"},
      {"value beyond float", with_line(19, "0 90 1e39 0 0 0 10 0 0\n"), 19,
       "number out of float range: '1e39'"},
      {"value beyond double", with_line(19, "0 90 1e400 0 0 0 10 0 0\n"), 19,
       "number out of float range: '1e400'"},
      {"junk after the last frame", std::string(kSmall) + "\n3 4 5\n", 22,
       "unexpected '3' after the last of 2 frames"},
      {"binary junk", std::string("HIERARCHY\nROOT a\n{\x01\x02\n"), 3,
       "expected '{' after ROOT name, got '{?" "?'"},
  };
}

TEST(BvhParse, RejectsMalformedInputNamingSourceLineAndExpectation) {
  for (const BadCase& c : bad_cases()) {
    SCOPED_TRACE(c.label);
    BvhDocument doc;
    std::string error;
    EXPECT_FALSE(bvh_parse(c.text, "walk.bvh", doc, error));
    const std::string where = "walk.bvh:" + std::to_string(c.line) + ": ";
    EXPECT_EQ(error.rfind(where, 0), 0u) << "error: " << error;
    EXPECT_NE(error.find(c.expected), std::string::npos) << "error: " << error;
  }
}

TEST(BvhParse, RejectsMoreJointsThanTheCap) {
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
  for (int i = 1; i <= kBvhMaxJoints; ++i)
    text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\n}\n";
  text += "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0\n";
  BvhDocument doc;
  std::string error;
  EXPECT_FALSE(bvh_parse(text, "many.bvh", doc, error));
  EXPECT_NE(error.find("many.bvh:" + std::to_string(6 + 4 * (kBvhMaxJoints - 1)) +
                       ": too many joints (the limit is 1024)"),
            std::string::npos)
      << error;
}

TEST(BvhParse, DeepNestingDoesNotOverflowTheStack) {
  // 1000 nested joints: the parser keeps its own stack.
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n";
  for (int i = 1; i < 1000; ++i) text += "JOINT j\n{\nOFFSET 0 1 0\n";
  for (int i = 0; i < 1000; ++i) text += "}\n";
  text += "MOTION\nFrames: 1\nFrame Time: 0.1\n0\n";
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(text, "deep.bvh", doc, error)) << error;
  EXPECT_EQ(doc.joints.size(), 1000u);
  EXPECT_EQ(doc.joints.back().parent, 998);
}

TEST(BvhParse, TruncatedOrMutatedInputNeverCrashesAndAlwaysSaysWhere) {
  const std::string base = kSmall;
  const char mutations[] = {'{', '}', '\n', ' ', 'x', '-', '9', '\0', '\r', 'e'};
  int failures = 0;
  auto check = [&](const std::string& text) {
    BvhDocument doc;
    std::string error;
    if (bvh_parse(text, "fuzz.bvh", doc, error)) {
      // Whatever parses is a consistent, writable document.
      EXPECT_TRUE(bvh_validate(doc, error)) << error;
      return;
    }
    ++failures;
    ASSERT_EQ(error.rfind("fuzz.bvh:", 0), 0u) << error;
    ASSERT_TRUE(std::isdigit(static_cast<unsigned char>(error[9]))) << error;
  };
  for (size_t cut = 0; cut < base.size(); ++cut) check(base.substr(0, cut));
  for (size_t at = 0; at < base.size(); ++at)
    for (char m : mutations) {
      std::string text = base;
      text[at] = m;
      check(text);
    }
  EXPECT_GT(failures, static_cast<int>(base.size()));  // almost every truncation is an error
}

bool same_document(const BvhDocument& a, const BvhDocument& b) {
  if (a.joints.size() != b.joints.size() || a.num_frames != b.num_frames ||
      a.frame_time_s != b.frame_time_s || a.values.size() != b.values.size())
    return false;
  for (size_t i = 0; i < a.joints.size(); ++i) {
    const BvhJoint &x = a.joints[i], &y = b.joints[i];
    if (x.name != y.name || x.parent != y.parent || x.offset != y.offset ||
        x.channels != y.channels || x.end_site != y.end_site)
      return false;
  }
  for (size_t i = 0; i < a.values.size(); ++i)
    if (a.values[i] != b.values[i] || std::signbit(a.values[i]) != std::signbit(b.values[i]))
      return false;
  return true;
}

TEST(BvhWrite, WriteThenParseGivesTheSameDocumentBitForBit) {
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(kSmall, "small.bvh", doc, error)) << error;
  // Values whose decimal forms are long or special.
  doc.values[0] = 1.0f / 3.0f;
  doc.values[1] = -0.0f;
  doc.values[2] = 1e-7f;
  doc.values[3] = 123456.789f;
  doc.values[4] = -1e30f;
  doc.values[5] = 1.17549435e-38f;
  doc.joints[1].offset = vec3(0.1f, -2.0f / 7.0f, 1e-20f);
  doc.frame_time_s = 1.0 / 120.0;
  const std::string text = bvh_write(doc);
  ASSERT_FALSE(text.empty());
  BvhDocument back;
  ASSERT_TRUE(bvh_parse(text, "written.bvh", back, error)) << error << "\n" << text;
  EXPECT_TRUE(same_document(doc, back)) << text;
  // And a second write is byte-identical.
  EXPECT_EQ(bvh_write(back), text);
}

TEST(BvhWrite, SaveAndLoadThroughAFile) {
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(kSmall, "small.bvh", doc, error)) << error;
  const auto path = test::scratch_dir() / "saved.bvh";
  ASSERT_TRUE(bvh_save(path, doc, error)) << error;
  BvhDocument back;
  ASSERT_TRUE(bvh_load(path, back, error)) << error;
  EXPECT_TRUE(same_document(doc, back));
}

TEST(BvhWrite, RefusesInvalidDocuments) {
  BvhDocument doc;
  std::string error;
  ASSERT_TRUE(bvh_parse(kSmall, "small.bvh", doc, error)) << error;
  BvhDocument wrong_values = doc;
  wrong_values.values.pop_back();
  BvhDocument not_depth_first = doc;
  not_depth_first.joints.push_back({"Late", 1, vec3(0), {BvhChannel::kXrotation}, false});
  not_depth_first.joints.push_back({"Later", 0, vec3(0), {}, false});
  not_depth_first.joints.push_back({"Wrong", 3, vec3(0), {}, false});  // 3 was closed by 4
  not_depth_first.num_frames = 0;
  not_depth_first.values.clear();
  BvhDocument end_site_channels = doc;
  end_site_channels.joints[2].channels = {BvhChannel::kXrotation};
  BvhDocument bad_name = doc;
  bad_name.joints[1].name = "two\nlines";
  BvhDocument nan_value = doc;
  nan_value.values[3] = std::nanf("");
  BvhDocument zero_time = doc;
  zero_time.frame_time_s = 0.0;
  for (const BvhDocument* d :
       {&wrong_values, &not_depth_first, &end_site_channels, &bad_name, &nan_value, &zero_time}) {
    EXPECT_FALSE(bvh_validate(*d, error));
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(bvh_write(*d), "");
    EXPECT_FALSE(bvh_save(test::scratch_dir() / "bad.bvh", *d, error));
  }
  EXPECT_TRUE(bvh_validate(doc, error)) << error;
}

TEST(BvhLoad, MissingFileNamesThePath) {
  BvhDocument doc;
  std::string error;
  const auto path = test::scratch_dir() / "absent.bvh";
  EXPECT_FALSE(bvh_load(path, doc, error));
  EXPECT_NE(error.find("absent.bvh"), std::string::npos) << error;
}

TEST(BvhLoad, ErrorsNameTheFile) {
  const auto path = test::scratch_dir() / "broken.bvh";
  std::ofstream(path) << with_line(19, "0 90 0 0 0 0 10 0\n");
  BvhDocument doc;
  std::string error;
  EXPECT_FALSE(bvh_load(path, doc, error));
  EXPECT_NE(error.find("broken.bvh:19: expected 9 values"), std::string::npos) << error;
}

}  // namespace
}  // namespace foresight
