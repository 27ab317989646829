#pragma once
// N scripted bots in one process, each a real client (its own ClientConnection: own UDP socket,
// own session), driven in one pass per frame:
//   start   up to connects_per_frame new handshakes per frame (a large fleet would otherwise hit
//           the server with hundreds of ConnectRequests in the same millisecond)
//   receive every socket drained (and between frames, as datagrams arrive: wait_until())
//   think   each connected bot's script turns its avatar's root into the keys it holds
//   send    each bot's Input (or Heartbeat), handshake resends, timeouts
//   watch   one bot's view (the first connected) goes through the CollisionWatch
// Nothing is allocated per frame once every bot is connected and the shared world is loaded,
// except route plans (rationed by plans_per_frame) and the first copy of a larger snapshot.
#include "bot_brain.hpp"
#include "bot_config.hpp"
#include "bot_report.hpp"
#include "bot_world.hpp"
#include "collision_watch.hpp"
#include "transport/client_connection.hpp"

#include <atomic>
#include <chrono>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace foresight::bots {

class BotFleet {
 public:
  using Clock = protocol::ClientConnection::Clock;
  using TimePoint = Clock::time_point;

  /// `library` must outlive the fleet; its content_hash is what the bots connect with. `log`
  /// (may be nullptr) gets one line per distinct event worth a person's attention (a refusal,
  /// a timeout, the scene loaded).
  BotFleet(const MotionLibrary& library, const BotFleetConfig& config, std::ostream* log = nullptr);
  ~BotFleet();
  BotFleet(const BotFleet&) = delete;
  BotFleet& operator=(const BotFleet&) = delete;

  /// False with a reason when the config is out of range (error() says why).
  bool ok() const { return error_.empty(); }
  /// Set when the fleet cannot go on (bad config, the server's scene or the replay recording
  /// cannot be loaded).
  const std::string& error() const { return error_; }

  /// One frame at `now` (see above).
  void frame(TimePoint now);
  /// Handles datagrams as they arrive until `deadline` (epoll over every bot's socket), so
  /// arrival times (round trips, snapshot intervals) are not rounded to the frame.
  void wait_until(TimePoint deadline);

  /// Asks the server for its ServerStats through the first connected bot.
  void request_stats();
  bool stats_arrived() const;
  /// Every bot sends Disconnect (a few times) and closes.
  void disconnect_all();

  /// Started, and each bot refused, timed out, gone or closed: nothing more will happen.
  bool all_finished() const;
  int connected_now() const;
  /// One line for people: connected, goals, rtt, drops, frame cost.
  std::string progress_line(TimePoint now) const;
  BotReport report(TimePoint now) const;

  int size() const { return static_cast<int>(bots_.size()); }
  const protocol::ClientConnection& connection(int i) const { return bots_[static_cast<size_t>(i)]->conn; }
  const BotWorld& world() const { return world_; }

 private:
  struct Bot {
    explicit Bot(const protocol::ClientConfig& c) : conn(c) {}
    protocol::ClientConnection conn;
    BotBrain brain;
    bool started = false;
    bool accepted = false;  ///< Ever.
    protocol::ClientState last_state = protocol::ClientState::kClosed;
    TimePoint session_end{};  ///< When it left kConnected (for its kbps).
    /// The connection's byte counters (lifetime: a churned bot reuses it) when its latest
    /// session began, so its kbps are that session's.
    uint64_t bytes_in_at_accept = 0, bytes_out_at_accept = 0;
    bool reconnect_pending = false;
    TimePoint reconnect_at{};
    double backoff_s = 0;     ///< The next wait (0: the first is reconnect_first_s).
    int reconnects = 0;       ///< Handshakes started again after losing the server.
  };

  void on_state_change(Bot& bot, int index, TimePoint now);
  void on_accept(Bot& bot, int index);
  void find_scene(Bot& bot, int index);  ///< Own copy of the server's scene, or start fetching it.
  void fetch_scene(Bot& bot);
  void load_world(const std::string& scene_name, std::string_view text, const std::string& how);
  void schedule_reconnect(Bot& bot, int index, TimePoint now);
  void log_once(const std::string& line);

  const MotionLibrary& library_;
  BotFleetConfig config_;
  std::ostream* log_;
  std::string error_;
  std::vector<std::unique_ptr<Bot>> bots_;
  BotWorld world_;
  int scene_fetcher_ = -1;  ///< The bot fetching the server's scene file (none here matched), or -1.
  CollisionWatch watch_;
  int observer_ = -1;  ///< The bot whose view the watch checks.
  int epoll_fd_ = -1;
  int next_to_start_ = 0;
  int next_to_churn_ = 0;
  TimePoint next_churn_{};
  int churns_ = 0;
  std::vector<std::string> refusals_;
  std::vector<std::string> logged_;
  bool has_last_frame_ = false;
  TimePoint last_frame_{};
  uint64_t frames_ = 0, frames_late_ = 0;
  protocol::LogHistogram frame_ms_;
};

/// The whole run in real time: frames at config.rate_hz for config.seconds (or until every bot
/// is finished, or `stop` becomes true), a progress line per second to `progress` (may be
/// nullptr), then a ServerStats request (waiting up to stats_wait_s), the report, and Disconnect.
BotReport bot_fleet_run(const MotionLibrary& library, const BotFleetConfig& config,
                        std::ostream* progress, const std::atomic<bool>* stop = nullptr);

}  // namespace foresight::bots
