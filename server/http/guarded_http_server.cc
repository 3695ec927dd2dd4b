#include "server/http/guarded_http_server.h"

#include <fcntl.h>
#include <netdb.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <string_view>

#include "absl/strings/ascii.h"
#include "absl/strings/match.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"

namespace seaplan::server {
namespace {

using Clock = std::chrono::steady_clock;

// Runs each job at once on the thread that enqueues it (httplib's accept
// loop), which only hands the socket over.
class InlineTaskQueue final : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> fn) override { fn(); }
  void shutdown() override {}
};

int MillisUntil(Clock::time_point t) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t - Clock::now()).count();
  return static_cast<int>(std::clamp<long long>(ms, 0, 60'000));
}

// poll() on one descriptor; true when `events` are ready (or an error or
// hang-up, which the next read or write reports).
bool PollOne(int fd, short events, int timeout_ms) {
  pollfd p{fd, events, 0};
  while (true) {
    const int n = ::poll(&p, 1, timeout_ms);
    if (n > 0) return true;
    if (n == 0) return false;
    if (errno != EINTR) return true;
  }
}

std::string NumericAddress(const sockaddr_storage& addr, socklen_t len, int* port) {
  char host[NI_MAXHOST] = "";
  char service[NI_MAXSERV] = "";
  if (getnameinfo(reinterpret_cast<const sockaddr*>(&addr), len, host, sizeof(host), service,
                  sizeof(service), NI_NUMERICHOST | NI_NUMERICSERV) != 0) {
    return "";
  }
  int value = 0;
  std::from_chars(service, service + std::string_view(service).size(), value);
  *port = value;
  return host;
}

// What the waiting room knows of the request at the front of a buffer.
struct HeadScan {
  bool complete = false;       // request line and headers arrived
  std::size_t head_bytes = 0;  // including the blank line
  std::size_t body_bytes = 0;  // Content-Length (0 when absent)
  bool streamed_body = false;  // chunked: the worker reads it
  bool bad = false;            // a malformed Content-Length
};

HeadScan ScanHead(const std::string& buffer) {
  HeadScan scan;
  const std::size_t end = buffer.find("\r\n\r\n");
  if (end == std::string::npos) return scan;
  scan.complete = true;
  scan.head_bytes = end + 4;
  for (absl::string_view line : absl::StrSplit(absl::string_view(buffer.data(), end), "\r\n")) {
    const std::size_t colon = line.find(':');
    if (colon == absl::string_view::npos) continue;
    const absl::string_view name = absl::StripAsciiWhitespace(line.substr(0, colon));
    const absl::string_view value = absl::StripAsciiWhitespace(line.substr(colon + 1));
    if (absl::EqualsIgnoreCase(name, "Content-Length")) {
      if (!absl::SimpleAtoi(value, &scan.body_bytes)) scan.bad = true;
    } else if (absl::EqualsIgnoreCase(name, "Transfer-Encoding")) {
      scan.streamed_body = true;
    }
  }
  return scan;
}

// `accept_encoding` without its "br" coding. Debian's cpp-httplib
// compresses with brotli at its slowest setting (quality 11) whenever a
// client accepts it, as browsers do: 1.5 s of a worker's CPU for the
// console's 330 KB script, against tens of milliseconds for gzip, which
// answers instead.
std::string WithoutBrotli(absl::string_view accept_encoding) {
  std::string kept;
  for (absl::string_view coding : absl::StrSplit(accept_encoding, ',')) {
    const absl::string_view name = absl::StripAsciiWhitespace(coding.substr(0, coding.find(';')));
    if (absl::EqualsIgnoreCase(name, "br")) continue;
    absl::StrAppend(&kept, kept.empty() ? "" : ", ", absl::StripAsciiWhitespace(coding));
  }
  return kept;
}

}  // namespace

// One client connection: its socket, TLS session and the bytes read ahead.
struct GuardedHttpServer::Connection {
  int fd = -1;
  SSL* ssl = nullptr;
  bool handshake_done = false;
  std::string buffer;  // read, not yet given to httplib
  // The first byte of the current request (for a new connection: accept).
  Clock::time_point request_started;
  bool request_begun = false;
  Clock::time_point waiting_since;
  Clock::time_point deadline;  // in the waiting room
  short poll_events = POLLIN;
  // Bytes of a next request are already buffered (pipelining): look at
  // them without waiting for the socket.
  bool check_buffer = false;
  int requests_served = 0;

