#include "debug_overlay.hpp"

#include "transport/client_connection.hpp"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace foresight::client {

const char* link_quality_name(LinkQuality quality) {
  switch (quality) {
    case LinkQuality::kGood: return "good";
    case LinkQuality::kFair: return "fair";
    case LinkQuality::kPoor: return "poor";
  }
  return "?";
}

LinkQuality classify_link(bool connected, double rtt_ms, double loss, const QualityThresholds& limits) {
  if (!connected || rtt_ms <= 0) return LinkQuality::kPoor;
  if (rtt_ms < limits.good_rtt_ms && loss < limits.good_loss) return LinkQuality::kGood;
  if (rtt_ms < limits.fair_rtt_ms && loss < limits.fair_loss) return LinkQuality::kFair;
  return LinkQuality::kPoor;
}

void LinkMeter::add(const LinkSample& sample) {
  if (count_ > 0) {
    const LinkSample& last = at(count_ - 1);
    const bool went_back = static_cast<int32_t>(sample.newest_snapshot - last.newest_snapshot) < 0 ||
                           sample.snapshots_received < last.snapshots_received || sample.bytes_down < last.bytes_down ||
                           sample.bytes_up < last.bytes_up || sample.t_s <= last.t_s;
    if (went_back) count_ = 0;  // a new connection: its counters start again
  }
  if (count_ == kWindow) {  // drop the oldest
    first_ = (first_ + 1) % kWindow;
    --count_;
  }
  ring_[static_cast<size_t>((first_ + count_) % kWindow)] = sample;
  ++count_;
  if (count_ < 2) {
    loss_ = down_kbit_s_ = up_kbit_s_ = 0;
    return;
  }
  const LinkSample& newest = at(count_ - 1);
  const LinkSample& previous = at(count_ - 2);
  const double dt = newest.t_s - previous.t_s;
  down_kbit_s_ = static_cast<double>(newest.bytes_down - previous.bytes_down) * 8.0 / 1000.0 / dt;
  up_kbit_s_ = static_cast<double>(newest.bytes_up - previous.bytes_up) * 8.0 / 1000.0 / dt;
  const LinkSample& oldest = at(0);
  // Snapshots are numbered one by one (not by server tick: 20 Hz snapshots on 30 Hz ticks are
  // still consecutive numbers).
  const auto expected = static_cast<double>(newest.newest_snapshot - oldest.newest_snapshot);
  const auto received = static_cast<double>(newest.snapshots_received - oldest.snapshots_received);
  loss_ = expected >= 1.0 ? std::clamp(1.0 - received / expected, 0.0, 1.0) : 0.0;
}

void FrameTimer::tick(double t_s) {
  if (last_s_ >= 0) {
    const double ms = (t_s - last_s_) * 1000.0;
    ms_ = ms_ > 0 ? ms_ + kSmoothing * (ms - ms_) : ms;
  }
  last_s_ = t_s;
}

namespace {

constexpr double kStatsIntervalS = 1.0;   ///< ServerStats requests while the window shows.
constexpr double kSampleIntervalS = 1.0;  ///< LinkMeter samples.
constexpr float kWindowWidth = 300.0f;    ///< Fixed; the height fits the contents.
constexpr float kDotRadius = 7.0f;

ImU32 quality_colour(LinkQuality q) {
  switch (q) {
    case LinkQuality::kGood: return IM_COL32(40, 200, 70, 255);
    case LinkQuality::kFair: return IM_COL32(230, 190, 0, 255);
    case LinkQuality::kPoor: return IM_COL32(220, 50, 50, 255);
  }
  return IM_COL32(128, 128, 128, 255);
}

void draw_dot(ImDrawList* list, ImVec2 centre, LinkQuality q) {
  list->AddCircleFilled(centre, kDotRadius, quality_colour(q), 16);
  list->AddCircle(centre, kDotRadius, IM_COL32(0, 0, 0, 200), 16, 1.5f);
}

unsigned long long ull(uint64_t v) { return static_cast<unsigned long long>(v); }

// The hit flash: red bands fading inwards from the four edges of the screen, under ImGui's
// windows and over the scene.
void draw_hit_flash(ImDrawList* list, ImVec2 size, float strength) {
  if (strength <= 0.0f) return;
  const float band = 0.12f * std::min(size.x, size.y);
  const ImU32 red = IM_COL32(230, 20, 20, static_cast<int>(std::min(strength, 1.0f) * 200.0f));
  const ImU32 clear = IM_COL32(230, 20, 20, 0);
  list->AddRectFilledMultiColor(ImVec2(0, 0), ImVec2(size.x, band), red, red, clear, clear);            // top
  list->AddRectFilledMultiColor(ImVec2(0, size.y - band), size, clear, clear, red, red);                // bottom
  list->AddRectFilledMultiColor(ImVec2(0, 0), ImVec2(band, size.y), red, clear, clear, red);            // left
  list->AddRectFilledMultiColor(ImVec2(size.x - band, 0), size, clear, red, red, clear);                // right
}

}  // namespace

void format_fight_line(const FightFigures& fight, char* out, size_t n) {
  std::snprintf(out, n, "fighters %d, hits taken %llu, dodged %llu", fight.fighters, ull(fight.hits_taken),
                ull(fight.dodged));
}

DebugOverlay::~DebugOverlay() { shutdown(); }

