#include "admin_http.hpp"

#include <httplib.h>

#include <future>
#include <random>

namespace foresight::server {

namespace {

// Compares in time independent of where the strings differ (no timing oracle for the token).
bool same_secret(const std::string& a, const std::string& b) {
  unsigned diff = a.size() == b.size() ? 0u : 1u;
  for (size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned>(a[i] ^ (i < b.size() ? b[i] : 0));
  return diff == 0;
}

}  // namespace

struct AdminEndpoint::Impl {
  httplib::Server http;
};

std::string admin_random_token() {
  std::random_device rd;
  static const char* hex = "0123456789abcdef";
  std::string t;
  for (int i = 0; i < 4; ++i) {
    const uint32_t v = rd();
    for (int k = 0; k < 8; ++k) t += hex[(v >> (4 * k)) & 15u];
  }
  return t;
}

AdminEndpoint::AdminEndpoint(std::shared_ptr<AdminState> state, std::shared_ptr<AdminQueue> queue, std::string token)
    : impl_(std::make_unique<Impl>()), state_(std::move(state)), queue_(std::move(queue)), token_(std::move(token)) {}

AdminEndpoint::~AdminEndpoint() {
  impl_->http.stop();
  if (thread_.joinable()) thread_.join();
}

bool AdminEndpoint::start(const std::string& bind_address, int port, std::string& error) {
  httplib::Server& http = impl_->http;
  http.new_task_queue = [] { return new httplib::ThreadPool(kConnections); };
  http.set_read_timeout(kIoTimeoutS, 0);
  http.set_write_timeout(kIoTimeoutS, 0);
  http.set_keep_alive_timeout(kIoTimeoutS);
  const auto authorised = [this](const httplib::Request& req, httplib::Response& res) {
    const std::string bearer = req.get_header_value("Authorization");
    const bool ok = (bearer.rfind("Bearer ", 0) == 0 && same_secret(bearer.substr(7), token_)) ||
                    (req.has_param("token") && same_secret(req.get_param_value("token"), token_));
    if (!ok) {
      res.status = 401;
      res.set_content("admin token required (Authorization: Bearer <token>, or ?token=)\n", "text/plain");
    }
    return ok;
  };
  http.Get("/healthz", [](const httplib::Request&, httplib::Response& res) { res.set_content("ok\n", "text/plain"); });
  http.Get("/readyz", [this](const httplib::Request&, httplib::Response& res) {
    const AdminMetrics m = state_->read();
    const bool ticking = std::chrono::steady_clock::now() - m.published < std::chrono::seconds(1);
    const bool room = m.players + m.joins_waiting < m.max_players;
    res.status = ticking && room ? 200 : 503;
    res.set_content(!ticking ? "not ticking\n" : room ? "ready\n" : "full\n", "text/plain");
  });
  http.Get("/metrics", [this, authorised](const httplib::Request& req, httplib::Response& res) {
    if (authorised(req, res)) res.set_content(admin_metrics_prometheus(state_->read()), "text/plain; version=0.0.4");
  });
  http.Get("/status", [this, authorised](const httplib::Request& req, httplib::Response& res) {
    if (authorised(req, res)) res.set_content(admin_metrics_json(state_->read()), "application/json");
  });
  http.Post("/command", [this, authorised](const httplib::Request& req, httplib::Response& res) {
    if (!authorised(req, res)) return;
    if (req.body.empty() || req.body.size() > 256 || req.body.find('\n') != std::string::npos) {
      res.status = 400;
      res.set_content("one command line (at most 256 bytes) in the body; 'help' lists them\n", "text/plain");
      return;
    }
    auto reply = std::make_shared<std::promise<AdminReply>>();
    std::future<AdminReply> answer = reply->get_future();
    queue_->post(req.body, [reply](const AdminReply& r) { reply->set_value(r); });
    if (answer.wait_for(std::chrono::duration<double>(kCommandTimeoutS)) != std::future_status::ready) {
      res.status = 504;
      res.set_content("the tick thread did not answer (server stopping or stalled?)\n", "text/plain");
      return;
    }
    const AdminReply r = answer.get();
    res.status = r.status;
    res.set_content(r.text + "\n", "text/plain");
  });
  http.Get("/", [authorised](const httplib::Request& req, httplib::Response& res) {
    if (authorised(req, res)) res.set_content(admin_page_html(), "text/html; charset=utf-8");
  });
  // cpp-httplib sets SO_REUSEPORT, with which a second server binds the same port without a
  // word and the kernel splits the requests between the two: only SO_REUSEADDR (a restart may
  // take a port still in TIME_WAIT), so a port another process listens on is an error.
  http.set_socket_options([](socket_t sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  port_ = port == 0 ? http.bind_to_any_port(bind_address) : (http.bind_to_port(bind_address, port) ? port : -1);
  if (port_ < 0) {
    error = "admin endpoint: cannot bind " + bind_address + ":" + std::to_string(port) +
            " (not an address of this machine, or the port is taken by another process)";
    return false;
  }
  thread_ = std::thread([this] { impl_->http.listen_after_bind(); });
  return true;
}

}  // namespace foresight::server
