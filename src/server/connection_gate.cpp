// The connection gate (connection_gate.hpp): an epoll thread holds the waiting connections, a
// pool of workers serves complete requests.
#include "connection_gate.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <map>
#include <set>
#include <thread>
#include <vector>

namespace pkm::server::detail {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kReadChunk = 64 * 1024;

int millisecondsOf(double seconds) {
  return static_cast<int>(std::clamp(seconds * 1000.0, 0.0, 3.6e6));
}

/// The address and port of a socket's end (`peer`: the other end).
void addressOf(int fd, bool peer, std::string& ip, int& port) {
  sockaddr_storage a{};
  socklen_t n = sizeof(a);
  auto* any = reinterpret_cast<sockaddr*>(&a);
  if ((peer ? ::getpeername(fd, any, &n) : ::getsockname(fd, any, &n)) != 0) return;
  char text[INET6_ADDRSTRLEN] = {};
  if (a.ss_family == AF_INET) {
    const auto* v4 = reinterpret_cast<const sockaddr_in*>(&a);
    ::inet_ntop(AF_INET, &v4->sin_addr, text, sizeof(text));
    port = ntohs(v4->sin_port);
  } else if (a.ss_family == AF_INET6) {
    const auto* v6 = reinterpret_cast<const sockaddr_in6*>(&a);
    ::inet_ntop(AF_INET6, &v6->sin6_addr, text, sizeof(text));
    port = ntohs(v6->sin6_port);
  }
  ip = text;
}

/// Waits up to `ms` for `events` on `fd`: true when they came.
bool waitFor(int fd, short events, int ms) {
  pollfd p{fd, events, 0};
  int r = 0;
  do {
    r = ::poll(&p, 1, ms);
  } while (r < 0 && errno == EINTR);
  return r > 0;
}

/// Whether the buffer's unread bytes hold a complete request header.
bool headerComplete(const Connection& c) {
  return c.buffer.find("\r\n\r\n", c.start) != std::string::npos;
}

}  // namespace

void Connection::consume(std::size_t n) {
  start += n;
  if (start == buffer.size()) {
    buffer.clear();
    start = 0;
  }
}

Connection::~Connection() {
  if (fd >= 0) ::close(fd);
}

ConnectionStream::ConnectionStream(Connection& c, const GateOptions& o)
    : c_(c),
      o_(o),
      deadline_(Clock::now() + std::chrono::milliseconds(millisecondsOf(o.request_timeout_s))) {}

bool ConnectionStream::is_readable() const {
  return c_.unread() > 0 || waitFor(c_.fd, POLLIN, millisecondsOf(o_.read_timeout_s));
}

bool ConnectionStream::is_writable() const {
  if (!waitFor(c_.fd, POLLOUT, millisecondsOf(o_.read_timeout_s))) return false;
  // Writable is not alive: a peer that has closed reads as end of file.
  if (!waitFor(c_.fd, POLLIN, 0)) return true;
  char byte = 0;
  const ssize_t n = ::recv(c_.fd, &byte, 1, MSG_PEEK | MSG_DONTWAIT);
  return n > 0 || (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK));
}

ssize_t ConnectionStream::read(char* ptr, size_t size) {
  while (c_.unread() == 0) {
    const auto left = std::chrono::duration<double>(deadline_ - Clock::now()).count();
    if (left <= 0.0) return -1;  // the request took too long in all
    if (!waitFor(c_.fd, POLLIN, millisecondsOf(std::min(left, o_.read_timeout_s)))) return -1;
    char chunk[kReadChunk];
    const ssize_t n = ::recv(c_.fd, chunk, sizeof(chunk), 0);
    if (n == 0) return 0;
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) continue;
      return -1;
    }
    c_.buffer.assign(chunk, static_cast<std::size_t>(n));
    c_.start = 0;
  }
  const std::size_t n = std::min(size, c_.unread());
  std::copy_n(c_.buffer.data() + c_.start, n, ptr);
  c_.consume(n);
  return static_cast<ssize_t>(n);
}

