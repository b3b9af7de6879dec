/// @file
/// @brief `pkm serve`'s HTTP transport (cpp-httplib): binds, passes each request to the Api and
/// streams the campaign's server-sent events. docs/web.md.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "pkm/server/api.hpp"

namespace pkm::server {

/// An HTTP server around one Api.
class HttpServer {
 public:
  /// Throws as Api's constructor.
  explicit HttpServer(ServerOptions options);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  /// Binds options.host:options.port (0: a free port) and returns the port bound. Throws
  /// pkm::IoError when the address cannot be bound.
  int bind();
  /// Serves until stop() (blocking; call bind() first).
  void listen();
  /// Stops listen() from another thread or a signal handler's thread; idempotent.
  void stop();
  /// The API (for tests).
  [[nodiscard]] Api& api();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace pkm::server
