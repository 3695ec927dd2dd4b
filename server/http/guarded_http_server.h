// An httplib::Server whose connections take a worker thread only while a
// request that has fully arrived is served, so that slow or idle clients
// cannot hold the server's threads (slow-loris).
//
// cpp-httplib gives each accepted connection a pool thread for its whole
// life: reading the headers, the body, and waiting between keep-alive
// requests. Its read timeout bounds each read, not the request, so a client
// that sends a byte every few seconds keeps a thread for ever, and as many
// such clients as threads stop the gateway. Here instead:
//   - accepted connections go to one "waiting room" thread (poll), which does
//     the TLS handshake and reads the request head (and a body up to
//     Limits::max_buffered_body_bytes) without blocking; the head must
//     arrive within head_timeout of its first byte (of the connection, for a
//     new one: the handshake counts), a buffered body at min_body_bytes_per_s
//     after that; a connection that misses its deadline gets 408 and is
//     closed;
//   - only a connection whose request is complete (or whose larger body is
//     to be streamed) is handed to a worker thread, which serves that one
//     request with httplib's own request processing; a body the worker
//     reads must keep min_body_bytes_per_s on average (head_timeout is the
//     grace) and be complete within max_body_time after the grace, else the
//     read fails and the connection is closed: a client sending a large
//     body at just the minimum rate holds a worker for max_body_time at
//     most, not for size / rate;
//   - between keep-alive requests the connection is back in the waiting
//     room (idle_timeout), holding no thread;
//   - the waiting room holds at most max_waiting_connections; a new one
//     beyond that closes the connection that has waited longest.
// Handlers, routes and TLS (mutual TLS included: Request::ssl is set) work
// as on httplib::Server / SSLServer, except that answers are never
// brotli-compressed: "br" is dropped from Accept-Encoding as the head is
// parsed (httplib compresses brotli at its slowest setting; gzip answers).
//
// Lifecycle: bind and listen as on httplib::Server (listen_after_bind runs
// the accept loop); stop() ends the accept loop; StopConnections() then
// closes waiting connections and joins the workers once their requests end.
// Thread-safety: as httplib::Server.
#pragma once

#include <httplib.h>
#include <openssl/ssl.h>

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace seaplan::server {

class GuardedHttpServer final : public httplib::Server {
 public:
  struct Limits {
    int worker_threads = 16;
    // The request head (and a new connection's TLS handshake) must arrive
    // within this time of its first byte.
    std::chrono::milliseconds head_timeout{10000};
    // After the head, the body must arrive at this average rate at least
    // (head_timeout is the grace)...
    std::size_t min_body_bytes_per_s = 64 * 1024;
    // ... and be complete this long after the grace, whatever its size
    // (at 64 KiB/s, bodies above 18.75 MiB need more than the minimum rate).
    std::chrono::milliseconds max_body_time{300000};
    // A keep-alive connection with no new request for this long is closed.
    std::chrono::milliseconds idle_timeout{5000};
    // A single read or write that makes no progress for this long fails.
    std::chrono::milliseconds read_timeout{10000};
    std::chrono::milliseconds write_timeout{10000};
    // Bodies up to this size are read by the waiting room, before a worker
    // is taken; larger ones (chart uploads) are read by the worker.
    std::size_t max_buffered_body_bytes = 1u << 20;
    // Request line and headers together; beyond: 431 and closed.
    std::size_t max_head_bytes = 64u << 10;
    std::size_t max_waiting_connections = 4096;
    int max_requests_per_connection = 100;
  };

  // `tls`: serve HTTPS with this context (the server takes a reference);
  // nullptr: plain HTTP.
  GuardedHttpServer(const Limits& limits, SSL_CTX* tls);
  ~GuardedHttpServer() override;
  GuardedHttpServer(const GuardedHttpServer&) = delete;
  GuardedHttpServer& operator=(const GuardedHttpServer&) = delete;

  // Closes the waiting connections, lets the workers finish the requests
  // they serve, joins them. Call after stop(); idempotent.
  void StopConnections();

  struct Connection;

 private:
  // httplib calls this on its accept thread (the task queue runs jobs
  // inline): the connection goes to the waiting room at once.
  bool process_and_close_socket(socket_t sock) override;

  void WaitingRoomLoop();
  void WorkerLoop();
  // Back to the waiting room (a new connection, or a served keep-alive one).
  void Wait(std::unique_ptr<Connection> connection);
  void Serve(Connection& connection);

  const Limits limits_;
  SSL_CTX* tls_ = nullptr;
  int wake_fd_ = -1;  // eventfd: wakes the waiting room

  std::mutex mu_;
  std::vector<std::unique_ptr<Connection>> arriving_;  // for the waiting room
  std::deque<std::unique_ptr<Connection>> ready_;      // for the workers
  std::condition_variable ready_cv_;
  bool stopping_ = false;

  std::thread waiting_room_;
  std::vector<std::thread> workers_;
};

}  // namespace seaplan::server
