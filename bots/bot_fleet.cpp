#include "bot_fleet.hpp"

#include "protocol/avatar_state.hpp"

#include <sys/epoll.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <thread>

namespace foresight::bots {

namespace {

using protocol::ClientState;

/// Independent, well-mixed seeds per bot from one run seed (SplitMix64 finaliser).
uint64_t bot_seed(uint64_t seed, int index) {
  uint64_t z = seed + 0x9E3779B97F4A7C15ull * static_cast<uint64_t>(index + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

bool finished(ClientState s) {
  return s == ClientState::kRefused || s == ClientState::kTimedOut ||
         s == ClientState::kServerGone || s == ClientState::kClosed;
}

double seconds_between(BotFleet::TimePoint a, BotFleet::TimePoint b) {
  return std::chrono::duration<double>(b - a).count();
}

std::string config_problem(const BotFleetConfig& c) {
  if (c.count < 1 || c.count > 4096) return "count must be in [1, 4096]";
  if (!(c.rate_hz >= 1 && c.rate_hz <= 240)) return "rate must be in [1, 240] Hz";
  if (!(c.seconds >= 0 && c.seconds <= 1e6)) return "seconds must be in [0, 1e6]";
  if (c.connects_per_frame < 1 || c.plans_per_frame < 1) return "connects and plans per frame must be >= 1";
  if (!(c.give_up_target_s > 0) || !(c.stats_wait_s >= 0)) return "give-up and stats wait times must be > 0";
  if (std::string error; !protocol::impairment_valid(c.impairment, error)) return error;
  return {};
}

// The NPC fighter nearest `own` in the connection's latest snapshot.
bool nearest_fighter(const MotionLibrary& library, const protocol::ClientConnection& conn, vec2 own, Threat& out) {
  float best = std::numeric_limits<float>::max();
  Placement root;
  for (const wire::AvatarState& a : conn.avatars()) {
    if (!(a.flags() & protocol::kAvatarNpc) || !protocol::avatar_root(library, a, root)) continue;
    const vec2 pos = root.pos_m;
    const float d = glm::length(pos - own);
    if (d < best) {
      best = d;
      out.pos_m = pos;
      out.striking = (a.flags() & protocol::kAvatarStriking) != 0;
    }
  }
  return best < std::numeric_limits<float>::max();
}

const BotWorld& unloaded_world() {
  static const BotWorld empty;
  return empty;
}

}  // namespace

BotFleet::BotFleet(const MotionLibrary& library, const BotFleetConfig& config, std::ostream* log)
    : library_(library), config_(config), log_(log), watch_(config.contact_distance_m) {
  error_ = config_problem(config_);
  if (!error_.empty()) return;
  epoll_fd_ = ::epoll_create1(EPOLL_CLOEXEC);
  if (epoll_fd_ < 0) {
    error_ = "epoll_create1 failed";
    return;
  }
  protocol::ClientConfig client;
  // Room for every avatar of the server (the observer reads them all) without growing later.
  client.reserve_avatars = static_cast<size_t>(config_.count) + 64;
  bots_.reserve(static_cast<size_t>(config_.count));
  for (int i = 0; i < config_.count; ++i) {
    client.impairment = config_.impairment;
    client.impairment.seed = bot_seed(config_.impairment.seed + config_.seed, i);
    bots_.push_back(std::make_unique<Bot>(client));
  }
  refusals_.reserve(8);
}

BotFleet::~BotFleet() {
  if (epoll_fd_ >= 0) ::close(epoll_fd_);
}

void BotFleet::frame(TimePoint now) {
  if (!ok()) return;
  const TimePoint work_start = Clock::now();
  const double period_s = 1.0 / config_.rate_hz;
  if (has_last_frame_ && seconds_between(last_frame_, now) > 1.5 * period_s) ++frames_late_;
  has_last_frame_ = true;
  last_frame_ = now;

  // Start: a few new handshakes per frame.
  for (int started = 0; started < config_.connects_per_frame && next_to_start_ < size(); ++started) {
    Bot& bot = *bots_[static_cast<size_t>(next_to_start_)];
    bot.started = true;
    const std::string name = config_.name_prefix + std::to_string(next_to_start_);
    if (bot.conn.start(config_.server, library_.content_hash, name, now)) {
      epoll_event ev{};
      ev.events = EPOLLIN;
      ev.data.u32 = static_cast<uint32_t>(next_to_start_);
      ::epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, bot.conn.socket_fd(), &ev);
    } else {
      log_once(bot.conn.status_message());  // no socket (out of descriptors?)
    }
    bot.last_state = bot.conn.state();
    ++next_to_start_;
  }

  // Churn: one connected bot leaves and comes back as a new session.
  if (config_.churn_every_s > 0 && next_to_start_ == size()) {
    if (next_churn_ == TimePoint{}) next_churn_ = now + std::chrono::duration_cast<Clock::duration>(
                                                     std::chrono::duration<double>(config_.churn_every_s));
    if (now >= next_churn_) {
      Bot& bot = *bots_[static_cast<size_t>(next_to_churn_)];
      next_to_churn_ = (next_to_churn_ + 1) % size();
      next_churn_ += std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(config_.churn_every_s));
      if (bot.conn.connected()) {
        bot.conn.disconnect();
        bot.last_state = bot.conn.state();
        bot.reconnect_pending = true;
        bot.reconnect_at = now + std::chrono::milliseconds(500);
        ++churns_;
      }
    }
  }

