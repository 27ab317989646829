#pragma once
// The admin endpoint (docs/SERVER.md "Admin endpoint"): HTTP on its own threads (cpp-httplib),
// on loopback unless told otherwise, every route but the health checks behind a token:
//   GET  /healthz   200 while the process serves (liveness; no token)
//   GET  /readyz    200 while ticks run and a player can join, else 503 (readiness; no token)
//   GET  /metrics   Prometheus text (admin_metrics.hpp)
//   GET  /status    the same figures as JSON
//   POST /command   one admin command line in the body (admin_commands.hpp); the reply as text
//   GET  /          a live page plotting tick time, budget use and tree sizes (polls /status)
// The token goes in `Authorization: Bearer <token>` or `?token=<token>` (the page's own URL).
// The HTTP threads read the metrics the tick thread publishes and post commands to the tick
// thread's queue: they never touch the simulation.
#include "admin_commands.hpp"
#include "admin_metrics.hpp"

#include <memory>
#include <string>
#include <thread>

namespace foresight::server {

class AdminEndpoint {
 public:
  AdminEndpoint(std::shared_ptr<AdminState> state, std::shared_ptr<AdminQueue> queue, std::string token);
  ~AdminEndpoint();
  AdminEndpoint(const AdminEndpoint&) = delete;
  AdminEndpoint& operator=(const AdminEndpoint&) = delete;

  /// Binds (port 0: any free one) and starts serving. False with a reason.
  bool start(const std::string& bind_address, int port, std::string& error);
  int port() const { return port_; }
  const std::string& token() const { return token_; }
  /// How long POST /command waits for the tick thread's reply.
  static constexpr double kCommandTimeoutS = 2.0;
  /// Connections served at once. cpp-httplib gives each connection a thread for as long as it is
  /// open, and a client that sends its request a line a second never hits the per-read timeout:
  /// with two threads, two such clients took the health checks down (issue 19). Past this many
  /// slow or idle connections, new requests wait for one to close (after kIoTimeoutS idle).
  static constexpr int kConnections = 64;
  /// Per read, per write and keep-alive idle time of a connection.
  static constexpr int kIoTimeoutS = 2;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::shared_ptr<AdminState> state_;
  std::shared_ptr<AdminQueue> queue_;
  std::string token_;
  int port_ = -1;
  std::thread thread_;
};

/// 32 random hexadecimal digits (128 bits from the system's random device).
std::string admin_random_token();
/// The live page (admin_page.cpp).
const char* admin_page_html();

}  // namespace foresight::server
