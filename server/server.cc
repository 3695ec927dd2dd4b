#include "server/server.h"

#include <arpa/inet.h>
#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/grpcpp.h>
#include <grpcpp/health_check_service_interface.h>

#include <condition_variable>
#include <fstream>
#include <sstream>
#include <thread>

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"
#include "server/grpc/services.h"
#include "server/http/gateway.h"

namespace seaplan::server {
namespace {

absl::StatusOr<std::string> ReadPem(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return absl::InvalidArgumentError(absl::StrCat("cannot read the ", what, " '", path, "'"));
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().find("-----BEGIN ") == std::string::npos) {
    return absl::InvalidArgumentError(absl::StrCat("the ", what, " '", path, "' is not PEM"));
  }
  return text.str();
}

absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> GrpcCredentials(const TlsOptions& tls) {
  if (!tls.enabled()) return grpc::InsecureServerCredentials();
  if (tls.key_file.empty())
    return absl::InvalidArgumentError("TLS: a certificate needs its private key file");
  grpc::SslServerCredentialsOptions options(
      tls.client_ca_file.empty() ? GRPC_SSL_DONT_REQUEST_CLIENT_CERTIFICATE
      : tls.require_client_cert  ? GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY
                                 : GRPC_SSL_REQUEST_CLIENT_CERTIFICATE_AND_VERIFY);
  grpc::SslServerCredentialsOptions::PemKeyCertPair pair;
  SEAPLAN_ASSIGN_OR_RETURN(pair.cert_chain, ReadPem(tls.cert_file, "TLS certificate"));
  SEAPLAN_ASSIGN_OR_RETURN(pair.private_key, ReadPem(tls.key_file, "TLS private key"));
  options.pem_key_cert_pairs.push_back(std::move(pair));
  if (!tls.client_ca_file.empty()) {
    SEAPLAN_ASSIGN_OR_RETURN(options.pem_root_certs, ReadPem(tls.client_ca_file, "client CA"));
  }
  return grpc::SslServerCredentials(options);
}

}  // namespace

bool IsLoopbackAddress(const std::string& address) {
  std::string host;
  int port = 0;
  if (!SplitHostPort(address, &host, &port).ok()) return false;
  if (host == "localhost" || host == "::1") return true;
  in_addr v4{};
  return inet_pton(AF_INET, host.c_str(), &v4) == 1 && (ntohl(v4.s_addr) >> 24) == 127;
}

absl::StatusOr<std::unique_ptr<Server>> Server::Start(
    const ServerOptions& options, storage::Store& store,
    std::shared_ptr<mission::MissionEngine> mission_engine) {
  if (options.max_request_bytes == 0 || options.max_request_bytes > (1u << 31) - 1) {
    return absl::InvalidArgumentError("max request bytes must be in 1..2^31-1");
  }
  if (!options.tls.enabled()) {
    for (const std::string& address : {options.grpc_address, options.http_address}) {
      if (address.empty() || IsLoopbackAddress(address)) continue;
      if (!options.insecure) {
        return absl::FailedPreconditionError(
            absl::StrCat("refusing to listen on ", address,
                         " without TLS: give --tls-cert and --tls-key (or listen on 127.0.0.1), or "
                         "--insecure to serve plaintext on the network anyway"));
      }
      log::Warn(
          "--insecure: serving plaintext on {}: anyone on the network can read and "
          "change the traffic",
          address);
    }
  }
  SEAPLAN_ASSIGN_OR_RETURN(auto credentials, GrpcCredentials(options.tls));
  std::unique_ptr<Server> server(new Server());
  server->options_ = options;
  server->core_ = std::make_unique<ServiceCore>(store, options.core, std::move(mission_engine));
  server->services_ = std::make_unique<GrpcServices>(*server->core_);

  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  builder.AddListeningPort(options.grpc_address, credentials, &server->grpc_port_);
  // gRPC binds with SO_REUSEPORT by default: a second server on a taken port
  // would start and silently take a share of the first one's connections.
  builder.AddChannelArgument(GRPC_ARG_ALLOW_REUSEPORT, 0);
  builder.SetMaxReceiveMessageSize(static_cast<int>(options.max_request_bytes));
  grpc::ResourceQuota quota("seaplan-server");
  // Streams hold a thread each in the sync server; leave room beyond the
  // HTTP worker count so watchers cannot starve unary calls.
  quota.SetMaxThreads(std::max(8, options.worker_threads * 4));
  builder.SetResourceQuota(quota);
  for (grpc::Service* service : server->services_->services()) builder.RegisterService(service);
  server->grpc_ = builder.BuildAndStart();
  if (!server->grpc_ || server->grpc_port_ == 0) {
    server->core_->Stop();
    return absl::UnavailableError(
        absl::StrCat("gRPC: cannot listen on ", options.grpc_address, " (in use?)"));
  }
  grpc::HealthCheckServiceInterface* health = server->grpc_->GetHealthCheckService();
  if (health != nullptr) {
    health->SetServingStatus("", true);
    for (const auto& name : GrpcServices::ServiceNames()) health->SetServingStatus(name, true);
  }

  if (!options.http_address.empty()) {
    server->http_ = std::make_unique<HttpGateway>(
        *server->core_,
        HttpGateway::Options{// JSON carries bytes as base64 (4/3 larger) plus syntax.
                             options.max_request_bytes / 3 * 4 + (1u << 20), options.worker_threads,
                             options.console_dir, options.tls, options.http_read_timeout,
                             options.http_write_timeout, options.http_min_body_bytes_per_s,
                             options.http_max_body_time});
    auto port = server->http_->Bind(options.http_address);
    if (!port.ok()) {
      server->Shutdown();
      return port.status();
    }
    server->http_port_ = *port;
    server->http_->Start();
  }
  log::Info(
      "seaplan-server listening: grpc={} (port {}), http={} (port {}), {}; planning workers: {} "
      "(queue {})",
      options.grpc_address, server->grpc_port_, options.http_address, server->http_port_,
      !options.tls.enabled()               ? "plaintext"
      : options.tls.client_ca_file.empty() ? "TLS"
      : options.tls.require_client_cert    ? "mutual TLS (client certificate required)"
                                           : "TLS (client certificate verified when given)",
      options.core.planning_threads, options.core.planning_queue);
  return server;
}

Server::~Server() {
  Shutdown();
}

void Server::Shutdown() {
  std::call_once(shutdown_once_, [this] {
    log::Info("shutting down: NOT_SERVING, draining for up to {} ms",
              options_.shutdown_grace.count());
    if (grpc_) {
      if (auto* health = grpc_->GetHealthCheckService())
        health->Shutdown();  // every service NOT_SERVING
    }
    if (http_) http_->SetServing(false);
    core_->CloseStreams();
    // After the grace period, stop whatever is still running.
    std::mutex mu;
    std::condition_variable cv;
    bool drained = false;
    std::thread canceller([&] {
      std::unique_lock lock(mu);
      if (!cv.wait_for(lock, options_.shutdown_grace, [&] { return drained; })) {
        log::Warn("grace period over: cancelling running work");
        core_->CancelAllWork();
      }
    });
    if (grpc_) grpc_->Shutdown(std::chrono::system_clock::now() + options_.shutdown_grace);
    if (http_) http_->Stop();
    {
      std::lock_guard lock(mu);
      drained = true;
    }
    cv.notify_all();
    canceller.join();
    if (grpc_) grpc_->Wait();
    core_->Stop();
    log::Info("shutdown complete");
  });
}

}  // namespace seaplan::server