  // Reconnect: bots whose server went away try again once their back-off is over (a restart
  // keeps the socket, so its epoll registration stays).
  for (int i = 0; i < next_to_start_; ++i) {
    Bot& bot = *bots_[static_cast<size_t>(i)];
    if (!bot.reconnect_pending || now < bot.reconnect_at) continue;
    bot.reconnect_pending = false;
    ++bot.reconnects;
    if (bot.conn.start(config_.server, library_.content_hash, config_.name_prefix + std::to_string(i), now))
      bot.last_state = bot.conn.state();
    else
      log_once(bot.conn.status_message());
  }

  int plans_left = config_.plans_per_frame;
  int observer = -1;
  for (int i = 0; i < next_to_start_; ++i) {
    Bot& bot = *bots_[static_cast<size_t>(i)];
    // Receive.
    bot.conn.poll(now);
    if (bot.conn.state() != bot.last_state) on_state_change(bot, i, now);
    if (!ok()) return;
    // Think.
    if (bot.conn.connected()) {
      if (observer < 0) observer = i;
      Placement root;
      const Placement* own = nullptr;
      if (const auto* a = bot.conn.own_avatar(); a && protocol::avatar_root(library_, *a, root)) own = &root;
      const bool same_scene = world_.loaded && bot.conn.accept().scene == world_.scene_name;
      const double t_s = seconds_between(bot.conn.accepted_at(), now);
      Threat threat;
      const bool threatened = own != nullptr && config_.script == BotScript::kDodge &&
                              nearest_fighter(library_, bot.conn, own->pos_m, threat);
      bot.conn.set_input(bot.brain.frame(same_scene ? world_ : unloaded_world(), config_, t_s, own,
                                         threatened ? &threat : nullptr, plans_left));
    }
    // Fetch the server's scene (one part a frame) when no copy here is the server's; should the
    // fetching bot have lost its session, the next connected bot starts again.
    if (!world_.loaded && ok() && bot.conn.connected() && scene_fetcher_ < 0 && bot.accepted) find_scene(bot, i);
    if (i == scene_fetcher_ && !world_.loaded && ok()) fetch_scene(bot);
    // Send.
    bot.conn.flush(now);
    if (bot.conn.state() != bot.last_state) on_state_change(bot, i, now);
  }

