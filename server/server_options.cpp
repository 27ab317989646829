#include "server_options.hpp"

#include "library_build/motion_source_cli.hpp"
#include "lookahead/motion_tree_node.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace foresight::server {

void add_server_options(CLI::App& app, ServerCommandLine& out) {
  ServerConfig& c = out.config;
  app.set_config("--config", "", "TOML file with any of these options (key = value; the command line wins)");
  app.allow_config_extras(false);  // a misspelt key is an error, not silently ignored
  app.add_option("--write-config", out.write_config,
                 "Write every option with its value to this file (a config to start from) and exit")
      ->configurable(false);
  app.add_option("--scene", c.scene, "Scene name (data/scenes/<name>.json) or path")->capture_default_str();
  app.add_option("--bind", c.bind_address, "Address to bind")->capture_default_str();
  app.add_option("--port", c.port, "UDP port (0: any free port)")->capture_default_str();
  app.add_option("--tick-hz", c.tick_hz, "Simulation ticks per second")->check(CLI::Range(1, 240))->capture_default_str();
  app.add_option("--snapshot-hz", c.snapshot_hz, "Snapshots per second (at most the tick rate)")
      ->check(CLI::Range(1, 240))->capture_default_str();
  app.add_option("--max-players", c.max_players, "Players at most")->check(CLI::Range(1, 65535))->capture_default_str();
  app.add_option("--timeout-s", c.session_timeout_s, "Drop a client silent this long")
      ->check(CLI::Range(0.1, 3600.0))->capture_default_str();
  app.add_option("--budget-ms", c.lookahead_budget_ms, "Look-ahead budget per tick at most, ms")
      ->check(CLI::Range(0.0, 1000.0))->capture_default_str();
  app.add_option("--avatar-budget-ms", c.lookahead_avatar_max_ms,
                 "Look-ahead time one avatar may take in a tick, at most, ms (0: its share by need)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--margin-ms", c.tick_safety_margin_ms, "Tick time kept free of look-ahead, ms")
      ->check(CLI::Range(0.0, 1000.0))->capture_default_str();
  app.add_option("--expansions", c.expansions_per_avatar,
                 "Deterministic mode: expansions per avatar per tick instead of a time budget (0: time)")
      ->check(CLI::Range(int64_t{0}, int64_t{10000000}))->capture_default_str();
  app.add_option("--threads", c.threads, "Look-ahead threads, the tick thread included (0: one per core)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--realtime-priority", c.realtime_priority,
                 "Run the tick and look-ahead threads in the real-time FIFO class at this priority (1-99; needs "
                 "CAP_SYS_NICE or ulimit -r; 0: normal class)")
      ->check(CLI::Range(0, 99))->capture_default_str();
  app.add_option("--status-every-s", c.status_every_s, "Log a status line this often (0: never)")
      ->check(CLI::Range(0.0, 86400.0))->capture_default_str();
  app.add_option("--strategy", out.strategy_name, "Exploration strategy: " + strategy_names())->capture_default_str();
  app.add_option("--tree-nodes", c.tree_max_nodes, "Tree node cap per avatar")->check(CLI::Range(16, kMaxTreeNodes))->capture_default_str();
  app.add_option("--resort-ticks", c.resort_interval_ticks,
                 "Re-prioritise trees at least every N ticks (also on command change and before decisions)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  app.add_option("--tree-depth", c.tree_max_depth, "Tree depth cap")->check(CLI::Range(1, 64))->capture_default_str();
  app.add_option("--steer-deg-per-s", c.steer_deg_per_s,
                 "Steering mode: turn the playing motion towards the command up to this fast (0: off; 540: the lab's responsive controller)")
      ->check(CLI::Range(0.0f, 3600.0f))
      ->capture_default_str();
  app.add_option("--max-challenges-per-tick", c.max_challenges_per_tick,
                 "Answers to unverified addresses per tick at most (challenges, bad-cookie refusals)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--max-joins-per-tick", c.max_joins_per_tick, "Verified joins admitted per tick at most (the rest queue)")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  app.add_option("--max-packets-per-s", c.max_packets_per_s, "Per-session packet rate limit")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  app.add_option("--locomotion", out.locomotion_name,
                 "How players move: graph (motion tree), terrain (footstep planner; no fighters), auto (terrain "
                 "when the scene has terrain)")
      ->transform(CLI::IsMember({"auto", "graph", "terrain"}, CLI::ignore_case))
      ->capture_default_str();
  app.add_option("--fighters", c.fighters,
                 "NPC fighters (-1: one per NPC spawn of the scene; N: that many)")
      ->check(CLI::Range(-1, 256))
      ->capture_default_str();
  app.add_flag("--fighters-supervised", out.supervised, "Fighters strike only when ordered (no own policy)");
  app.add_option("--fighter-cooldown-s", c.fighter_cooldown_s, "Fighters' own policy: seconds between strikes")
      ->check(CLI::Range(0.0, 600.0))
      ->capture_default_str();
  app.add_option("--fighter-morphology", c.fighter_morphology,
                 "Fighters' body (-1: they cycle through the five morphologies; 0-4: all this one)")
      ->check(CLI::Range(-1, 4))
      ->capture_default_str();
  app.add_option("--fighter-hit-radius-m", c.fighter_hit_radius_m, "A strike hits when the effector comes this close to the head")
      ->check(CLI::Range(0.01, 2.0))
      ->capture_default_str();
  app.add_option("--fighter-strikes", c.fighter_strikes, "Extra BVH folder of strikes for the fighters");
  app.add_option("--fighter-strikes-sidecar", c.fighter_strikes_sidecar,
                 "Annotations of that folder (default: its strikes.json, else automatic splitting)");
  app.add_option("--fighter-cache", c.fighter_cache_dir, "Folder caching the fighters' pose clusters");
  app.add_flag("--console", out.console,
               "Read supervisor commands from stdin (fighters, order <id|all> punch|kick|any, auto on|off, help)");
  app.add_option("--seconds", out.seconds, "Stop after this long (0: run until Ctrl-C)")->check(CLI::Range(0.0, 1e7));
  app.add_option("--interest-radius-m", c.interest_radius_m,
                 "Avatars this near a client's own go into its every snapshot, the rest every --far-every (0: all always)")
      ->check(CLI::Range(0.0, 10000.0))
      ->capture_default_str();
  app.add_option("--far-every", c.far_every, "Farther avatars go into every N-th snapshot (0: never)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  app.add_option("--far-radius-m", c.far_radius_m,
                 "With --interest-radius-m: avatars farther than this are not sent at all (0: no limit)")
      ->check(CLI::Range(0.0, 10000.0))
      ->capture_default_str();
  app.add_flag_callback(
      "--agones", [&c] { c.agones_sdk_port = 0; },
      "Run as an Agones GameServer: Ready, Health and Shutdown to the SDK sidecar (AGONES_SDK_HTTP_PORT)");
  app.add_option("--agones-health-s", c.agones_health_s, "With --agones: seconds between health pings")
      ->check(CLI::Range(0.01, 60.0))
      ->capture_default_str();
  app.add_option("--admin-bind", c.admin_bind, "Admin endpoint address (loopback by default)")->capture_default_str();
  app.add_option("--admin-port", c.admin_port, "Admin endpoint TCP port (-1: none; 0: any free port)")
      ->check(CLI::Range(-1, 65535))
      ->capture_default_str();
  app.add_option("--admin-token", c.admin_token, "Admin token (empty: a random one, printed at start)");
  add_motion_source_options(app, c.motions);
  // NaN passes every range check (every comparison with it is false) and infinity passes the
  // open-ended ones: every number must be finite, on the command line and in the TOML file.
  const CLI::Validator finite(
      [](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        return end != text.c_str() && *end == '\0' && !std::isfinite(v) ? std::string("must be a finite number")
                                                                      : std::string();
      },
      "FINITE");
  // An unset variable (`--port "$PORT"`) reads as 0 ("any free port"): an empty number is an error.
  const CLI::Validator given([](std::string& text) { return text.empty() ? std::string("must not be empty") : std::string(); },
                             "GIVEN");
  for (CLI::Option* option : app.get_options()) {
    const std::string type = option->get_type_name();
    if (type.find("FLOAT") != std::string::npos) option->check(finite);
    if (type.find("FLOAT") != std::string::npos || type.find("INT") != std::string::npos) option->check(given);
  }
}

std::string server_config_text(const CLI::App& app) {
  // Options without a value (no --motions folder, detected BVH units) stay commented out: an
  // empty value read back would mean "this folder" or "no unit".
  std::string out = "# foresight-server configuration: foresight-server --config FILE (command-line options win)\n";
  std::istringstream lines(app.config_to_str(true, true));
  for (std::string line; std::getline(lines, line);) {
    const bool empty_value = line.size() > 3 && line.compare(line.size() - 3, 3, "=\"\"") == 0;
    out += (empty_value ? "# " : "") + line + "\n";
  }
  return out;
}

bool finish_server_options(ServerCommandLine& out, std::string& error) {
  out.config.fighters_auto_attack = !out.supervised;
  const std::string& l = out.locomotion_name;
  out.config.locomotion = l == "graph" ? Locomotion::kGraph : l == "terrain" ? Locomotion::kTerrain : Locomotion::kAuto;
  return strategy_parse(out.strategy_name, out.config.strategy, error);
}

}  // namespace foresight::server
