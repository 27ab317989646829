// The client as a person runs it: a real server and real bots as separate processes, the client
// under Xvfb (Mesa software GL) writing a screenshot, then the PNG checked.
#include "support/test_paths.hpp"
#include "world/data_paths.hpp"

#include <gtest/gtest.h>
#include <stb_image.h>

#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

extern char** environ;

namespace {

std::string bin(const char* name) { return std::string(FORESIGHT_BIN_DIR) + "/" + name; }

// A UDP port nobody uses right now (the kernel's choice; closed again for the server to take).
int free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    if (fd >= 0) ::close(fd);
    return 0;
  }
  ::close(fd);
  return ntohs(addr.sin_port);
}

// Starts a process with its output in `log`; returns its pid (or -1).
pid_t spawn(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

void stop(pid_t pid) {
  if (pid <= 0) return;
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
}

struct Image {
  int w = 0, h = 0;
  unsigned char* pixels = nullptr;
  ~Image() { stbi_image_free(pixels); }
};

// Runs a server (maze) and three bots, then the client under Xvfb with `client_args`, writing
// `name`.png in the scratch folder; loads it into `img`.
void run_client_screenshot(const std::string& name, const std::string& client_args, Image& img) {
  const std::filesystem::path dir = foresight::test::scratch_dir();
  const int port = free_udp_port();
  ASSERT_GT(port, 0);
  const std::string server_address = "127.0.0.1:" + std::to_string(port);
  const pid_t server = spawn({bin("foresight-server"), "--scene", "maze", "--port", std::to_string(port),
                              "--seconds", "120"},
                             (dir / (name + "-server.log")).string());
  ASSERT_GT(server, 0);
  // The bots join 2 s after the client, so the player takes the scene's first spawn place: the
  // same designer camera every run, the avatar in view and not under the debug overlay.
  const pid_t bots = spawn({"/bin/sh", "-c",
                            "sleep 2; exec " + bin("foresight-bots") + " --server " + server_address +
                                " --count 3 --seconds 120"},
                           (dir / (name + "-bots.log")).string());
  const std::string shot = (dir / (name + ".png")).string();
  const std::string log = (dir / (name + "-client.log")).string();
  // Mesa leaks a few bytes at exit: keep LeakSanitizer quiet in sanitizer builds.
  const std::string command = "ASAN_OPTIONS=detect_leaks=0 timeout 120 xvfb-run -a -s '-screen 0 1280x720x24' " +
                              bin("foresight-client") + " --server " + server_address +
                              " --screenshot " + shot + " --frames 60 --timeout 60 " + client_args +
                              " > " + log + " 2>&1";
  const int status = std::system(command.c_str());
  stop(bots);
  stop(server);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "client failed; see " << log;
  int channels = 0;
  img.pixels = stbi_load(shot.c_str(), &img.w, &img.h, &channels, 3);
  ASSERT_NE(img.pixels, nullptr) << "cannot read " << shot;
}

TEST(ClientScreenshot, ShowsTheSceneAndThePlayersAvatar) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  Image img;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("shot", "", img));
  EXPECT_EQ(img.w, 1280);
  EXPECT_EQ(img.h, 720);
  const size_t n = static_cast<size_t>(img.w) * static_cast<size_t>(img.h);
  size_t differs = 0, orange = 0;
  for (size_t i = 0; i < n; ++i) {
    const int r = img.pixels[3 * i], g = img.pixels[3 * i + 1], b = img.pixels[3 * i + 2];
    if (r != img.pixels[0] || g != img.pixels[1] || b != img.pixels[2]) ++differs;
    // The player's orange (1, 0.55, 0.1) under any shading: red strong, green about half, blue low.
    if (r > 80 && g > 0.35 * r && g < 0.75 * r && b < 0.3 * r) ++orange;
  }
  EXPECT_GT(differs, n / 4) << "the image is (nearly) uniform";
  EXPECT_GT(orange, 20u) << "the player's avatar colour does not appear";
}

// --script steers the player: the client replays the maze recording for 4 s, takes the shot then
// and exits 0. (With the follow camera a wall may stand between camera and avatar: where the
// avatar is on screen is not checked.)
TEST(ClientScreenshot, RunsWithAScript) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  const std::string script = "--script " + (foresight::data_dir() / "recordings/maze_eval.json").string();
  Image img;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("script", script + " --screenshot-at-s 4", img));
  EXPECT_EQ(img.w, 1280);
  EXPECT_EQ(img.h, 720);
}

// Counts pixels within `tolerance` of an exact (unlit) colour.
size_t count_colour(const Image& img, int r0, int g0, int b0, int tolerance = 12) {
  const size_t n = static_cast<size_t>(img.w) * static_cast<size_t>(img.h);
  size_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    const int r = img.pixels[3 * i], g = img.pixels[3 * i + 1], b = img.pixels[3 * i + 2];
    if (std::abs(r - r0) <= tolerance && std::abs(g - g0) <= tolerance && std::abs(b - b0) <= tolerance) ++count;
  }
  return count;
}

TEST(ClientScreenshot, TheTreeOverlayDrawsTheTreeAndItsChosenBranch) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps installs it)";
  Image plain, overlay;
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("tree-off", "", plain));
  ASSERT_NO_FATAL_FAILURE(run_client_screenshot("tree-overlay", "--tree-overlay", overlay));
  // The overlay's unlit colours (client_app.cpp): cyan (0.10, 0.85, 0.85) for the tree, yellow
  // (1.00, 0.95, 0.10) for the chosen branch. Without the overlay neither appears.
  const size_t tree = count_colour(overlay, 26, 217, 217), chosen = count_colour(overlay, 255, 242, 26);
  EXPECT_GT(tree, 30u) << "the tree's lines do not appear";
  EXPECT_GT(chosen, 10u) << "the chosen branch is not highlighted";
  EXPECT_LT(count_colour(plain, 26, 217, 217) + count_colour(plain, 255, 242, 26), 10u)
      << "the overlay colours appear without the overlay";
}

}  // namespace
