// The HTTP/JSON gateway: every RPC of seaplan.v1 as
//   POST /v1/<Service>/<Method>     e.g. POST /v1/PlanningService/Plan
// with the request and response in Protobuf's canonical JSON mapping
// (lowerCamelCase names; unknown fields are an error; fields at their
// default are printed too). Server-streaming RPCs answer
// application/x-ndjson, one JSON message per line, chunked; an error after
// the stream started ends it with a last line {"error": {...}}. Errors
// before any message are a plain error response (status_mapping.h).
//   GET /healthz  200 {"status":"SERVING"} / 503 {"status":"NOT_SERVING"}
// A client deadline may be given as header "X-Seaplan-Timeout-Ms: <ms>"
// (the gRPC deadline's equivalent; without it a request has no deadline).
// With TLS options the gateway serves HTTPS only (the same port). Every RPC
// counts against its caller's rate limit (429 with a Retry-After header).
// Bodies are limited to max_body_bytes (413 beyond) and read as JSON
// whatever their Content-Type (curl -d sends a form type); multipart bodies
// are refused (400).
// Every RPC needs a credential: "Authorization: Bearer <token>", or the
// console's session cookie together with its CSRF token in the header
// X-CSRF-Token (403 without it; server/auth/csrf.h). 401 without a (valid)
// credential, 403 when the role may not call the RPC.
//   POST /auth/login   {"token": "..."}: sets the session cookie (HttpOnly,
//                      SameSite=Strict) and answers {"csrfToken", "tokenId",
//                      "role", "vesselId"}
//   GET  /auth/session the same answer for the cookie's token (401 if none)
//   POST /auth/logout  (cookie + CSRF header) clears the cookie
//   GET /  and other paths: the operator console's static files
//          (Options::console_dir), with a same-origin Content-Security-Policy.
//
// The gateway only parses, calls the same core handlers as the gRPC
// services (server/core) and prints.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include "seaplan/common/status.h"
#include "server/core/service_core.h"
#include "server/tls_options.h"

namespace seaplan::server {

class GuardedHttpServer;

class HttpGateway {
 public:
  struct Options {
    std::size_t max_body_bytes = 64u << 20;
    int threads = 16;
    // Folder of the built operator console (index.html ...), served at
    // "/"; empty or without index.html: GET / answers 404 saying so.
    std::string console_dir;
    // HTTPS when tls.enabled() (mutual TLS with tls.client_ca_file).
    TlsOptions tls;
    // Slow clients (guarded_http_server.h): a request's head must arrive
    // within read_timeout of its first byte, its body at min_body_bytes_per_s
    // at least after that and wholly within max_body_time, and a connection
    // that sends or takes nothing for read_timeout / write_timeout is closed.
    // Connections waiting for their request hold no worker thread.
    std::chrono::milliseconds read_timeout{10000};
    std::chrono::milliseconds write_timeout{10000};
    std::size_t min_body_bytes_per_s = 16 * 1024;
    std::chrono::milliseconds max_body_time{300000};
  };

  HttpGateway(ServiceCore& core, const Options& options);
  ~HttpGateway();  // Stop()
  HttpGateway(const HttpGateway&) = delete;
  HttpGateway& operator=(const HttpGateway&) = delete;

  // Binds "host:port" (port 0 = ephemeral) and returns the bound port.
  // InvalidArgument when the TLS files cannot be used.
  absl::StatusOr<int> Bind(const std::string& address);
  // Serves on a background thread.
  void Start();
  // /healthz answers NOT_SERVING after SetServing(false).
  void SetServing(bool serving) { serving_ = serving; }
  // Stops accepting, waits for running handlers.
  void Stop();

 private:
  void RegisterRoutes();
  void RegisterSessionRoutes();

  ServiceCore& core_;
  Options options_;
  std::unique_ptr<GuardedHttpServer> server_;
  std::thread thread_;
  std::atomic<bool> serving_{true};
  std::string tls_error_;  // why the TLS context could not be set up
};

// Splits "host:port" ("[::1]:80" too); InvalidArgument when malformed.
absl::Status SplitHostPort(const std::string& address, std::string* host, int* port);

}  // namespace seaplan::server