ssize_t ConnectionStream::write(const char* ptr, size_t size) {
  std::size_t done = 0;
  while (done < size) {
    if (!waitFor(c_.fd, POLLOUT, millisecondsOf(o_.read_timeout_s))) return -1;
    const ssize_t n = ::send(c_.fd, ptr + done, size - done, MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) continue;
      return -1;
    }
    done += static_cast<std::size_t>(n);
  }
  return static_cast<ssize_t>(done);
}

void ConnectionStream::get_remote_ip_and_port(std::string& ip, int& port) const {
  ip = c_.peer_ip;
  port = c_.peer_port;
}

void ConnectionStream::get_local_ip_and_port(std::string& ip, int& port) const {
  ip = c_.local_ip;
  port = c_.local_port;
}

socket_t ConnectionStream::socket() const { return c_.fd; }

struct ConnectionGate::State : std::enable_shared_from_this<State> {
  GateOptions o;
  ServeRequest serve;
  int epoll = -1, wake = -1;
  std::mutex mutex;  // guards waiting and serving
  std::map<int, std::shared_ptr<Connection>> waiting;
  std::set<int> serving;
  std::atomic<bool> stopping{false};
  std::unique_ptr<httplib::ThreadPool> workers;
  std::thread thread;

  /// Starts waiting on `c` (under mutex): closes the client's oldest waiting connection first
  /// when it is at its cap.
  void wait(std::shared_ptr<Connection> c);
  /// Reads what `fd` has sent; dispatches it to a worker once its header is complete.
  void readable(int fd);
  void dispatch(std::shared_ptr<Connection> c);
  void expire();
  void loop();
};

void ConnectionGate::State::wait(std::shared_ptr<Connection> c) {
  c->waiting_since = Clock::now();
  std::size_t mine = 0;
  auto oldest = waiting.end();
  for (auto it = waiting.begin(); it != waiting.end(); ++it)
    if (it->second->peer_ip == c->peer_ip) {
      ++mine;
      if (oldest == waiting.end() || it->second->waiting_since < oldest->second->waiting_since)
        oldest = it;
    }
  if (mine >= o.max_waiting_per_client && oldest != waiting.end()) {
    ::epoll_ctl(epoll, EPOLL_CTL_DEL, oldest->first, nullptr);
    waiting.erase(oldest);  // closes it
  }
  epoll_event e{};
  e.events = EPOLLIN | EPOLLRDHUP;
  e.data.fd = c->fd;
  if (::epoll_ctl(epoll, EPOLL_CTL_ADD, c->fd, &e) != 0) return;  // closes it
  waiting[c->fd] = std::move(c);
}

void ConnectionGate::State::readable(int fd) {
  const std::lock_guard lock(mutex);
  const auto it = waiting.find(fd);
  if (it == waiting.end()) return;
  Connection& c = *it->second;
  bool closed = false;
  while (c.unread() <= o.max_header_bytes) {
    char chunk[16 * 1024];
    const ssize_t n = ::recv(fd, chunk, sizeof(chunk), MSG_DONTWAIT);
    if (n > 0) {
      c.buffer.append(chunk, static_cast<std::size_t>(n));
      continue;
    }
    closed = n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR);
    break;
  }
  if (headerComplete(c)) {
    ::epoll_ctl(epoll, EPOLL_CTL_DEL, fd, nullptr);
    std::shared_ptr<Connection> ready = std::move(it->second);
    waiting.erase(it);
    dispatch(std::move(ready));
    return;
  }
  if (c.unread() > o.max_header_bytes) {
    static const char k431[] =
        "HTTP/1.1 431 Request Header Fields Too Large\r\nContent-Length: 0\r\nConnection: "
        "close\r\n\r\n";
    (void)::send(fd, k431, sizeof(k431) - 1, MSG_NOSIGNAL | MSG_DONTWAIT);
    closed = true;
  }
  if (closed) {
    ::epoll_ctl(epoll, EPOLL_CTL_DEL, fd, nullptr);
    waiting.erase(it);
  }
}

