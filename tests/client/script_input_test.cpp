#include "script_input.hpp"

#include <gtest/gtest.h>

#include <string>

namespace foresight::client {
namespace {

Recording two_step_script() {
  const std::string json = R"({
    "format": "foresight-recording", "version": 1, "scene": "maze",
    "start": {"pos": [1.25, 1.25], "heading_deg": 90}, "goal": {"pos": [5, 5]},
    "samples": [
      {"t": 0, "dir": [0, 0], "camera_yaw_deg": 45, "crouch": false},
      {"t": 0.5, "dir": [0, 1], "camera_yaw_deg": 45, "crouch": false},
      {"t": 2, "dir": [1, 0], "camera_yaw_deg": -90, "crouch": true}
    ]})";
  Recording rec;
  std::string error;
  EXPECT_TRUE(recording_parse(json, "script", rec, error)) << error;
  return rec;
}

TEST(ClientScript, SampleAndHoldThenStop) {
  const Recording rec = two_step_script();
  ASSERT_EQ(rec.samples.size(), 3u);
  // Before the first command arrives: stop.
  EXPECT_EQ(script_input_at(rec, -0.1).camera_dir, vec2(0.0f));
  EXPECT_EQ(script_input_at(rec, 0.2).camera_dir, vec2(0.0f));
  // Held from 0.5 s until the next sample, with the recording's camera yaw.
  for (const double t : {0.5, 1.0, 1.99}) {
    const ControlInput in = script_input_at(rec, t);
    EXPECT_EQ(in.camera_dir, vec2(0.0f, 1.0f)) << t;
    EXPECT_NEAR(in.camera_yaw_rad, glm::radians(45.0f), 1e-6f) << t;
    EXPECT_FALSE(in.crouch) << t;
    EXPECT_TRUE(control_input_valid(in));
  }
  // The last sample (crouching) plays at its own time...
  const ControlInput last = script_input_at(rec, 2.0);
  EXPECT_EQ(last.camera_dir, vec2(1.0f, 0.0f));
  EXPECT_NEAR(last.camera_yaw_rad, glm::radians(-90.0f), 1e-6f);
  EXPECT_TRUE(last.crouch);
  EXPECT_FALSE(script_ended(rec, 2.0));
  // ...and once the script has ended the input is stop.
  EXPECT_TRUE(script_ended(rec, 2.01));
  const ControlInput after = script_input_at(rec, 10.0);
  EXPECT_EQ(after.camera_dir, vec2(0.0f));
  EXPECT_FALSE(after.crouch);
}

}  // namespace
}  // namespace foresight::client
