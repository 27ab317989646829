#include "agones_sdk.hpp"

#include <httplib.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace foresight::server {

int agones_port_from_environment() {
  if (const char* env = std::getenv("AGONES_SDK_HTTP_PORT")) {
    char* end = nullptr;
    const long port = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && port > 0 && port < 65536) return static_cast<int>(port);
    std::fprintf(stderr, "foresight-server: AGONES_SDK_HTTP_PORT '%s' is not a port; using 9358\n", env);
  }
  return 9358;
}

AgonesSdk::AgonesSdk(AgonesConfig config, const std::atomic<int64_t>& last_tick_ns)
    : config_(std::move(config)), last_tick_ns_(last_tick_ns) {}

AgonesSdk::~AgonesSdk() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void AgonesSdk::start() { thread_ = std::thread([this] { loop(); }); }

bool AgonesSdk::ticking() const {
  const int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::steady_clock::now().time_since_epoch())
                          .count();
  const int64_t last = last_tick_ns_.load();
  return last != 0 && static_cast<double>(now - last) * 1e-9 < config_.stall_s;
}

bool AgonesSdk::post(const char* path) {
  httplib::Client client(config_.host, config_.port);
  client.set_connection_timeout(std::chrono::milliseconds(500));
  client.set_read_timeout(std::chrono::seconds(1));
  const auto res = client.Post(path, "{}", "application/json");
  return res && res->status >= 200 && res->status < 300;
}

void AgonesSdk::loop() {
  using Seconds = std::chrono::duration<double>;
  auto next_health = std::chrono::steady_clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    Seconds wait{config_.retry_s};
    lock.unlock();
    if (!ready_.load()) {
      // Ready only once the tick runs: before it, a player sent here would wait for nothing.
      if (ticking() && post("/ready")) {
        ready_.store(true);
        std::fprintf(stderr, "foresight-server: Agones sidecar told: Ready\n");
      }
    } else {
      const auto now = std::chrono::steady_clock::now();
      if (now >= next_health && ticking()) {
        post("/health");  // unanswered: Agones itself notices the missing pings
        next_health = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(Seconds(config_.health_interval_s));
      }
      wait = std::min(Seconds(config_.health_interval_s), Seconds(config_.stall_s) / 2.0);
    }
    lock.lock();
    wake_.wait_for(lock, wait, [this] { return stop_; });
  }
}

void AgonesSdk::shutdown() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (shut_down_) return;
    shut_down_ = stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  if (post("/shutdown")) std::fprintf(stderr, "foresight-server: Agones sidecar told: Shutdown\n");
}

}  // namespace foresight::server
