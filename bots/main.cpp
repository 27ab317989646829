// foresight-bots: N scripted clients in one process against a running server (docs/BOTS.md).
//   foresight-bots --server 127.0.0.1:7777 --count 50 --script goals --seconds 30 [--json]
//                  [--motions DIR] [--seed S] [--rate 30]
// Progress (one line a second) and events go to stderr; the summary to stdout, and with --json
// one JSON object as the last line of stdout. Exit status: 0 when at least one bot connected and
// nothing stopped the run, 1 otherwise (nobody connected, the scene or recording missing, ...).
#include "bot_fleet.hpp"
#include "connect_flood.hpp"
#include "library_build/library_source.hpp"
#include "library_build/motion_source_cli.hpp"
#include "transport/impairment_cli.hpp"

#include <CLI/CLI.hpp>

#include <sys/resource.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>

namespace {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }

/// Each bot holds a UDP socket plus the descriptors of its Asio context (4 in all): 400 bots
/// exceed the common soft limit of 1024, so raise it as far as the hard limit allows.
void raise_descriptor_limit(int bots) {
  rlimit limit{};
  if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return;
  const rlim_t wanted = static_cast<rlim_t>(bots) * 6 + 64;
  if (limit.rlim_cur >= wanted) return;
  limit.rlim_cur = limit.rlim_max == RLIM_INFINITY ? wanted : std::min(wanted, limit.rlim_max);
  ::setrlimit(RLIMIT_NOFILE, &limit);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace foresight;
  CLI::App app{"foresight-bots: scripted clients over the real protocol, with a summary of what they measured"};
  bots::BotFleetConfig config;
  std::string server = "127.0.0.1:7777", script = "goals";
  bool json = false;
  app.add_option("--server", server, "Server address host:port")->capture_default_str();
  app.add_option("--count", config.count, "Bots (each its own UDP socket and session)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  app.add_option("--script", script, "replay | goals | wander | dodge")
      ->check(CLI::IsMember({"replay", "goals", "wander", "dodge"}))
      ->capture_default_str();
  app.add_option("--seconds", config.seconds, "Run time")->check(CLI::Range(0.0, 1e6))->capture_default_str();
  app.add_option("--scene", config.scene_path,
                 "Our copy of the server's scene file (default: data/scenes/<its name>.json); fetched from "
                 "the server when missing or different");
  app.add_option("--seed", config.seed, "Seed of goal choices and human behaviour")->capture_default_str();
  app.add_option("--rate", config.rate_hz, "Bot frames (Inputs) per second")
      ->check(CLI::Range(1.0, 240.0))
      ->capture_default_str();
  // The network impairment layer (docs/RELIABILITY.md), both directions of every bot's link.
  protocol::add_impairment_options(app, config.impairment);
  app.add_option("--churn-s", config.churn_every_s, "Soak: every this many seconds one bot leaves and joins again")
      ->check(CLI::Range(0.0, 3600.0));
  app.add_flag("!--no-reconnect", config.reconnect, "Bots whose server went away stay gone (no back-off retries)");
  double flood_per_s = 0;
  app.add_option("--flood-connects-per-s", flood_per_s,
                 "Meanwhile flood the server with this many bogus connects a second (0: none)")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  // The same library options as the server: the library's content hash must match its own.
  MotionSource source;
  add_motion_source_options(app, source);
  app.add_flag("--json", json, "Print one JSON object as the last line of stdout");
  CLI11_PARSE(app, argc, argv);

  std::string error;
  if (!protocol::parse_endpoint(server, config.server, error)) {
    std::fprintf(stderr, "foresight-bots: --server: %s\n", error.c_str());
    return 1;
  }
  bots::bot_script_from_name(script, config.script);

  MotionLibrary library;
  if (!motion_library_load(source, library, error)) {
    std::fprintf(stderr, "foresight-bots: %s\n", error.c_str());
    return 1;
  }
  std::fprintf(stderr, "foresight-bots: %d bots (%s) -> %s for %.1f s, library '%s' %016llx\n",
               config.count, script.c_str(), server.c_str(), config.seconds, library.name.c_str(),
               static_cast<unsigned long long>(library.content_hash));

  raise_descriptor_limit(config.count);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  bots::ConnectFlood flood;
  if (flood_per_s > 0) {
    if (!flood.start(config.server, library.content_hash, flood_per_s, error)) {
      std::fprintf(stderr, "foresight-bots: flood: %s\n", error.c_str());
      return 1;
    }
    std::fprintf(stderr, "foresight-bots: flooding %s with %.0f bogus connects a second\n", server.c_str(), flood_per_s);
  }
  const bots::BotReport report = bots::bot_fleet_run(library, config, &std::cerr, &g_stop);
  flood.stop();

  bots::bot_report_print(report, std::cout);
  if (flood_per_s > 0) std::cout << "flood: " << flood.sent() << " bogus connects sent\n";
  if (json) {
    auto j = bots::bot_report_json(report);
    if (flood_per_s > 0) j["flood_connects_sent"] = flood.sent();
    std::cout << j.dump() << '\n';
  }
  std::cout << std::flush;
  return report.connected > 0 && report.error.empty() ? 0 : 1;
}