  // Watch. A new observer may count a few avatars of the current tick a second time.
  if (observer != observer_) watch_.restart();
  observer_ = observer;
  if (observer_ >= 0 && world_.loaded) {
    watch_.observe(library_, world_.scene, world_.world, bots_[static_cast<size_t>(observer_)]->conn);
  }
  ++frames_;
  frame_ms_.add(std::chrono::duration<double, std::milli>(Clock::now() - work_start).count());
}

void BotFleet::wait_until(TimePoint deadline) {
  std::array<epoll_event, 256> events;
  for (;;) {
    const TimePoint now = Clock::now();
    if (now >= deadline) return;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count();
    if (epoll_fd_ < 0 || ms == 0) {
      std::this_thread::sleep_until(deadline);  // the last fraction of a millisecond
      return;
    }
    const int n = ::epoll_wait(epoll_fd_, events.data(), static_cast<int>(events.size()),
                               static_cast<int>(ms));
    if (n <= 0) continue;
    const TimePoint arrived = Clock::now();
    for (int k = 0; k < n; ++k) {
      const int i = static_cast<int>(events[static_cast<size_t>(k)].data.u32);
      Bot& bot = *bots_[static_cast<size_t>(i)];
      bot.conn.poll(arrived);
      if (bot.conn.state() != bot.last_state) on_state_change(bot, i, arrived);
      // Parts of a tick may be superseded before the next frame: check them as they come.
      if (i == observer_ && world_.loaded && bot.conn.connected()) {
        watch_.observe(library_, world_.scene, world_.world, bot.conn);
      }
    }
  }
}

void BotFleet::on_state_change(Bot& bot, int index, TimePoint now) {
  const ClientState was = bot.last_state;
  const ClientState is = bot.conn.state();
  bot.last_state = is;
  if (was == ClientState::kConnected) bot.session_end = now;
  switch (is) {
    case ClientState::kConnected:
      on_accept(bot, index);
      break;
    case ClientState::kRefused:
      if (refusals_.size() < 5 &&
          std::find(refusals_.begin(), refusals_.end(), bot.conn.status_message()) == refusals_.end()) {
        refusals_.push_back(bot.conn.status_message());
      }
      log_once(bot.conn.status_message());
      break;
    case ClientState::kTimedOut:
    case ClientState::kServerGone:
      log_once(bot.conn.status_message());
      // Never accepted too: a handshake lost to a hostile link is tried again, with the same
      // back-off (issue 19: such a bot never tried again).
      if (config_.reconnect) schedule_reconnect(bot, index, now);
      break;
    default:
      break;
  }
}

void BotFleet::schedule_reconnect(Bot& bot, int index, TimePoint now) {
  bot.backoff_s = bot.backoff_s <= 0 ? config_.reconnect_first_s : std::min(2 * bot.backoff_s, config_.reconnect_max_s);
  // Jitter from the bot's own seed: deterministic, and different per bot.
  const double jitter = 0.75 + 0.5 * static_cast<double>(bot_seed(config_.seed, index + bot.reconnects) % 1000) / 1000.0;
  bot.reconnect_at = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(bot.backoff_s * jitter));
  bot.reconnect_pending = true;
}

void BotFleet::on_accept(Bot& bot, int index) {
  bot.accepted = true;
  bot.bytes_in_at_accept = bot.conn.bytes_received();
  bot.bytes_out_at_accept = bot.conn.bytes_sent();
  bot.backoff_s = 0;  // a session again: the next loss starts the back-off afresh
  bot.brain.reset(config_.script, bot_seed(config_.seed, index), 1.0 / config_.rate_hz);
  if (world_.loaded) {
    if (bot.conn.accept().scene != world_.scene_name) {
      log_once("bot " + std::to_string(index) + " was given scene '" + bot.conn.accept().scene +
               "', not '" + world_.scene_name + "': it will stand still");
    }
    return;
  }
  if (scene_fetcher_ < 0) find_scene(bot, index);
}

void BotFleet::find_scene(Bot& bot, int index) {
  // The first Accept names the scene: load it once for every bot (a pause of one frame), from our
  // own file when it is the server's, else fetched from the server by this bot (frame()).
  std::string text;
  const protocol::AcceptInfo& accept = bot.conn.accept();
  if (protocol::own_scene_file_matches(config_.scene_path, accept.scene, accept.scene_hash, text)) {
    load_world(accept.scene, text, bot.conn.status_message());
    return;
  }
  scene_fetcher_ = index;
  log_once("scene '" + accept.scene + "': " + (text.empty() ? "no copy here" : "our copy differs from the server's") +
           ", fetching the server's (" + std::to_string(accept.scene_bytes) + " bytes)");
}

void BotFleet::load_world(const std::string& scene_name, std::string_view text, const std::string& how) {
  std::string error;
  if (!bot_world_load(world_, library_, scene_name, text, config_.script, error)) {
    error_ = error;
    log_once(error);
    return;
  }
  log_once("scene '" + world_.scene_name + "' loaded (" + std::to_string(world_.scene.goals.size()) + " goals); " + how);
}

