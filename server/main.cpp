// foresight-server: the authoritative server (docs/SERVER.md).
//   foresight-server [--scene maze] [--port 7777] [--tick-hz 30] [--snapshot-hz 20] [--threads 1]
//                    [--budget-ms 20] [--strategy command] [--motions DIR] ...
#include "io/text_file.hpp"
#include "process_memory.hpp"
#include "server.hpp"
#include "server_options.hpp"

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <iostream>
#include <string>
#include <thread>

namespace {
foresight::server::Server* g_server = nullptr;
extern "C" void on_signal(int) {
  if (g_server != nullptr) g_server->stop();  // an atomic store: async-signal-safe
}
}  // namespace

// Exit codes (docs/SERVER.md "Exit codes"): what an orchestrator or a script can act on.
enum ExitCode : int {
  kExitStopped = 0,      ///< Stopped as asked (signal, --seconds), or --help / --write-config done.
  kExitStartFailed = 1,  ///< The configuration was fine but the server could not start or write.
  kExitBadConfig = 2,    ///< The command line or the --config file is wrong: fix it, do not retry.
};

int main(int argc, char** argv) {
  foresight::server::configure_heap();  // before anything is allocated (process_memory.hpp)
  using namespace foresight;
  server::ServerCommandLine cli;
  CLI::App app{"Foresight authoritative server: players and bots connect over UDP"};
  server::add_server_options(app, cli);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 prints the help, or the mistake with the --help hint; its own codes (105, 106, ...)
    // name its internal error classes, so every mistake is one code here.
    return app.exit(e) == 0 ? kExitStopped : kExitBadConfig;
  }
  std::string error;
  if (!server::finish_server_options(cli, error)) {
    std::fprintf(stderr, "foresight-server: %s\n", error.c_str());
    return kExitBadConfig;
  }
  if (!cli.write_config.empty()) {
    if (!file_write_atomic(cli.write_config, server::server_config_text(app), error)) {
      std::fprintf(stderr, "foresight-server: %s\n", error.c_str());
      return kExitStartFailed;
    }
    std::fprintf(stderr, "foresight-server: wrote %s\n", cli.write_config.c_str());
    return kExitStopped;
  }
  const server::ServerConfig& config = cli.config;
  const double seconds = cli.seconds;
  const bool console = cli.console;
  server::Server server;
  if (!server.start(config, error)) {
    std::fprintf(stderr, "foresight-server: %s\n", error.c_str());
    return kExitStartFailed;
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
  return kExitStopped;
}