  ~Connection() {
    if (ssl != nullptr) {
      if (handshake_done) SSL_shutdown(ssl);  // best effort: the socket is non-blocking
      SSL_free(ssl);
    }
    if (fd >= 0) {
      ::shutdown(fd, SHUT_RDWR);
      ::close(fd);
    }
  }

  // Reads what is available into `buffer` (at most up to `cap` bytes).
  // Returns false when the connection is finished (EOF, error).
  bool ReadAvailable(std::size_t cap) {
    char chunk[16384];
    while (buffer.size() < cap) {
      const int want = static_cast<int>(std::min(sizeof(chunk), cap - buffer.size()));
      if (ssl != nullptr) {
        const int n = SSL_read(ssl, chunk, want);
        if (n > 0) {
          buffer.append(chunk, static_cast<std::size_t>(n));
          continue;
        }
        const int error = SSL_get_error(ssl, n);
        if (error == SSL_ERROR_WANT_READ) {
          poll_events = POLLIN;
          return true;
        }
        if (error == SSL_ERROR_WANT_WRITE) {
          poll_events = POLLOUT;
          return true;
        }
        return false;
      }
      const ssize_t n = ::recv(fd, chunk, static_cast<std::size_t>(want), 0);
      if (n > 0) {
        buffer.append(chunk, static_cast<std::size_t>(n));
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
        poll_events = POLLIN;
        return true;
      }
      return false;
    }
    return true;
  }

  // Best effort (the socket is non-blocking): a short answer before closing.
  void SendBestEffort(std::string_view response) {
    if (ssl != nullptr) {
      if (handshake_done) SSL_write(ssl, response.data(), static_cast<int>(response.size()));
      return;
    }
    (void)!::send(fd, response.data(), response.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  }
};

namespace {

// When `body_bytes` of a request body begun at `request_started` must have
// arrived: the head's grace, then the minimum rate, within max_body_time.
Clock::time_point BodyDeadline(Clock::time_point request_started, std::size_t body_bytes,
                               const GuardedHttpServer::Limits& limits) {
  const std::chrono::milliseconds at_minimum_rate(
      body_bytes * 1000 / std::max<std::size_t>(1, limits.min_body_bytes_per_s));
  return request_started + limits.head_timeout + std::min(at_minimum_rate, limits.max_body_time);
}

// httplib's view of a connection a worker serves: the bytes the waiting
// room read first, then the socket, with the request's minimum rate.
class GuardedStream final : public httplib::Stream {
 public:
  GuardedStream(GuardedHttpServer::Connection& c, const GuardedHttpServer::Limits& limits)
      : c_(c), limits_(limits) {}

  bool is_readable() const override {
    if (!c_.buffer.empty() || (c_.ssl != nullptr && SSL_pending(c_.ssl) > 0)) return true;
    return PollOne(c_.fd, POLLIN, static_cast<int>(limits_.read_timeout.count()));
  }

  bool is_writable() const override {
    pollfd p{c_.fd, POLLOUT, 0};
    const int n = ::poll(&p, 1, static_cast<int>(limits_.write_timeout.count()));
    return n > 0 && (p.revents & (POLLERR | POLLHUP | POLLNVAL)) == 0;
  }

  ssize_t read(char* ptr, size_t size) override {
    const ssize_t n = ReadSome(ptr, size);
    if (n < 0) failed_ = true;
    return n;
  }

  // A read failed (too slow, stalled, broken): the connection is not reused.
  bool failed() const { return failed_; }

  ssize_t write(const char* ptr, size_t size) override {
    const ssize_t n = WriteSome(ptr, size);
    if (n < 0) failed_ = true;
    return n;
  }

  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage addr{};
    socklen_t len = sizeof(addr);
    if (getpeername(c_.fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0)
      ip = NumericAddress(addr, len, &port);
  }

