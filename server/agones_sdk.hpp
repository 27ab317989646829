#pragma once
// Agones integration (docs/SCALING.md): run as an Agones GameServer, the server tells the SDK
// sidecar over its REST port (http://localhost:AGONES_SDK_HTTP_PORT) that it is Ready once its
// ticks run, pings Health while they keep coming (a stalled tick stops the pings, so Agones marks
// the instance Unhealthy and replaces it), and asks for Shutdown when it stops (graceful shutdown,
// after the clients were told). On its own thread: the tick never waits for HTTP. The sidecar may
// start after the server, so Ready is retried until it is answered.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace foresight::server {

struct AgonesConfig {
  std::string host = "127.0.0.1";
  int port = 9358;                ///< The sidecar's REST port (AGONES_SDK_HTTP_PORT).
  double health_interval_s = 2.0;  ///< Agones' default health period is 5 s: ping well within it.
  double stall_s = 1.0;           ///< No tick for this long: stop pinging (as /readyz says "not ticking").
  double retry_s = 0.5;           ///< Between unanswered Ready calls.
};

/// The sidecar's REST port: AGONES_SDK_HTTP_PORT if set (and a port), else Agones' default 9358.
int agones_port_from_environment();

class AgonesSdk {
 public:
  /// `last_tick_ns`: steady-clock nanoseconds of the latest tick, stored by the tick thread.
  AgonesSdk(AgonesConfig config, const std::atomic<int64_t>& last_tick_ns);
  ~AgonesSdk();  ///< Stops the thread (no Shutdown call: that is shutdown()'s).
  AgonesSdk(const AgonesSdk&) = delete;
  AgonesSdk& operator=(const AgonesSdk&) = delete;

  void start();
  /// Stops pinging and asks the sidecar to shut this game server down. Once; later calls do nothing.
  void shutdown();

  bool ready() const { return ready_.load(); }

 private:
  void loop();
  bool post(const char* path);
  bool ticking() const;

  AgonesConfig config_;
  const std::atomic<int64_t>& last_tick_ns_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool shut_down_ = false;
  std::atomic<bool> ready_{false};
};

}  // namespace foresight::server
