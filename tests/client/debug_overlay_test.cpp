// The debug overlay's pure logic: connection-quality classification, the snapshot loss and
// bandwidth meter, the smoothed frame timer (the ImGui window itself shows in ClientScreenshot).
#include "debug_overlay.hpp"

#include <gtest/gtest.h>

namespace foresight::client {
namespace {

TEST(ClientDebugOverlay, QualityFromRttAndLoss) {
  EXPECT_EQ(classify_link(true, 20, 0.0), LinkQuality::kGood);
  EXPECT_EQ(classify_link(true, 99, 0.019), LinkQuality::kGood);
  EXPECT_EQ(classify_link(true, 100, 0.0), LinkQuality::kFair);    // RTT at the green limit
  EXPECT_EQ(classify_link(true, 20, 0.05), LinkQuality::kFair);    // loss past green
  EXPECT_EQ(classify_link(true, 249, 0.099), LinkQuality::kFair);
  EXPECT_EQ(classify_link(true, 250, 0.0), LinkQuality::kPoor);
  EXPECT_EQ(classify_link(true, 20, 0.10), LinkQuality::kPoor);
  EXPECT_EQ(classify_link(false, 20, 0.0), LinkQuality::kPoor);   // not connected
  EXPECT_EQ(classify_link(true, 0, 0.0), LinkQuality::kPoor);     // no RTT sample yet
  QualityThresholds strict;
  strict.good_rtt_ms = 10;
  EXPECT_EQ(classify_link(true, 20, 0.0, strict), LinkQuality::kFair);
  EXPECT_STREQ(link_quality_name(LinkQuality::kFair), "fair");
}

LinkSample sample(double t, uint32_t tick, uint64_t received, uint64_t down = 0, uint64_t up = 0) {
  return {t, tick, received, down, up};
}

TEST(ClientDebugOverlay, MeterLossFromSnapshotNumbers) {
  LinkMeter m;
  m.add(sample(0, 100, 50));
  EXPECT_EQ(m.loss(), 0.0);  // one sample: nothing to compare
  m.add(sample(1, 130, 80));
  EXPECT_DOUBLE_EQ(m.loss(), 0.0);  // 30 snapshots numbered, 30 received
  m.add(sample(2, 160, 107));
  EXPECT_NEAR(m.loss(), 3.0 / 60.0, 1e-12);  // 57 of 60 over the window
  // Snapshot numbers count snapshots, whatever the tick rate: 20 a second (on 30 Hz ticks), 16
  // of them received, is 20 % lost (it once read as none: the numbers were taken for server ticks).
  LinkMeter twenty;
  twenty.add(sample(0, 0, 0));
  twenty.add(sample(1, 20, 16));
  EXPECT_NEAR(twenty.loss(), 0.2, 1e-12);
}

TEST(ClientDebugOverlay, MeterWindowForgetsOldLoss) {
  LinkMeter m;
  m.add(sample(0, 0, 0));
  m.add(sample(1, 30, 15));  // half lost
  EXPECT_NEAR(m.loss(), 0.5, 1e-12);
  uint64_t received = 15;
  for (int s = 2; s <= 1 + LinkMeter::kWindow; ++s) {
    received += 30;
    m.add(sample(s, static_cast<uint32_t>(30 * s), received));
  }
  EXPECT_EQ(m.samples(), LinkMeter::kWindow);
  EXPECT_DOUBLE_EQ(m.loss(), 0.0);
}

TEST(ClientDebugOverlay, MeterBandwidthAndRestart) {
  LinkMeter m;
  m.add(sample(0, 0, 0, 0, 0));
  m.add(sample(2, 60, 60, 25000, 5000));
  EXPECT_DOUBLE_EQ(m.down_kbit_s(), 100.0);  // 25 kB in 2 s
  EXPECT_DOUBLE_EQ(m.up_kbit_s(), 20.0);
  // A reconnect: counters start again; the meter restarts instead of reading huge numbers.
  m.add(sample(3, 10, 5, 100, 100));
  EXPECT_EQ(m.samples(), 1);
  EXPECT_EQ(m.loss(), 0.0);
  EXPECT_EQ(m.down_kbit_s(), 0.0);
  // Tick wrap-around is not a restart.
  LinkMeter w;
  w.add(sample(0, 0xFFFFFFF0u, 0));
  w.add(sample(1, 0x0000000Eu, 30));
  EXPECT_EQ(w.samples(), 2);
  EXPECT_DOUBLE_EQ(w.loss(), 0.0);
}

TEST(ClientDebugOverlay, FrameTimerSmooths) {
  FrameTimer f;
  f.tick(0.0);
  EXPECT_EQ(f.ms(), 0.0);
  f.tick(0.010);
  EXPECT_NEAR(f.ms(), 10.0, 1e-9);
  EXPECT_NEAR(f.fps(), 100.0, 1e-6);
  f.tick(0.030);  // one 20 ms frame moves the average 5 % of the way
  EXPECT_NEAR(f.ms(), 10.5, 1e-9);
}

}  // namespace
}  // namespace foresight::client