void BotFleet::fetch_scene(Bot& bot) {
  const protocol::SceneDownload& d = bot.conn.scene_download();
  if (!bot.conn.connected() || !d.started()) {
    scene_fetcher_ = -1;  // another connected bot takes over (frame())
    return;
  }
  if (!d.complete()) {
    bot.conn.request_scene_part();
    return;
  }
  if (!d.verified()) {
    error_ = "the server's scene '" + bot.conn.accept().scene + "' arrived with another hash than its Accept named";
    log_once(error_);
    return;
  }
  load_world(bot.conn.accept().scene, d.bytes(), "fetched from the server");
}

void BotFleet::log_once(const std::string& line) {
  if (std::find(logged_.begin(), logged_.end(), line) != logged_.end()) return;
  if (logged_.size() < 64) logged_.push_back(line);
  if (log_) *log_ << line << '\n' << std::flush;
}

void BotFleet::request_stats() {
  for (auto& bot : bots_) {
    if (bot->conn.connected()) {
      bot->conn.request_stats();
      return;
    }
  }
}

bool BotFleet::stats_arrived() const {
  return std::any_of(bots_.begin(), bots_.end(),
                     [](const auto& b) { return b->conn.server_stats_count() > 0; });
}

void BotFleet::disconnect_all() {
  for (auto& bot : bots_) bot->conn.disconnect();
}

bool BotFleet::all_finished() const {
  if (next_to_start_ < size()) return false;
  return std::all_of(bots_.begin(), bots_.end(),
                     [](const auto& b) { return finished(b->conn.state()) && !b->reconnect_pending; });
}

int BotFleet::connected_now() const {
  return static_cast<int>(std::count_if(bots_.begin(), bots_.end(),
                                        [](const auto& b) { return b->conn.connected(); }));
}

std::string BotFleet::progress_line(TimePoint now) const {
  int connected = 0, refused = 0, lost = 0;
  uint64_t goals = 0, drops = 0;
  double walked = 0;
  protocol::LogHistogram rtt;
  double elapsed = 0;
  for (const auto& b : bots_) {
    const ClientState s = b->conn.state();
    connected += s == ClientState::kConnected;
    refused += s == ClientState::kRefused;
    lost += s == ClientState::kTimedOut || s == ClientState::kServerGone;
    goals += b->brain.targets_reached();
    walked += b->brain.walked_m();
    drops += b->conn.drops().total();
    rtt.merge(b->conn.rtt_ms());
    if (b->started) elapsed = std::max(elapsed, seconds_between(b->conn.started_at(), now));
  }
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "[%6.1f s] connected %d/%d, refused %d, lost %d | goals %llu, walked %.0f m | rtt p50 %.2f p99 %.2f ms"
                " | collisions %llu | drops %llu | frame p99 %.2f ms",
                elapsed, connected, size(), refused, lost, static_cast<unsigned long long>(goals),
                walked, rtt.percentile(0.5), rtt.percentile(0.99),
                static_cast<unsigned long long>(watch_.scene_collisions() + watch_.avatar_contacts()),
                static_cast<unsigned long long>(drops), frame_ms_.percentile(0.99));
  return buf;
}

