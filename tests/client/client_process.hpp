#pragma once
// The client as a person runs it: a real server (and real bots) as separate processes, the client
// under Xvfb (Mesa software GL) writing a screenshot, then the PNG loaded for checks. Shared by
// the screenshot tests.
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

namespace foresight::test {

inline std::string bin(const char* name) { return std::string(FORESIGHT_BIN_DIR) + "/" + name; }

inline bool have_xvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

// A UDP port nobody uses right now (the kernel's choice; closed again for the server to take).
inline int free_udp_port() {
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
inline pid_t spawn(const std::vector<std::string>& args, const std::string& log) {
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

inline void stop(pid_t pid) {
  if (pid <= 0) return;
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
}

struct Image {
  int w = 0, h = 0;
  unsigned char* pixels = nullptr;
  Image() = default;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
  ~Image() { stbi_image_free(pixels); }
  size_t size() const { return static_cast<size_t>(w) * static_cast<size_t>(h); }
};

struct ClientRun {
  std::filesystem::path dir;    ///< Scratch folder (one per test): PNG and logs land here.
  std::string name;             ///< File stem of this run's PNG and logs.
  std::string client_args;      ///< Besides --server, --screenshot, --frames 60, --timeout 60.
  int bots = 3;                 ///< 0: the player alone (nothing else moves).
  std::string scene = "maze";
  std::vector<std::string> server_args;  ///< Extra server options (e.g. {"--fighters", "0"}).
};

// Runs a server and `run.bots` bots, then the client under Xvfb, writing run.name.png in run.dir;
// loads it into `img`.
inline void run_client_screenshot(const ClientRun& run, Image& img) {
  const int port = free_udp_port();
  ASSERT_GT(port, 0);
  const std::string server_address = "127.0.0.1:" + std::to_string(port);
  std::vector<std::string> server_args = {bin("foresight-server"), "--scene", run.scene, "--port",
                                          std::to_string(port), "--seconds", "120", "--admin-port", "-1"};
  server_args.insert(server_args.end(), run.server_args.begin(), run.server_args.end());
  const pid_t server = spawn(server_args, (run.dir / (run.name + "-server.log")).string());
  ASSERT_GT(server, 0);
  // The bots join 2 s after the client, so the player takes the scene's first spawn place: the
  // same designer camera every run, the avatar in view and not under the debug overlay.
  pid_t bots = -1;
  if (run.bots > 0)
    bots = spawn({"/bin/sh", "-c",
                  "sleep 2; exec " + bin("foresight-bots") + " --server " + server_address + " --count " +
                      std::to_string(run.bots) + " --seconds 120"},
                 (run.dir / (run.name + "-bots.log")).string());
  const std::string shot = (run.dir / (run.name + ".png")).string();
  const std::string log = (run.dir / (run.name + "-client.log")).string();
  // Mesa leaks a few bytes at exit: keep LeakSanitizer quiet in sanitizer builds.
  const std::string command = "ASAN_OPTIONS=detect_leaks=0 timeout 120 xvfb-run -a -s '-screen 0 1280x720x24' " +
                              bin("foresight-client") + " --server " + server_address +
                              " --screenshot " + shot + " --frames 60 --timeout 60 " + run.client_args +
                              " > " + log + " 2>&1";
  const int status = std::system(command.c_str());
  stop(bots);
  stop(server);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "client failed; see " << log;
  int channels = 0;
  img.pixels = stbi_load(shot.c_str(), &img.w, &img.h, &channels, 3);
  ASSERT_NE(img.pixels, nullptr) << "cannot read " << shot;
}

// Share of pixels that differ from the image's first pixel (1 - share of a uniform image).
inline double non_uniform_share(const Image& img) {
  size_t differs = 0;
  for (size_t i = 0; i < img.size(); ++i) {
    const unsigned char* p = img.pixels + 3 * i;
    if (p[0] != img.pixels[0] || p[1] != img.pixels[1] || p[2] != img.pixels[2]) ++differs;
  }
  return img.size() ? static_cast<double>(differs) / static_cast<double>(img.size()) : 0.0;
}

// Pixels of the player's orange (1, 0.55, 0.1) under any shading: red strong, green about half,
// blue low.
inline size_t orange_pixels(const Image& img, int x0 = 0, int x1 = -1) {
  // Columns [x0, x1) only (x1 < 0: to the right edge): one frame of a --strip.
  if (x1 < 0) x1 = img.w;
  size_t orange = 0;
  for (size_t i = 0; i < img.size(); ++i) {
    const int x = static_cast<int>(i % static_cast<size_t>(img.w));
    if (x < x0 || x >= x1) continue;
    const int r = img.pixels[3 * i], g = img.pixels[3 * i + 1], b = img.pixels[3 * i + 2];
    if (r > 80 && g > 0.35 * r && g < 0.75 * r && b < 0.3 * r) ++orange;
  }
  return orange;
}

// Pixels of the NPC fighters' crimson (0.72, 0.06, 0.10), or the brighter red of a striking one
// (1.00, 0.16, 0.12), under any shading: red strong, green and blue both low. Not the player's
// orange (green half of red), the idle-fallback red (0.70, 0.30, 0.30: green 0.43 of red) nor
// walls or floor. Only pixels at least `margin` px inside the image's edges (the hit flash tints
// the edges red) and outside the debug overlay's corner (up to `overlay_w` x `overlay_h`).
inline size_t fighter_pixels(const Image& img, int margin = 0, int overlay_w = 0, int overlay_h = 0) {
  size_t count = 0;
  for (int y = margin; y < img.h - margin; ++y) {
    for (int x = margin; x < img.w - margin; ++x) {
      if (x < overlay_w && y < overlay_h) continue;
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(img.w) + static_cast<size_t>(x);
      const int r = img.pixels[3 * i], g = img.pixels[3 * i + 1], b = img.pixels[3 * i + 2];
      if (r > 60 && g < 0.25 * r && b < 0.3 * r) ++count;
    }
  }
  return count;
}

}  // namespace foresight::test
