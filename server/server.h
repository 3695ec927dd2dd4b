// seaplan-server assembled: the core, the gRPC server (four services, the
// standard health service, reflection) and the HTTP/JSON gateway, with a
// graceful shutdown. main.cc and the in-process tests use this class; it
// reads no flags or environment (config/ does, only in main).
//
// Shutdown(grace):
//   1. health NOT_SERVING for every service and "" (gRPC) and /healthz 503;
//   2. watch streams end (UNAVAILABLE: resume elsewhere / later);
//   3. both transports stop accepting; running requests get `grace` to
//      finish, then their work is cancelled through the StopTokens;
//   4. the pool and the mission thread are joined. The caller then closes
//      the database.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <string>

#include "seaplan/common/status.h"
#include "seaplan/storage/repositories.h"
#include "server/core/service_core.h"
#include "server/tls_options.h"

namespace grpc {
class Server;
}

namespace seaplan::server {

class GrpcServices;
class HttpGateway;

struct ServerOptions {
  std::string grpc_address = "127.0.0.1:50051";  // port 0 = ephemeral
  std::string http_address = "127.0.0.1:8080";   // port 0 = ephemeral; "" = no HTTP gateway
  int worker_threads = 16;                    // HTTP handler threads; gRPC sync-server thread cap
  std::size_t max_request_bytes = 64u << 20;  // one request message
  std::string console_dir;                    // operator console's static files; "" = none
  CoreOptions core;
  std::chrono::milliseconds shutdown_grace{2000};
  // TLS on both transports (tls_options.h).
  TlsOptions tls;
  // Without TLS the server listens only on loopback addresses unless this
  // is set (it then logs a warning): plaintext on a network is a choice.
  bool insecure = false;
  // The HTTP gateway closes connections idle in a read or write this long;
  // a request's head must arrive within http_read_timeout of its first
  // byte and its body at http_min_body_bytes_per_s at least, complete
  // within http_max_body_time after that (a large body at the minimum rate
  // would hold a worker thread for size / rate).
  std::chrono::milliseconds http_read_timeout{10000};
  std::chrono::milliseconds http_write_timeout{10000};
  std::size_t http_min_body_bytes_per_s = 16 * 1024;
  std::chrono::milliseconds http_max_body_time{300000};
};

// Whether `address` ("host:port") listens only on the loopback interface:
// 127.0.0.0/8, ::1 or localhost.
bool IsLoopbackAddress(const std::string& address);

class Server {
 public:
  // Binds both ports and starts serving. `store` must outlive the server.
  // FailedPrecondition for a non-loopback address without TLS (unless
  // `insecure`); InvalidArgument when the TLS files cannot be used.
  static absl::StatusOr<std::unique_ptr<Server>> Start(
      const ServerOptions& options, storage::Store& store,
      std::shared_ptr<mission::MissionEngine> mission_engine = nullptr);
  ~Server();  // Shutdown()
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  int grpc_port() const { return grpc_port_; }
  int http_port() const { return http_port_; }
  ServiceCore& core() { return *core_; }

  // Graceful and idempotent (see the file comment).
  void Shutdown();

 private:
  Server() = default;

  ServerOptions options_;
  std::unique_ptr<ServiceCore> core_;
  std::unique_ptr<GrpcServices> services_;
  std::unique_ptr<grpc::Server> grpc_;
  std::unique_ptr<HttpGateway> http_;
  int grpc_port_ = 0;
  int http_port_ = 0;
  std::once_flag shutdown_once_;
};

}  // namespace seaplan::server