  void get_local_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage addr{};
    socklen_t len = sizeof(addr);
    if (getsockname(c_.fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0)
      ip = NumericAddress(addr, len, &port);
  }

  socket_t socket() const override { return c_.fd; }

 private:
  ssize_t ReadSome(char* ptr, size_t size) {
    if (!c_.buffer.empty()) {
      const std::size_t n = std::min(size, c_.buffer.size());
      std::copy_n(c_.buffer.data(), n, ptr);
      c_.buffer.erase(0, n);
      return static_cast<ssize_t>(n);
    }
    while (true) {
      // The rate check: the request may have taken head_timeout plus the
      // time its bytes so far need at the minimum rate, and no more than
      // head_timeout plus max_body_time in all.
      const auto allowed = BodyDeadline(c_.request_started, read_from_socket_, limits_);
      if (Clock::now() > allowed) return -1;
      const int wait_ms =
          std::min(MillisUntil(allowed) + 1, static_cast<int>(limits_.read_timeout.count()));
      short wait_for = POLLIN;
      if (c_.ssl != nullptr) {
        const int n = SSL_read(c_.ssl, ptr, static_cast<int>(std::min<size_t>(size, 1 << 30)));
        if (n > 0) return Count(n);
        const int error = SSL_get_error(c_.ssl, n);
        if (error == SSL_ERROR_ZERO_RETURN) return 0;
        if (error == SSL_ERROR_WANT_WRITE) {
          wait_for = POLLOUT;
        } else if (error != SSL_ERROR_WANT_READ) {
          return -1;
        }
      } else {
        const ssize_t n = ::recv(c_.fd, ptr, size, 0);
        if (n >= 0) return n == 0 ? 0 : Count(n);
        if (errno == EINTR) continue;
        if (errno != EAGAIN && errno != EWOULDBLOCK) return -1;
      }
      if (!PollOne(c_.fd, wait_for, wait_ms) && wait_ms >= limits_.read_timeout.count()) return -1;
    }
  }

  ssize_t WriteSome(const char* ptr, size_t size) {
    while (true) {
      short wait_for = POLLOUT;
      if (c_.ssl != nullptr) {
        const int n = SSL_write(c_.ssl, ptr, static_cast<int>(std::min<size_t>(size, 1 << 30)));
        if (n > 0) return n;
        const int error = SSL_get_error(c_.ssl, n);
        if (error == SSL_ERROR_WANT_READ) {
          wait_for = POLLIN;
        } else if (error != SSL_ERROR_WANT_WRITE) {
          return -1;
        }
      } else {
        const ssize_t n = ::send(c_.fd, ptr, size, MSG_NOSIGNAL);
        if (n >= 0) return n;
        if (errno == EINTR) continue;
        if (errno != EAGAIN && errno != EWOULDBLOCK) return -1;
      }
      if (!PollOne(c_.fd, wait_for, static_cast<int>(limits_.write_timeout.count()))) return -1;
    }
  }

  ssize_t Count(ssize_t n) {
    read_from_socket_ += static_cast<std::size_t>(n);
    return n;
  }

