// The server's configuration (docs/SERVER.md "Configuration"): a TOML file sets any option, the
// command line wins, mistakes are reported (unknown key, bad value, missing file), and the file
// --write-config writes reads back to the same configuration.
#include "server_options.hpp"

#include "io/text_file.hpp"
#include "support/test_paths.hpp"

#include <gtest/gtest.h>

#include <sys/socket.h>
#include <sys/wait.h>
#include <netinet/in.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <memory>

namespace foresight::server {
namespace {

struct Parsed {
  std::unique_ptr<CLI::App> app = std::make_unique<CLI::App>("test");
  ServerCommandLine cli;
  std::string error;  ///< Parse or finish error; empty on success.
};

std::unique_ptr<Parsed> parse(std::vector<std::string> args) {
  auto p = std::make_unique<Parsed>();
  add_server_options(*p->app, p->cli);
  std::vector<const char*> argv{"foresight-server"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  try {
    p->app->parse(static_cast<int>(argv.size()), argv.data());
    finish_server_options(p->cli, p->error);
  } catch (const CLI::ParseError& e) {
    p->error = e.what();
  }
  return p;
}

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("foresight-options-" + name);
  std::string error;
  EXPECT_TRUE(file_write_atomic(path, text, error)) << error;
  return path;
}

// The exit status of the real binary run with `args`, its output discarded.
int server_exit_code(const std::string& args) {
  const std::string cmd = std::string(FORESIGHT_BIN_DIR) + "/foresight-server " + args + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// docs/SERVER.md "Exit codes": 0 stopped as asked, 1 could not start, 2 a configuration mistake
// (issue 19: CLI11's own 105-114 came out, and the docs said otherwise).
TEST(ServerOptions, ExitCodesSayWhatWentWrong) {
  EXPECT_EQ(server_exit_code("--help"), 0);
  EXPECT_EQ(server_exit_code("--budget-ms nan"), 2);
  EXPECT_EQ(server_exit_code("--no-such-option"), 2);
  EXPECT_EQ(server_exit_code("--port ''"), 2);
  EXPECT_EQ(server_exit_code("--config /no/such/file.toml"), 2);
  EXPECT_EQ(server_exit_code("--tick-hz 30 --threshold -5"), 2);
  // A UDP port another socket holds: the configuration is fine, the start is not.
  const int held = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(held, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(held, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  socklen_t len = sizeof addr;
  ASSERT_EQ(::getsockname(held, reinterpret_cast<sockaddr*>(&addr), &len), 0);
  EXPECT_EQ(server_exit_code("--scene arena --bind 127.0.0.1 --port " + std::to_string(ntohs(addr.sin_port)) +
                             " --admin-port -1 --seconds 5"),
            1);
  ::close(held);
  EXPECT_EQ(server_exit_code("--scene no-such-scene --admin-port -1 --seconds 5"), 1);
  EXPECT_EQ(server_exit_code("--scene arena --port 0 --admin-port -1 --seconds 0.3"), 0);
}

TEST(ServerOptions, TheFileSetsOptionsAndTheCommandLineWins) {
  const auto file = write_file("a.toml", "tick-hz = 20\nbudget-ms = 3.5\nstrategy = \"statistic\"\n"
                                         "locomotion = \"terrain\"\nmax-players = 64\n");
  const auto p = parse({"--config", file.string(), "--tick-hz", "60"});
  ASSERT_TRUE(p->error.empty()) << p->error;
  const ServerConfig& c = p->cli.config;
  EXPECT_EQ(c.tick_hz, 60);  // the command line
  EXPECT_DOUBLE_EQ(c.lookahead_budget_ms, 3.5);
  EXPECT_EQ(c.strategy, Strategy::kStatistic);
  EXPECT_EQ(c.locomotion, Locomotion::kTerrain);
  EXPECT_EQ(c.max_players, 64);
  EXPECT_EQ(c.snapshot_hz, ServerConfig{}.snapshot_hz);  // untouched: the default
}

// NaN passes every range check and infinity the open-ended ones (issue 19): a server started with
// --budget-ms nan ran avatars that never moved while /readyz said ready. Every number must be
// finite, on the command line and in the file; an empty number (an unset variable) is an error.
TEST(ServerOptions, EveryNumberIsFiniteAndGiven) {
  for (const char* option : {"--budget-ms", "--timeout-s", "--steer-deg-per-s", "--margin-ms", "--status-every-s",
                             "--fighter-cooldown-s", "--interest-radius-m", "--threshold", "--bvh-scale"})
    for (const char* value : {"nan", "NaN", "inf", "-inf"}) {
      const auto r = parse({option, value});
      EXPECT_NE(r->error.find(option), std::string::npos) << option << " " << value << ": " << r->error;
    }
  EXPECT_NE(parse({"--config", write_file("nan.toml", "budget-ms = nan\n").string()})->error.find("finite"),
            std::string::npos);
  EXPECT_NE(parse({"--port", ""})->error.find("must not be empty"), std::string::npos);
  EXPECT_FALSE(parse({"--threshold", "-5"})->error.empty());
  EXPECT_TRUE(parse({"--budget-ms", "2.5", "--timeout-s", "30", "--threshold", "0.05"})->error.empty());
}

TEST(ServerOptions, MistakesInTheFileAreReported) {
  EXPECT_NE(parse({"--config", write_file("b.toml", "tick-hz = 30\nbugdet-ms = 4\n").string()})->error.find("bugdet"),
            std::string::npos);
  EXPECT_FALSE(parse({"--config", write_file("c.toml", "tick-hz = \"fast\"\n").string()})->error.empty());
  EXPECT_FALSE(parse({"--config", write_file("d.toml", "tick-hz = 100000\n").string()})->error.empty());
  EXPECT_FALSE(parse({"--config", write_file("e.toml", "strategy = \"greedy\"\n").string()})->error.empty());
  EXPECT_FALSE(parse({"--steer-deg-per-s", "-90"})->error.empty());
  EXPECT_FALSE(parse({"--config", "/nonexistent/foresight.toml"})->error.empty());
}

TEST(ServerOptions, TheWrittenConfigReadsBackToTheSameConfiguration) {
  const auto first = parse({"--tick-hz", "45", "--strategy", "hybrid", "--budget-ms", "2.25", "--scene", "arena",
                            "--fighters", "3", "--locomotion", "GRAPH", "--steer-deg-per-s", "540"});
  ASSERT_TRUE(first->error.empty()) << first->error;
  const std::string text = server_config_text(*first->app);
  EXPECT_NE(text.find("# Look-ahead budget per tick"), std::string::npos) << "each option is explained";
  const auto again = parse({"--config", write_file("f.toml", text).string()});
  ASSERT_TRUE(again->error.empty()) << again->error << "\n" << text;
  const ServerConfig& a = first->cli.config;
  const ServerConfig& b = again->cli.config;
  EXPECT_EQ(b.tick_hz, 45);
  EXPECT_EQ(b.strategy, Strategy::kHybrid);
  EXPECT_EQ(b.locomotion, Locomotion::kGraph);
  EXPECT_DOUBLE_EQ(b.lookahead_budget_ms, 2.25);
  EXPECT_EQ(b.scene, "arena");
  EXPECT_EQ(b.fighters, 3);
  EXPECT_FLOAT_EQ(b.steer_deg_per_s, 540.0f);
  EXPECT_FLOAT_EQ(ServerConfig{}.steer_deg_per_s, 540.0f) << "steering mode is on by default (issue 18)";
  EXPECT_EQ(b.port, a.port);
  EXPECT_EQ(b.max_packets_per_s, a.max_packets_per_s);
  EXPECT_EQ(b.tree_max_nodes, a.tree_max_nodes);
  EXPECT_EQ(b.motions.motions_dir, a.motions.motions_dir);
}

TEST(ServerOptions, TheShippedThousandPlayerConfigReads) {
  const auto p = parse({"--config", (test::source_dir() / "deploy" / "field-1000.toml").string()});
  ASSERT_TRUE(p->error.empty()) << p->error;
  const ServerConfig& c = p->cli.config;
  EXPECT_EQ(c.scene, "field");
  EXPECT_GE(c.max_players, 1000);
  EXPECT_DOUBLE_EQ(c.lookahead_budget_ms, 6.0);
  EXPECT_FLOAT_EQ(c.interest_radius_m, 8.0f);
  EXPECT_EQ(c.far_every, 8);
  EXPECT_FLOAT_EQ(c.far_radius_m, 16.0f);
}

TEST(ServerOptions, HelpListsTheOptionsWithTheirDefaults) {
  const auto p = parse({});
  const std::string help = p->app->help();
  for (const char* s : {"--config", "--write-config", "--budget-ms", "--tick-hz", "--locomotion", "--strategy"})
    EXPECT_NE(help.find(s), std::string::npos) << s;
  EXPECT_NE(help.find("=30"), std::string::npos) << "the tick rate's default";
}

}  // namespace
}  // namespace foresight::server
