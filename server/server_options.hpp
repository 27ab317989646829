#pragma once
// The server's command line and config file (docs/SERVER.md "Configuration"): every tunable of
// ServerConfig is an option; `--config FILE` reads the same options from a TOML file (CLI11's
// config reader: `key = value` lines, the option names without dashes), and the command line wins
// over the file. `--write-config FILE` writes every option with its current value (defaults,
// the file's and the command line's) and a comment saying what it is, as a starting point.
#include "server_config.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace foresight::server {

/// What the command line asks for: the config, and what main() does with it.
struct ServerCommandLine {
  ServerConfig config;
  std::string strategy_name = "command";
  std::string locomotion_name = "auto";
  double seconds = 0;      ///< Stop after this long (0: until a signal).
  bool console = false;    ///< Supervisor commands from stdin.
  bool supervised = false; ///< Fighters strike only when ordered.
  std::string write_config;  ///< Write the effective configuration here and exit.
};

/// Declares every option on `app`, bound to `out` (call once, before app.parse).
void add_server_options(CLI::App& app, ServerCommandLine& out);
/// The configuration `app` holds now (after a parse: defaults, file and command line), as a config
/// file with a comment per option.
std::string server_config_text(const CLI::App& app);
/// After a successful parse: the values that need more than a conversion. False with a reason.
bool finish_server_options(ServerCommandLine& out, std::string& error);

}  // namespace foresight::server