void ConnectionGate::State::dispatch(std::shared_ptr<Connection> c) {
  serving.insert(c->fd);
  workers->enqueue([self = shared_from_this(), c] {
    bool again = false;
    {
      ConnectionStream stream(*c, self->o);
      again = self->serve(*c, stream);
    }
    ++c->requests;
    const std::lock_guard lock(self->mutex);
    self->serving.erase(c->fd);
    if (!again || self->stopping || c->requests >= self->o.max_requests_per_connection) return;
    if (headerComplete(*c))
      self->dispatch(c);  // the next request came with this one
    else
      self->wait(c);
  });
}

void ConnectionGate::State::expire() {
  const std::lock_guard lock(mutex);
  const auto now = Clock::now();
  for (auto it = waiting.begin(); it != waiting.end();) {
    const Connection& c = *it->second;
    const double limit = c.requests == 0 || c.unread() > 0 ? o.header_timeout_s : o.idle_timeout_s;
    // An idle keep-alive connection whose next request has just arrived (not read yet: its
    // event comes with the next epoll_wait) is not closed under it: a browser that sent a POST
    // on it would wait for an answer that never comes. If the header then stays incomplete, the
    // header timeout, counted from the same moment, closes it at the next pass.
    // (Polled only for a connection about to be closed: not every waiting one every pass.)
    const bool expired = std::chrono::duration<double>(now - c.waiting_since).count() > limit;
    if (expired && !(c.requests > 0 && c.unread() == 0 && waitFor(it->first, POLLIN, 0))) {
      ::epoll_ctl(epoll, EPOLL_CTL_DEL, it->first, nullptr);
      it = waiting.erase(it);
    } else {
      ++it;
    }
  }
}

void ConnectionGate::State::loop() {
  std::vector<epoll_event> events(256);
  while (!stopping) {
    const int n = ::epoll_wait(epoll, events.data(), static_cast<int>(events.size()), 100);
    for (int i = 0; i < n; ++i)
      if (events[static_cast<std::size_t>(i)].data.fd != wake)
        readable(events[static_cast<std::size_t>(i)].data.fd);
    expire();
  }
}

ConnectionGate::ConnectionGate(GateOptions options, ServeRequest serve)
    : state_(std::make_shared<State>()) {
  state_->o = options;
  state_->serve = std::move(serve);
  state_->epoll = ::epoll_create1(EPOLL_CLOEXEC);
  state_->wake = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  epoll_event e{};
  e.events = EPOLLIN;
  e.data.fd = state_->wake;
  ::epoll_ctl(state_->epoll, EPOLL_CTL_ADD, state_->wake, &e);
  state_->workers = std::make_unique<httplib::ThreadPool>(options.workers);
  state_->thread = std::thread([s = state_.get()] { s->loop(); });
}

ConnectionGate::~ConnectionGate() {
  stop();
  ::close(state_->epoll);
  ::close(state_->wake);
}

void ConnectionGate::admit(int fd) {
  auto c = std::make_shared<Connection>();
  c->fd = fd;
  addressOf(fd, true, c->peer_ip, c->peer_port);
  addressOf(fd, false, c->local_ip, c->local_port);
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK);
  if (state_->stopping) return;  // closes it
  const std::lock_guard lock(state_->mutex);
  state_->wait(std::move(c));
}

void ConnectionGate::stop() {
  if (state_->stopping.exchange(true)) return;
  const std::uint64_t one = 1;
  (void)::write(state_->wake, &one, sizeof(one));
  state_->thread.join();
  {
    const std::lock_guard lock(state_->mutex);
    state_->waiting.clear();
    // Requests being served (a campaign's or a routine's stream): their writes now fail.
    for (const int fd : state_->serving) ::shutdown(fd, SHUT_RDWR);
  }
  state_->workers->shutdown();
}

}  // namespace pkm::server::detail
