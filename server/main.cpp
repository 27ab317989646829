// foresight-server: the authoritative server (docs/SERVER.md).
//   foresight-server [--scene maze] [--port 7777] [--tick-hz 30] [--snapshot-hz 20] [--threads 1]
//                    [--budget-ms 20] [--strategy command] [--motions DIR] ...
#include "library/motion_source_cli.hpp"
#include "server.hpp"

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <thread>

namespace {
foresight::server::Server* g_server = nullptr;
extern "C" void on_signal(int) {
  if (g_server != nullptr) g_server->stop();  // an atomic store: async-signal-safe
}
}  // namespace

int main(int argc, char** argv) {
  using namespace foresight;
  server::ServerConfig config;
  CLI::App app{"Foresight authoritative server: players and bots connect over UDP"};
  app.add_option("--scene", config.scene, "Scene name (data/scenes/<name>.json) or path")->capture_default_str();
  app.add_option("--bind", config.bind_address, "Address to bind")->capture_default_str();
  app.add_option("--port", config.port, "UDP port (0: any free port)")->capture_default_str();
  app.add_option("--tick-hz", config.tick_hz, "Simulation ticks per second")->check(CLI::Range(1, 240))->capture_default_str();
  app.add_option("--snapshot-hz", config.snapshot_hz, "Snapshots per second (at most the tick rate)")
      ->check(CLI::Range(1, 240))->capture_default_str();
  app.add_option("--max-players", config.max_players, "Players at most")->check(CLI::Range(1, 65535))->capture_default_str();
  app.add_option("--timeout-s", config.session_timeout_s, "Drop a client silent this long")
      ->check(CLI::Range(0.1, 3600.0))->capture_default_str();
  app.add_option("--budget-ms", config.lookahead_budget_ms, "Look-ahead budget per tick at most, ms")
      ->check(CLI::Range(0.0, 1000.0))->capture_default_str();
  app.add_option("--margin-ms", config.tick_safety_margin_ms, "Tick time kept free of look-ahead, ms")
      ->check(CLI::Range(0.0, 1000.0))->capture_default_str();
  app.add_option("--expansions", config.expansions_per_avatar,
                 "Deterministic mode: expansions per avatar per tick instead of a time budget (0: time)")
      ->check(CLI::Range(int64_t{0}, int64_t{10000000}))->capture_default_str();
  app.add_option("--threads", config.threads, "Look-ahead threads, the tick thread included (0: one per core)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--status-every-s", config.status_every_s, "Log a status line this often (0: never)")
      ->check(CLI::Range(0.0, 86400.0))->capture_default_str();
  std::string strategy = "command";
  app.add_option("--strategy", strategy, "Exploration strategy: " + strategy_names())->capture_default_str();
  app.add_option("--tree-nodes", config.tree_max_nodes, "Tree node cap per avatar")->check(CLI::Range(16, 1 << 20))->capture_default_str();
  app.add_option("--resort-ticks", config.resort_interval_ticks,
                 "Re-prioritise trees at least every N ticks (also on command change and before decisions)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--tree-depth", config.tree_max_depth, "Tree depth cap")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--max-packets-per-s", config.max_packets_per_s, "Per-session packet rate limit")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  const std::map<std::string, server::Locomotion> locomotions{
      {"auto", server::Locomotion::kAuto}, {"graph", server::Locomotion::kGraph}, {"terrain", server::Locomotion::kTerrain}};
  app.add_option("--locomotion", config.locomotion,
                 "How players move: graph (motion tree), terrain (footstep planner; no fighters), auto (terrain "
                 "when the scene has terrain)")
      ->transform(CLI::CheckedTransformer(locomotions, CLI::ignore_case))
      ->capture_default_str();
  double seconds = 0;
  app.add_option("--fighters", config.fighters,
                 "NPC fighters (-1: one per NPC spawn of the scene; N: that many)")
      ->check(CLI::Range(-1, 256))
      ->capture_default_str();
  bool supervised = false;
  app.add_flag("--fighters-supervised", supervised, "Fighters strike only when ordered (no own policy)");
  app.add_option("--fighter-cooldown-s", config.fighter_cooldown_s, "Fighters' own policy: seconds between strikes")
      ->check(CLI::Range(0.0, 600.0))
      ->capture_default_str();
  app.add_option("--fighter-strikes", config.fighter_strikes, "Extra BVH folder of strikes for the fighters");
  app.add_option("--fighter-strikes-sidecar", config.fighter_strikes_sidecar,
                 "Annotations of that folder (default: its strikes.json, else automatic splitting)");
  app.add_option("--fighter-cache", config.fighter_cache_dir, "Folder caching the fighters' pose clusters");
  bool console = false;
  app.add_flag("--console", console,
               "Read supervisor commands from stdin (fighters, order <id|all> punch|kick|any, auto on|off, help)");
  app.add_option("--seconds", seconds, "Stop after this long (0: run until Ctrl-C)")->check(CLI::Range(0.0, 1e7));
  add_motion_source_options(app, config.motions);
  CLI11_PARSE(app, argc, argv);
  config.fighters_auto_attack = !supervised;

  std::string error;
  if (!strategy_parse(strategy, config.strategy, error)) {
    std::fprintf(stderr, "foresight-server: %s\n", error.c_str());
    return 2;
  }
  server::Server server;
  if (!server.start(config, error)) {
    std::fprintf(stderr, "foresight-server: %s\n", error.c_str());
    return 1;
  }
  g_server = &server;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::thread timer;
  if (seconds > 0) {
    timer = std::thread([&server, seconds] {
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
      server.stop();
    });
    timer.detach();
  }
  if (console) {
    // Detached: a blocking read of stdin cannot be interrupted portably. It holds the queue, not
    // the server, so a line typed during shutdown goes nowhere instead of into a dead object.
    std::thread([queue = server.admin_queue()] {
      std::string line;
      while (std::getline(std::cin, line)) queue->post(line);
    }).detach();
  }
  server.run();
  const auto& c = server.counters();
  const auto& s = server.tick_stats();
  std::fprintf(stderr,
               "foresight-server: stopped after %llu ticks; tick ms p50 %.2f p99 %.2f max %.2f, %llu overruns; "
               "%llu sessions opened, %llu timed out; %llu packets in, %llu dropped; %llu avatar contacts\n",
               static_cast<unsigned long long>(s.ticks()), s.tick_ms_percentile(50), s.tick_ms_percentile(99),
               s.tick_ms_max(), static_cast<unsigned long long>(s.overruns()),
               static_cast<unsigned long long>(c.sessions_opened),
               static_cast<unsigned long long>(c.sessions_timed_out),
               static_cast<unsigned long long>(c.packets_in), static_cast<unsigned long long>(c.drops.total()),
               static_cast<unsigned long long>(c.avatar_contacts));
  g_server = nullptr;
  return 0;
}
