// The connection gate of `pkm serve`'s HTTP transport (http_server.cpp; docs/web.md,
// "Robustness"): no worker thread waits for a client. One thread watches every open connection
// (epoll) until it has sent a complete request header; only then does a worker serve the request
// (httplib's request processing), after which the connection comes back to the gate to wait for
// the next. A connection that has not completed its header within the header timeout, or stays
// idle past the idle timeout, is closed; when one client holds more waiting connections than its
// cap, its oldest waiting one is closed. So idle, silent or slow-header connections cost a file
// descriptor and a few bytes each, never a worker, and the next real request is served at once.
#pragma once

#include <httplib.h>

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace pkm::server::detail {

/// The gate's limits.
struct GateOptions {
  double header_timeout_s = 5.0;    ///< from accept (or the last response) to a complete header
  double idle_timeout_s = 5.0;      ///< a kept-alive connection waiting for its next request
  double read_timeout_s = 5.0;      ///< one read or write of a request being served
  double request_timeout_s = 60.0;  ///< reading one request's body, in all
  std::size_t max_header_bytes = 64 * 1024;  ///< a longer header is answered 431 and closed
  std::size_t max_waiting_per_client = 64;   ///< waiting connections of one address
  std::size_t max_requests_per_connection = 1000;
  std::size_t workers = 32;  ///< threads that serve requests (long jobs hold one each)
};

/// One client connection: its socket and the bytes read ahead of httplib (the next request's).
struct Connection {
  int fd = -1;
  std::string peer_ip, local_ip;
  int peer_port = 0, local_port = 0;
  std::string buffer;        ///< bytes received; those from `start` on are not consumed yet
  std::size_t start = 0;     ///< the first unconsumed byte of buffer
  std::size_t requests = 0;  ///< requests served on it
  std::chrono::steady_clock::time_point waiting_since;
  [[nodiscard]] std::size_t unread() const { return buffer.size() - start; }
  /// Marks `n` unread bytes consumed.
  void consume(std::size_t n);
  ~Connection();
};

/// Serves one request of a connection whose buffer holds a complete header: returns true when
/// the connection may wait for another (keep-alive).
using ServeRequest = std::function<bool(Connection&, httplib::Stream&)>;

/// A Stream over a Connection for httplib's request processing: reads the buffer first, then the
/// socket (each read waits at most read_timeout_s, and all of a request's reads
/// request_timeout_s); writes wait at most read_timeout_s each.
class ConnectionStream : public httplib::Stream {
 public:
  ConnectionStream(Connection& c, const GateOptions& o);
  bool is_readable() const override;
  bool is_writable() const override;
  ssize_t read(char* ptr, size_t size) override;
  ssize_t write(const char* ptr, size_t size) override;
  void get_remote_ip_and_port(std::string& ip, int& port) const override;
  void get_local_ip_and_port(std::string& ip, int& port) const override;
  socket_t socket() const override;

 private:
  Connection& c_;
  const GateOptions& o_;
  std::chrono::steady_clock::time_point deadline_;
};

/// The gate: its thread and the workers.
class ConnectionGate {
 public:
  ConnectionGate(GateOptions options, ServeRequest serve);
  ~ConnectionGate();
  ConnectionGate(const ConnectionGate&) = delete;
  ConnectionGate& operator=(const ConnectionGate&) = delete;

  /// Takes an accepted socket (the gate closes it).
  void admit(int fd);
  /// Closes every connection (those being served are shut down, so their writes fail) and stops
  /// the threads.
  void stop();

  struct State;

 private:
  std::shared_ptr<State> state_;
};

}  // namespace pkm::server::detail