BotReport BotFleet::report(TimePoint now) const {
  BotReport r;
  r.script = bot_script_name(config_.script);
  r.scene = world_.scene_name;
  r.bots = size();
  r.refusals = refusals_;
  r.error = error_;
  std::vector<double> down, up;
  down.reserve(bots_.size());
  up.reserve(bots_.size());
  r.churns = churns_;
  for (const auto& b : bots_) {
    const auto& c = b->conn;
    if (b->started) r.seconds = std::max(r.seconds, seconds_between(c.started_at(), now));
    r.connected += b->accepted;
    r.connected_at_end += c.connected();
    r.refused += c.state() == ClientState::kRefused;
    r.timed_out += c.state() == ClientState::kTimedOut;
    r.server_gone += c.state() == ClientState::kServerGone;
    r.reconnects += b->reconnects;
    r.goals_reached += b->brain.targets_reached();
    r.walked_m_mean += b->brain.walked_m();
    r.targets_given_up += b->brain.targets_given_up();
    r.plan_failures += b->brain.plan_failures();
    const std::string& why = b->brain.last_plan_failure();
    if (!why.empty() && r.plan_failure_reasons.size() < 3 &&
        std::find(r.plan_failure_reasons.begin(), r.plan_failure_reasons.end(), why) == r.plan_failure_reasons.end())
      r.plan_failure_reasons.push_back(why);
    r.rtt_ms.merge(c.rtt_ms());
    r.snapshot_interval_ms.merge(c.snapshot_interval_ms());
    r.snapshot_packets += c.snapshot_packets();
    r.inputs_sent += c.inputs_sent();
    r.send_failures += c.send_failures();
    for (size_t k = 0; k < r.drops.by_reason.size(); ++k) r.drops.by_reason[k] += c.drops().by_reason[k];
    if (b->accepted) {
      const TimePoint end = c.connected() ? now : b->session_end;
      const double s = seconds_between(c.accepted_at(), end);
      if (s > 0.5) {  // shorter sessions say nothing about a rate
        down.push_back(static_cast<double>(c.bytes_received() - b->bytes_in_at_accept) * 8.0 / 1000.0 / s);
        up.push_back(static_cast<double>(c.bytes_sent() - b->bytes_out_at_accept) * 8.0 / 1000.0 / s);
      }
    }
    if (!r.has_server_stats && c.server_stats_count() > 0) {
      r.has_server_stats = true;
      r.server = c.server_stats();
    }
  }
  if (r.connected > 0) r.walked_m_mean /= r.connected;
  auto median = [](std::vector<double>& v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  r.down_kbps_max = down.empty() ? 0.0 : *std::max_element(down.begin(), down.end());
  r.down_kbps_p50 = median(down);
  r.up_kbps_p50 = median(up);
  r.scene_collisions = watch_.scene_collisions();
  r.avatar_contacts = watch_.avatar_contacts();
  r.avatars_checked = watch_.avatars_checked();
  r.invalid_states = watch_.invalid_states();
  r.frame_ms = frame_ms_;
  r.frames = frames_;
  r.frames_late = frames_late_;
  return r;
}

BotReport bot_fleet_run(const MotionLibrary& library, const BotFleetConfig& config,
                        std::ostream* progress, const std::atomic<bool>* stop) {
  BotFleet fleet(library, config, progress);
  using Clock = BotFleet::Clock;
  const auto period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / config.rate_hz));
  const Clock::time_point start = Clock::now();
  const Clock::time_point end =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(config.seconds));
  Clock::time_point next_frame = start;
  Clock::time_point next_progress = start + std::chrono::seconds(1);

  // Frames until the time is up. A frame that overruns its period delays the next one instead
  // of bunching frames up to catch up (a person does not press keys twice as fast after a stall).
  auto one_frame = [&]() {
    fleet.frame(Clock::now());
    next_frame = std::max(next_frame + period, Clock::now());
    fleet.wait_until(next_frame);
  };
  while (fleet.ok() && Clock::now() < end && !fleet.all_finished() && !(stop && stop->load())) {
    one_frame();
    if (progress && Clock::now() >= next_progress) {
      *progress << fleet.progress_line(Clock::now()) << '\n' << std::flush;
      next_progress += std::chrono::seconds(1);
    }
  }

  // The server's own figures, then goodbye.
  if (fleet.connected_now() > 0) {
    // At least three round trips as measured: over a link with a second of latency each way the
    // answer to a request takes two seconds (issue 19's soak got none in one).
    const double rtt_s = fleet.report(Clock::now()).rtt_ms.percentile(0.99) / 1000.0;
    const double wait_s = std::max(config.stats_wait_s, std::isfinite(rtt_s) ? 3.0 * rtt_s : 0.0);
    const Clock::time_point stats_deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(wait_s));
    // Asked again every 250 ms: on a lossy link the request or its answer may be lost.
    Clock::time_point next_request = Clock::now();
    while (!fleet.stats_arrived() && fleet.connected_now() > 0 && Clock::now() < stats_deadline) {
      if (Clock::now() >= next_request) {
        fleet.request_stats();
        next_request += std::chrono::milliseconds(250);
      }
      one_frame();
    }
  }
  BotReport report = fleet.report(Clock::now());
  fleet.disconnect_all();
  return report;
}

}  // namespace foresight::bots