bool DebugOverlay::init(GLFWwindow* window, std::string& error) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in the working directory
  io.LogFilename = nullptr;
  // Keyboard navigation stays off: the window never takes WASD / arrows from the game.
  ImGui::StyleColorsDark();
  if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) {
    ImGui::DestroyContext();
    error = "cannot initialise the ImGui GLFW backend";
    return false;
  }
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    error = "cannot initialise the ImGui OpenGL 3 backend";
    return false;
  }
  window_ = window;
  return true;
}

void DebugOverlay::shutdown() {
  if (!window_) return;
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  window_ = nullptr;
}

bool DebugOverlay::wants_keyboard() const { return window_ && ImGui::GetIO().WantCaptureKeyboard; }
bool DebugOverlay::wants_mouse() const { return window_ && ImGui::GetIO().WantCaptureMouse; }

void DebugOverlay::frame(protocol::ClientConnection& connection, double t_s, bool& tree_overlay,
                         const FightFigures& fight) {
  if (!window_) return;
  frame_timer_.tick(t_s);
  const bool f1 = glfwGetWindowAttrib(window_, GLFW_FOCUSED) && glfwGetKey(window_, GLFW_KEY_F1) == GLFW_PRESS;
  if (f1 && !f1_down_) visible_ = !visible_;
  f1_down_ = f1;

  const bool connected = connection.connected();
  const protocol::AcceptInfo& accept = connection.accept();
  if (!connected) {
    meter_.reset();
  } else if (connection.has_snapshot() && t_s >= next_sample_s_) {
    // From the first snapshot on: a sample taken before it (number 0) anchored the window at 0
    // while snapshots are numbered since the server started, and a session's first seconds read
    // as a third of the snapshots lost ("link poor") on a perfect link.
    meter_.add({t_s, connection.snapshot_tick(), connection.snapshot_ticks(), connection.bytes_received(),
                connection.bytes_sent()});
    next_sample_s_ = t_s + kSampleIntervalS;
  }
  if (connected && visible_ && t_s >= next_stats_request_s_) {
    connection.request_stats();
    next_stats_request_s_ = t_s + kStatsIntervalS;
  }
  const protocol::LogHistogram& rtt = connection.rtt_ms();
  const double rtt_p50 = rtt.count() ? rtt.percentile(0.5) : 0.0;
  quality_ = classify_link(connected, rtt_p50, meter_.loss());

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  draw_hit_flash(ImGui::GetBackgroundDrawList(), ImGui::GetIO().DisplaySize, fight.hit_flash);
  if (!visible_) {
    draw_dot(ImGui::GetForegroundDrawList(), ImVec2(8.0f + kDotRadius, 8.0f + kDotRadius), quality_);
  } else {
    ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(kWindowWidth, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.80f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                                   ImGuiWindowFlags_NoSavedSettings;
    if (ImGui::Begin("Foresight (F1)", nullptr, flags)) {
      // The quality dot, then the state beside it.
      const ImVec2 p = ImGui::GetCursorScreenPos();
      const float line = ImGui::GetTextLineHeight();
      draw_dot(ImGui::GetWindowDrawList(), ImVec2(p.x + kDotRadius, p.y + 0.5f * line), quality_);
      ImGui::Dummy(ImVec2(2.0f * kDotRadius, line));
      ImGui::SameLine();
      ImGui::Text("%s, link %s", protocol::client_state_name(connection.state()), link_quality_name(quality_));
      if (connected) ImGui::Text("scene %s, avatar %u", accept.scene.c_str(), accept.avatar);
      ImGui::Separator();
      ImGui::TextDisabled("network");
      if (rtt.count())
        ImGui::Text("ping       %.0f ms p50, %.0f ms last", rtt_p50, connection.last_rtt_ms());
      else
        ImGui::TextUnformatted("ping       -");
      ImGui::Text("loss       %.1f %% of snapshots", 100.0 * meter_.loss());
      ImGui::Text("down / up  %.0f / %.0f kbit/s", meter_.down_kbit_s(), meter_.up_kbit_s());
      const protocol::LogHistogram& interval = connection.snapshot_interval_ms();
      if (interval.count())
        ImGui::Text("snapshots  every %.1f ms (p50)", interval.percentile(0.5));
      else
        ImGui::TextUnformatted("snapshots  -");
      ImGui::Text("dropped    %llu packets", ull(connection.drops().total()));
      ImGui::Separator();
      ImGui::TextDisabled("server");
      if (connection.server_stats_count() > 0) {
        const protocol::ServerFigures& s = connection.server_stats();
        ImGui::Text("tick       %.2f ms p50, %.2f ms p99", static_cast<double>(s.tick_ms_p50),
                    static_cast<double>(s.tick_ms_p99));
        ImGui::Text("overruns   %llu", ull(s.overruns));
        ImGui::Text("players    %u", s.players);
        ImGui::Text("tree size  %.0f nodes (mean)", static_cast<double>(s.tree_size_mean));
      } else {
        ImGui::TextUnformatted("(waiting for stats)");
      }
      ImGui::Separator();
      ImGui::TextDisabled("fighters");
      char fight_line[96];
      format_fight_line(fight, fight_line, sizeof fight_line);
      ImGui::TextUnformatted(fight_line);
      ImGui::Separator();
      ImGui::TextDisabled("client");
      ImGui::Text("frame      %.1f ms, %.0f fps", frame_timer_.ms(), frame_timer_.fps());
      ImGui::Checkbox("tree overlay (T)", &tree_overlay);
    }
    ImGui::End();
  }
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace foresight::client
