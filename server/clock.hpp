#pragma once
// The server's clock, and the one helper that times the tick's stages.
#include <chrono>

namespace foresight::server {

using Clock = std::chrono::steady_clock;

inline double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

/// Times consecutive stages on the real clock: lap_ms() is the time since the previous lap (or
/// the start).
class StageTimer {
 public:
  StageTimer() : start_(Clock::now()), last_(start_) {}
  float lap_ms() {
    const Clock::time_point now = Clock::now();
    const double ms = ms_between(last_, now);
    last_ = now;
    return static_cast<float>(ms);
  }
  Clock::time_point start() const { return start_; }
  Clock::time_point last() const { return last_; }
  float total_ms() const { return static_cast<float>(ms_between(start_, Clock::now())); }

 private:
  Clock::time_point start_;
  Clock::time_point last_;
};

}  // namespace foresight::server