  GuardedHttpServer::Connection& c_;
  const GuardedHttpServer::Limits& limits_;
  std::size_t read_from_socket_ = 0;
  bool failed_ = false;
};

constexpr std::string_view kRequestTimeout =
    "HTTP/1.1 408 Request Timeout\r\nConnection: close\r\nContent-Type: text/plain\r\n"
    "Content-Length: 43\r\n\r\nthe request did not arrive in time; closed\n";
constexpr std::string_view kHeadTooLarge =
    "HTTP/1.1 431 Request Header Fields Too Large\r\nConnection: close\r\n"
    "Content-Length: 0\r\n\r\n";

}  // namespace

GuardedHttpServer::GuardedHttpServer(const Limits& limits, SSL_CTX* tls)
    : limits_(limits), tls_(tls) {
  if (tls_ != nullptr) SSL_CTX_up_ref(tls_);
  new_task_queue = [] { return new InlineTaskQueue(); };
  wake_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  waiting_room_ = std::thread([this] { WaitingRoomLoop(); });
  for (int i = 0; i < std::max(1, limits_.worker_threads); ++i)
    workers_.emplace_back([this] { WorkerLoop(); });
}

GuardedHttpServer::~GuardedHttpServer() {
  stop();
  StopConnections();
  if (wake_fd_ >= 0) ::close(wake_fd_);
  if (tls_ != nullptr) SSL_CTX_free(tls_);
}

void GuardedHttpServer::StopConnections() {
  {
    std::lock_guard lock(mu_);
    stopping_ = true;
  }
  ready_cv_.notify_all();
  const std::uint64_t one = 1;
  (void)!::write(wake_fd_, &one, sizeof(one));
  if (waiting_room_.joinable()) waiting_room_.join();
  for (std::thread& t : workers_) {
    if (t.joinable()) t.join();
  }
  std::lock_guard lock(mu_);
  arriving_.clear();
  ready_.clear();
}

bool GuardedHttpServer::process_and_close_socket(socket_t sock) {
  auto c = std::make_unique<Connection>();
  c->fd = sock;
  const int flags = fcntl(sock, F_GETFL, 0);
  fcntl(sock, F_SETFL, flags | O_NONBLOCK);
  if (tls_ != nullptr) {
    c->ssl = SSL_new(tls_);
    if (c->ssl == nullptr || SSL_set_fd(c->ssl, sock) != 1) return false;
    SSL_set_accept_state(c->ssl);
    SSL_set_mode(c->ssl, SSL_MODE_ACCEPT_MOVING_WRITE_BUFFER);
  }
  // A new connection's request (the TLS handshake included) starts now.
  c->request_started = Clock::now();
  c->request_begun = true;
  Wait(std::move(c));
  return true;
}

void GuardedHttpServer::Wait(std::unique_ptr<Connection> c) {
  {
    std::lock_guard lock(mu_);
    if (stopping_) return;  // closed by the destructor
    arriving_.push_back(std::move(c));
  }
  const std::uint64_t one = 1;
  (void)!::write(wake_fd_, &one, sizeof(one));
}

void GuardedHttpServer::WaitingRoomLoop() {
  std::vector<std::unique_ptr<Connection>> waiting;
  std::vector<pollfd> fds;
  while (true) {
    {
      std::lock_guard lock(mu_);
      if (stopping_) return;
      for (auto& c : arriving_) {
        const auto now = Clock::now();
        c->waiting_since = now;
        c->poll_events = POLLIN;
        // A request that has begun (a new connection, pipelined bytes) has
        // its head deadline; an idle keep-alive connection its idle limit.
        if (!c->request_begun && !c->buffer.empty()) {
          c->request_begun = true;
          c->request_started = now;
          c->check_buffer = true;
        }
        c->deadline = c->request_begun ? c->request_started + limits_.head_timeout
                                       : now + limits_.idle_timeout;
        waiting.push_back(std::move(c));
      }
      arriving_.clear();
    }
    // Over the cap: the connections that have waited longest go first.
    if (waiting.size() > limits_.max_waiting_connections) {
      std::sort(waiting.begin(), waiting.end(),
                [](const auto& a, const auto& b) { return a->waiting_since < b->waiting_since; });
      waiting.erase(
          waiting.begin(),
          waiting.begin() + static_cast<long>(waiting.size() - limits_.max_waiting_connections));
    }
    auto next_deadline = Clock::now() + std::chrono::seconds(1);
    fds.assign(1, pollfd{wake_fd_, POLLIN, 0});
    for (const auto& c : waiting) {
      fds.push_back(pollfd{c->fd, c->poll_events, 0});
      next_deadline = std::min(next_deadline, c->deadline);
    }
    const int n = ::poll(fds.data(), fds.size(), MillisUntil(next_deadline) + 1);
    if (n < 0 && errno != EINTR) continue;
    if (fds[0].revents != 0) {
      std::uint64_t count = 0;
      (void)!::read(wake_fd_, &count, sizeof(count));
    }
    const auto now = Clock::now();
    std::vector<std::unique_ptr<Connection>> still_waiting;
    std::vector<std::unique_ptr<Connection>> ready;
    for (std::size_t i = 0; i < waiting.size(); ++i) {
      std::unique_ptr<Connection>& c = waiting[i];
      bool open = true;
      if (fds[i + 1].revents != 0 || c->check_buffer) {
        c->check_buffer = false;
        if (c->ssl != nullptr && !c->handshake_done) {
          const int r = SSL_do_handshake(c->ssl);
          if (r == 1) {
            c->handshake_done = true;
          } else {
            const int error = SSL_get_error(c->ssl, r);
            if (error == SSL_ERROR_WANT_READ) {
              c->poll_events = POLLIN;
            } else if (error == SSL_ERROR_WANT_WRITE) {
              c->poll_events = POLLOUT;
            } else {
              open = false;
            }
          }
        }
        if (open && (c->ssl == nullptr || c->handshake_done)) {
          const std::size_t cap = limits_.max_head_bytes + limits_.max_buffered_body_bytes;
          open = c->ReadAvailable(cap);
          if (!c->request_begun && !c->buffer.empty()) {
            c->request_begun = true;
            c->request_started = now;
            c->deadline = now + limits_.head_timeout;
          }
          const HeadScan scan = ScanHead(c->buffer);
          if (open && !scan.complete && c->buffer.size() >= limits_.max_head_bytes) {
            c->SendBestEffort(kHeadTooLarge);
            open = false;
          }
          if (open && scan.complete) {
            const bool worker_reads_body =
                scan.bad || scan.streamed_body || scan.body_bytes > limits_.max_buffered_body_bytes;
            if (worker_reads_body || c->buffer.size() >= scan.head_bytes + scan.body_bytes) {
              ready.push_back(std::move(c));
              continue;
            }
            // A buffered body: the head's deadline plus its size at the
            // minimum rate.
            c->deadline = BodyDeadline(c->request_started, scan.body_bytes, limits_);
          }
        }
      }
      if (open && now >= c->deadline) {
        if (c->request_begun) c->SendBestEffort(kRequestTimeout);
        open = false;
      }
      if (open) still_waiting.push_back(std::move(c));
    }
    waiting = std::move(still_waiting);
    if (!ready.empty()) {
      {
        std::lock_guard lock(mu_);
        for (auto& c : ready) ready_.push_back(std::move(c));
      }
      ready_cv_.notify_all();
    }
  }
}

void GuardedHttpServer::WorkerLoop() {
  while (true) {
    std::unique_ptr<Connection> c;
    {
      std::unique_lock lock(mu_);
      ready_cv_.wait(lock, [&] { return stopping_ || !ready_.empty(); });
      if (ready_.empty()) return;  // stopping
      c = std::move(ready_.front());
      ready_.pop_front();
    }
    Serve(*c);
    const bool keep = c != nullptr && c->fd >= 0;
    if (keep) {
      c->request_begun = false;
      Wait(std::move(c));
    }
  }
}

void GuardedHttpServer::Serve(Connection& c) {
  GuardedStream stream(c, limits_);
  ++c.requests_served;
  bool stopping = false;
  {
    std::lock_guard lock(mu_);
    stopping = stopping_;
  }
  const bool close_after = stopping || c.requests_served >= limits_.max_requests_per_connection;
  bool connection_closed = false;
  const SSL* ssl = c.ssl;
  // Runs once the head is parsed, before routing; the answer's coding is
  // chosen from Accept-Encoding after the handler.
  const auto setup = [ssl](httplib::Request& req) {
    req.ssl = ssl;
    const auto [first, last] = req.headers.equal_range("Accept-Encoding");
    for (auto it = first; it != last; ++it) it->second = WithoutBrotli(it->second);
  };
  const bool ok = process_request(stream, close_after, connection_closed, setup);
  if (!ok || connection_closed || close_after || stream.failed()) {
    // Closed here rather than by the destructor so that WorkerLoop sees it.
    if (c.ssl != nullptr) {
      SSL_shutdown(c.ssl);
      SSL_free(c.ssl);
      c.ssl = nullptr;
    }
    ::shutdown(c.fd, SHUT_RDWR);
    ::close(c.fd);
    c.fd = -1;
  }
}

}  // namespace seaplan::server
