#include "server/http/gateway.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <httplib.h>
#include <openssl/err.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <sys/socket.h>

#include <charconv>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "seaplan/common/json.h"
#include "seaplan/common/log.h"
#include "server/auth/csrf.h"
#include "server/core/caller_limits.h"
#include "server/core/status_details.h"
#include "server/http/guarded_http_server.h"
#include "server/http/json_codec.h"
#include "server/http/status_mapping.h"

namespace seaplan::server {
namespace {

constexpr char kJson[] = "application/json";
constexpr char kNdjson[] = "application/x-ndjson";
constexpr char kTimeoutHeader[] = "X-Seaplan-Timeout-Ms";
constexpr char kCsrfHeader[] = "X-CSRF-Token";
constexpr char kSessionCookie[] = "seaplan_session";
// A console session lasts a working day; the token's own expiry and
// revocation apply within it.
constexpr int kSessionMaxAgeS = 12 * 3600;

void Reply(httplib::Response& res, const absl::Status& status) {
  res.status = ToHttpStatus(status.code());
  // RFC 6750: a 401 names the scheme it wants.
  if (absl::IsUnauthenticated(status)) res.set_header("WWW-Authenticate", "Bearer");
  if (auto retry_after = GetRetryAfter(status)) {
    // Whole seconds (RFC 9110), rounded up.
    res.set_header("Retry-After", std::to_string((retry_after->count() + 999) / 1000));
  }
  res.set_content(ErrorJson(status), kJson);
}

absl::StatusOr<StopToken::Clock::time_point> Deadline(const httplib::Request& req) {
  if (!req.has_header(kTimeoutHeader)) return StopToken::Clock::time_point::max();
  const std::string value = req.get_header_value(kTimeoutHeader);
  long long ms = 0;
  auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), ms);
  if (ec != std::errc() || end != value.data() + value.size() || ms <= 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(kTimeoutHeader, ": expected a positive number of ms, got '", value, "'"));
  }
  return StopToken::Clock::now() + std::chrono::milliseconds(ms);
}

// Reads the whole body whatever its Content-Type: cpp-httplib would take an
// application/x-www-form-urlencoded body (curl -d's default) as a form and
// refuse it beyond 8 KiB, so every RPC reads its body through a content
// reader, which skips form parsing. False when the response is already set
// (multipart, too large, malformed).
bool ReadBody(const httplib::Request& req, const httplib::ContentReader& reader,
              httplib::Response& res, std::string* body) {
  if (req.is_multipart_form_data()) {
    res.set_header("Connection", "close");  // the unread body must not be taken as the next request
    Reply(res, absl::InvalidArgumentError(
                   "multipart/form-data is not accepted: send the request message itself as JSON "
                   "in the body (any Content-Type)"));
    return false;
  }
  // On failure read_content has set res.status (413 too large, 400
  // malformed); the error handler writes the body.
  return reader([body](const char* data, std::size_t size) {
    body->append(data, size);
    return true;
  });
}

// What the log says of a body ReadBody refused.
absl::Status BodyError(const httplib::Response& res) {
  if (res.status == 413) return absl::ResourceExhaustedError("request body too large");
  return absl::InvalidArgumentError("request body not read");
}

// The value of cookie `name` in the request's Cookie header ("" if none).
std::string CookieValue(const httplib::Request& req, std::string_view name) {
  const std::string header = req.get_header_value("Cookie");
  std::string_view rest = header;
  while (!rest.empty()) {
    const std::size_t end = std::min(rest.find(';'), rest.size());
    std::string_view part = rest.substr(0, end);
    rest.remove_prefix(std::min(end + 1, rest.size()));
    while (!part.empty() && part.front() == ' ') part.remove_prefix(1);
    if (part.size() > name.size() && part.starts_with(name) && part[name.size()] == '=') {
      return std::string(part.substr(name.size() + 1));
    }
  }
  return "";
}

// The credential of a request, as an Authorization header value: the
// header itself, or the token in the console's session cookie, which also
// needs the CSRF token derived from it in its header (a page of another site
// can make the browser send the cookie, but cannot read it or the CSRF
// token).
absl::StatusOr<std::string> Credential(const httplib::Request& req) {
  if (req.has_header("Authorization")) return req.get_header_value("Authorization");
  const std::string token = CookieValue(req, kSessionCookie);
  if (token.empty()) return std::string();
  if (!auth::CsrfTokenMatches(token, req.get_header_value(kCsrfHeader))) {
    return absl::PermissionDeniedError(
        absl::StrCat("missing or wrong ", kCsrfHeader, " header for the session cookie"));
  }
  return absl::StrCat("Bearer ", token);
}

// The caller of `method`, from the request's credential.
absl::StatusOr<Caller> Authorize(ServiceCore& core, const std::string& method,
                                 const httplib::Request& req) {
  SEAPLAN_ASSIGN_OR_RETURN(std::string credential, Credential(req));
  return core.Authorize(method, credential);
}

// A stream in flight: the core handler runs on `worker` and queues lines;
// httplib's content provider (the connection thread) writes them.
struct StreamState {
  std::mutex mu;
  std::condition_variable cv;
  std::deque<std::string> lines;
  bool done = false;
  bool client_gone = false;
  absl::Status status;
  CallContext call;
  std::thread worker;
  std::string method;
  StopToken::Clock::time_point started;

  ~StreamState() {
    if (worker.joinable()) worker.join();
  }
};

// The OpenSSL error queue as text (emptied).
std::string OpenSslErrors() {
  std::string text;
  while (unsigned long e = ERR_get_error()) {
    char buffer[256];
    ERR_error_string_n(e, buffer, sizeof(buffer));
    if (!text.empty()) text += "; ";
    text += buffer;
  }
  return text.empty() ? "unknown OpenSSL error" : text;
}

// The server's TLS context: certificate chain and key, TLS 1.2 at least,
// and client certificates verified against the client CA (mutual TLS).
bool SetUpTls(const TlsOptions& tls, SSL_CTX& ctx, std::string* error) {
  SSL_CTX_set_min_proto_version(&ctx, TLS1_2_VERSION);
  SSL_CTX_set_options(&ctx, SSL_OP_NO_COMPRESSION | SSL_OP_NO_RENEGOTIATION);
  if (SSL_CTX_use_certificate_chain_file(&ctx, tls.cert_file.c_str()) != 1) {
    *error = absl::StrCat("cannot use the certificate '", tls.cert_file, "': ", OpenSslErrors());
    return false;
  }
  if (SSL_CTX_use_PrivateKey_file(&ctx, tls.key_file.c_str(), SSL_FILETYPE_PEM) != 1 ||
      SSL_CTX_check_private_key(&ctx) != 1) {
    *error = absl::StrCat("cannot use the private key '", tls.key_file,
                          "' with the certificate: ", OpenSslErrors());
    return false;
  }
  if (!tls.client_ca_file.empty()) {
    if (SSL_CTX_load_verify_locations(&ctx, tls.client_ca_file.c_str(), nullptr) != 1) {
      *error =
          absl::StrCat("cannot read the client CA '", tls.client_ca_file, "': ", OpenSslErrors());
      return false;
    }
    // The CA's name goes into the certificate request, so clients pick the
    // right certificate.
    if (STACK_OF(X509_NAME)* names = SSL_load_client_CA_file(tls.client_ca_file.c_str()))
      SSL_CTX_set_client_CA_list(&ctx, names);
    SSL_CTX_set_verify(
        &ctx, SSL_VERIFY_PEER | (tls.require_client_cert ? SSL_VERIFY_FAIL_IF_NO_PEER_CERT : 0),
        nullptr);
  }
  return true;
}

// The subject CN of the client's certificate when the handshake verified
// one; empty otherwise.
std::string ClientCertSubject(const httplib::Request& req) {
  if (req.ssl == nullptr || SSL_get_verify_result(req.ssl) != X509_V_OK) return "";
  X509* cert = SSL_get_peer_certificate(req.ssl);
  if (cert == nullptr) return "";
  std::string cn;
  char buffer[256];
  const int n = X509_NAME_get_text_by_NID(X509_get_subject_name(cert), NID_commonName, buffer,
                                          sizeof(buffer));
  if (n > 0) cn.assign(buffer, static_cast<std::size_t>(n));
  X509_free(cert);
  return cn;
}

// The core's context of an HTTP call: deadline, who calls.
CallContext MakeCall(ServiceCore& core, const std::string& method, const httplib::Request& req,
                     StopToken::Clock::time_point deadline, std::function<bool()> client_gone) {
  CallContext call = core.NewCall("http", deadline, std::move(client_gone));
  call.method = method;
  // The credential authorisation reads (header, or a console session's
  // cookie): one bucket per token whichever way it is presented.
  const absl::StatusOr<std::string> credential = Credential(req);
  call.caller_key = CallerKey(credential.ok() ? *credential : std::string(), req.remote_addr);
  call.client_cert_subject = ClientCertSubject(req);
  return call;
}

}  // namespace

absl::Status SplitHostPort(const std::string& address, std::string* host, int* port) {
  const auto colon = address.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == address.size()) {
    return absl::InvalidArgumentError(absl::StrCat("address '", address, "' is not host:port"));
  }
  *host = address.substr(0, colon);
  if (host->size() >= 2 && host->front() == '[' && host->back() == ']')
    *host = host->substr(1, host->size() - 2);
  const std::string port_text = address.substr(colon + 1);
  auto [end, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), *port);
  if (ec != std::errc() || end != port_text.data() + port_text.size() || *port < 0 ||
      *port > 65535) {
    return absl::InvalidArgumentError(
        absl::StrCat("address '", address, "': bad port '", port_text, "'"));
  }
  return absl::OkStatus();
}

HttpGateway::HttpGateway(ServiceCore& core, const Options& options)
    : core_(core), options_(options) {
  SSL_CTX* tls = nullptr;
  if (options_.tls.enabled()) {
    tls = SSL_CTX_new(TLS_server_method());
    if (tls == nullptr) {
      tls_error_ = absl::StrCat("cannot create a TLS context: ", OpenSslErrors());
    } else if (!SetUpTls(options_.tls, *tls, &tls_error_)) {
      SSL_CTX_free(tls);
      tls = nullptr;
    }
  }
  GuardedHttpServer::Limits limits;
  limits.worker_threads = std::max(1, options_.threads);
  limits.head_timeout = options_.read_timeout;
  limits.read_timeout = options_.read_timeout;
  limits.write_timeout = options_.write_timeout;
  limits.min_body_bytes_per_s = options_.min_body_bytes_per_s;
  limits.max_body_time = options_.max_body_time;
  server_ = std::make_unique<GuardedHttpServer>(limits, tls);
  if (tls != nullptr) SSL_CTX_free(tls);  // the server holds its own reference
  server_->set_payload_max_length(options_.max_body_bytes);
  // httplib binds with SO_REUSEPORT by default: a second server on a taken
  // port would start and take a share of the first one's connections.
  // SO_REUSEADDR alone still lets a restart bind while old connections linger.
  server_->set_socket_options([](socket_t sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  server_->set_keep_alive_timeout(
      std::chrono::duration_cast<std::chrono::seconds>(limits.idle_timeout).count());
  server_->set_keep_alive_max_count(static_cast<std::size_t>(limits.max_requests_per_connection));
  RegisterRoutes();
}

HttpGateway::~HttpGateway() {
  Stop();
}

absl::StatusOr<int> HttpGateway::Bind(const std::string& address) {
  std::string host;
  int port = 0;
  SEAPLAN_RETURN_IF_ERROR(SplitHostPort(address, &host, &port));
  if (!tls_error_.empty()) return absl::InvalidArgumentError(absl::StrCat("HTTPS: ", tls_error_));
  if (port == 0) {
    const int bound = server_->bind_to_any_port(host);
    if (bound <= 0) return absl::UnavailableError(absl::StrCat("HTTP: cannot bind ", address));
    return bound;
  }
  if (!server_->bind_to_port(host, port)) {
    return absl::UnavailableError(absl::StrCat("HTTP: cannot bind ", address, " (in use?)"));
  }
  return port;
}

void HttpGateway::Start() {
  thread_ = std::thread([this] { server_->listen_after_bind(); });
}

void HttpGateway::Stop() {
  if (server_) server_->stop();
  if (thread_.joinable()) thread_.join();
  if (server_) server_->StopConnections();
}

void HttpGateway::RegisterRoutes() {
  ServiceCore& core = core_;

  auto unary = [this, &core]<typename Request, typename Response>(
                   const std::string& method,
                   std::function<absl::StatusOr<Response>(const Request&, const CallContext&)> fn) {
    server_->Post("/v1/" + method,
                  [&core, method, fn](const httplib::Request& hreq, httplib::Response& hres,
                                      const httplib::ContentReader& reader) {
                    const auto started = StopToken::Clock::now();
                    std::string body;
                    if (!ReadBody(hreq, reader, hres, &body)) {
                      LogCall("http", method, BodyError(hres), started);
                      return;
                    }
                    absl::Status status = [&]() -> absl::Status {
                      SEAPLAN_ASSIGN_OR_RETURN(auto deadline, Deadline(hreq));
                      CallContext call = MakeCall(core, method, hreq, deadline, nullptr);
                      // Counted before the token is looked up: guessing
                      // tokens is rate limited too.
                      SEAPLAN_RETURN_IF_ERROR(core.Admit(call));
                      SEAPLAN_ASSIGN_OR_RETURN(call.caller, Authorize(core, method, hreq));
                      Request request;
                      SEAPLAN_RETURN_IF_ERROR(MessageFromJson(body, &request));
                      SEAPLAN_ASSIGN_OR_RETURN(Response response, fn(request, call));
                      std::string json;
                      SEAPLAN_RETURN_IF_ERROR(MessageToJson(response, &json));
                      hres.status = 200;
                      hres.set_content(json, kJson);
                      return absl::OkStatus();
                    }();
                    if (!status.ok()) Reply(hres, status);
                    LogCall("http", method, status, started);
                  });
  };

  auto stream =
      [this, &core]<typename Request, typename Event>(
          const std::string& method,
          std::function<absl::Status(const Request&, const CallContext&, const StreamSink<Event>&)>
              fn) {
        server_->Post("/v1/" + method, [&core, method, fn](const httplib::Request& hreq,
                                                           httplib::Response& hres,
                                                           const httplib::ContentReader& reader) {
          const auto started = StopToken::Clock::now();
          std::string body;
          if (!ReadBody(hreq, reader, hres, &body)) {
            LogCall("http", method, BodyError(hres), started);
            return;
          }
          absl::StatusOr<Caller> caller = Authorize(core, method, hreq);
          auto request = std::make_shared<Request>();
          absl::Status parsed =
              caller.ok() ? MessageFromJson(body, request.get()) : caller.status();
          auto deadline = Deadline(hreq);
          if (!parsed.ok() || !deadline.ok()) {
            const absl::Status& st = parsed.ok() ? deadline.status() : parsed;
            Reply(hres, st);
            LogCall("http", method, st, started);
            return;
          }
          auto state = std::make_shared<StreamState>();
          state->method = method;
          state->started = started;
          state->call = MakeCall(core, method, hreq, *deadline, [raw = state.get()] {
            std::lock_guard lock(raw->mu);
            return raw->client_gone;
          });
          if (absl::Status admitted = core.Admit(state->call); !admitted.ok()) {
            Reply(hres, admitted);
            LogCall("http", method, admitted, started);
            return;
          }
          state->call.caller = std::move(*caller);
          // The worker holds only a raw pointer: the state outlives it (the
          // state's destructor joins the worker).
          state->worker = std::thread([raw = state.get(), request, fn] {
            StreamSink<Event> sink = [raw](const Event& event) {
              std::string json;
              if (!MessageToJson(event, &json).ok()) return false;
              std::lock_guard lock(raw->mu);
              if (raw->client_gone) return false;
              raw->lines.push_back(std::move(json) + "\n");
              raw->cv.notify_all();
              return true;
            };
            absl::Status st = fn(*request, raw->call, sink);
            std::lock_guard lock(raw->mu);
            raw->status = st;
            raw->done = true;
            raw->cv.notify_all();
          });
          // Errors before the first message get a proper HTTP status.
          {
            std::unique_lock lock(state->mu);
            state->cv.wait(lock, [&] { return state->done || !state->lines.empty(); });
            if (state->done && state->lines.empty() && !state->status.ok()) {
              const absl::Status st = state->status;
              lock.unlock();
              state->worker.join();
              Reply(hres, st);
              LogCall("http", method, st, started);
              return;
            }
          }
          hres.status = 200;
          hres.set_chunked_content_provider(
              kNdjson,
              [state](std::size_t, httplib::DataSink& sink) {
                std::unique_lock lock(state->mu);
                state->cv.wait_for(lock, std::chrono::milliseconds(100),
                                   [&] { return state->done || !state->lines.empty(); });
                std::deque<std::string> batch;
                batch.swap(state->lines);
                const bool done = state->done;
                const absl::Status status = state->status;
                lock.unlock();
                for (const auto& line : batch) {
                  if (!sink.is_writable() || !sink.write(line.data(), line.size())) {
                    std::lock_guard relock(state->mu);
                    state->client_gone = true;
                    state->call.stop.Cancel();
                    return false;
                  }
                }
                if (batch.empty() && !sink.is_writable()) {
                  std::lock_guard relock(state->mu);
                  state->client_gone = true;
                  state->call.stop.Cancel();
                  return false;
                }
                if (done) {
                  if (!status.ok()) {
                    const std::string line = "{\"error\":" + ErrorJson(status) + "}\n";
                    sink.write(line.data(), line.size());
                  }
                  sink.done();
                }
                return true;
              },
              [state](bool) {
                {
                  std::lock_guard lock(state->mu);
                  if (!state->done) {
                    state->client_gone = true;
                    state->call.stop.Cancel();
                  }
                }
                if (state->worker.joinable()) state->worker.join();
                LogCall("http", state->method, state->status, state->started);
              });
        });
      };

  using R = CallContext;
  unary.operator()<v1::PlanRequest, v1::PlanResponse>(
      "PlanningService/Plan",
      [&core](const v1::PlanRequest& r, const R& c) { return core.planning().Plan(r, c); });
  stream.operator()<v1::PlanRequest, v1::PlanStreamEvent>(
      "PlanningService/PlanStream",
      [&core](const v1::PlanRequest& r, const R& c, const StreamSink<v1::PlanStreamEvent>& s) {
        return core.planning().PlanStream(r, c, s);
      });
  unary.operator()<v1::ValidateRequest, v1::ValidateResponse>(
      "PlanningService/Validate",
      [&core](const v1::ValidateRequest& r, const R& c) { return core.planning().Validate(r, c); });

  unary.operator()<v1::UploadChartRequest, v1::UploadChartResponse>(
      "ChartService/UploadChart", [&core](const v1::UploadChartRequest& r, const R& c) {
        return core.charts().UploadChart(r, c);
      });
  unary.operator()<v1::GetChartRequest, v1::GetChartResponse>(
      "ChartService/GetChart",
      [&core](const v1::GetChartRequest& r, const R& c) { return core.charts().GetChart(r, c); });
  unary.operator()<v1::ListChartsRequest, v1::ListChartsResponse>(
      "ChartService/ListCharts", [&core](const v1::ListChartsRequest& r, const R& c) {
        return core.charts().ListCharts(r, c);
      });

  unary.operator()<v1::GetObstaclesRequest, v1::GetObstaclesResponse>(
      "ChartService/GetObstacles", [&core](const v1::GetObstaclesRequest& r, const R& c) {
        return core.charts().GetObstacles(r, c);
      });

  unary.operator()<v1::DeleteChartRequest, v1::DeleteChartResponse>(
      "ChartService/DeleteChart", [&core](const v1::DeleteChartRequest& r, const R& c) {
        return core.charts().DeleteChart(r, c);
      });

  unary.operator()<v1::PlanRouteRequest, v1::PlanRouteResponse>(
      "RouteService/PlanRoute",
      [&core](const v1::PlanRouteRequest& r, const R& c) { return core.routes().PlanRoute(r, c); });
  unary.operator()<v1::EstimateRiskRequest, v1::EstimateRiskResponse>(
      "RouteService/EstimateRisk", [&core](const v1::EstimateRiskRequest& r, const R& c) {
        return core.routes().EstimateRisk(r, c);
      });

  unary.operator()<v1::CreateMissionRequest, v1::Mission>(
      "MissionService/CreateMission", [&core](const v1::CreateMissionRequest& r, const R& c) {
        return core.missions().CreateMission(r, c);
      });
  unary.operator()<v1::GetMissionRequest, v1::Mission>(
      "MissionService/GetMission", [&core](const v1::GetMissionRequest& r, const R& c) {
        return core.missions().GetMission(r, c);
      });
  unary.operator()<v1::ListMissionsRequest, v1::ListMissionsResponse>(
      "MissionService/ListMissions", [&core](const v1::ListMissionsRequest& r, const R& c) {
        return core.missions().ListMissions(r, c);
      });
  stream.operator()<v1::WatchMissionRequest, v1::MissionEvent>(
      "MissionService/WatchMission",
      [&core](const v1::WatchMissionRequest& r, const R& c, const StreamSink<v1::MissionEvent>& s) {
        return core.vessels().WatchMission(core.missions(), r, c, s);
      });
  unary.operator()<v1::ReportFeedbackRequest, v1::ReportFeedbackResponse>(
      "MissionService/ReportFeedback", [&core](const v1::ReportFeedbackRequest& r, const R& c) {
        return core.missions().ReportFeedback(r, c);
      });
  unary.operator()<v1::RequestReplanRequest, v1::RequestReplanResponse>(
      "MissionService/RequestReplan", [&core](const v1::RequestReplanRequest& r, const R& c) {
        return core.missions().RequestReplan(r, c);
      });
  unary.operator()<v1::CancelMissionRequest, v1::Mission>(
      "MissionService/CancelMission", [&core](const v1::CancelMissionRequest& r, const R& c) {
        return core.missions().CancelMission(r, c);
      });

  unary.operator()<v1::ReportVesselStateRequest, v1::ReportVesselStateResponse>(
      "MissionService/ReportVesselState",
      [&core](const v1::ReportVesselStateRequest& r, const R& c) {
        return core.vessels().ReportVesselState(r, c);
      });
  unary.operator()<v1::ListFeedbackRequest, v1::ListFeedbackResponse>(
      "MissionService/ListFeedback", [&core](const v1::ListFeedbackRequest& r, const R& c) {
        return core.missions().ListFeedback(r, c);
      });

  unary.operator()<v1::WhoAmIRequest, v1::WhoAmIResponse>(
      "AccessService/WhoAmI",
      [&core](const v1::WhoAmIRequest& r, const R& c) { return core.access().WhoAmI(r, c); });
  unary.operator()<v1::CreateTokenRequest, v1::CreateTokenResponse>(
      "AccessService/CreateToken", [&core](const v1::CreateTokenRequest& r, const R& c) {
        return core.access().CreateToken(r, c);
      });
  unary.operator()<v1::ListTokensRequest, v1::ListTokensResponse>(
      "AccessService/ListTokens", [&core](const v1::ListTokensRequest& r, const R& c) {
        return core.access().ListTokens(r, c);
      });
  unary.operator()<v1::RevokeTokenRequest, v1::RevokeTokenResponse>(
      "AccessService/RevokeToken", [&core](const v1::RevokeTokenRequest& r, const R& c) {
        return core.access().RevokeToken(r, c);
      });
  unary.operator()<v1::ListAuditEventsRequest, v1::ListAuditEventsResponse>(
      "AccessService/ListAuditEvents", [&core](const v1::ListAuditEventsRequest& r, const R& c) {
        return core.access().ListAuditEvents(r, c);
      });
  RegisterSessionRoutes();

  // The operator console: static files (index.html, JS, CSS) from
  // console_dir at "/". The page loads nothing from elsewhere.
  std::error_code ec;
  if (!options_.console_dir.empty() &&
      std::filesystem::is_regular_file(std::filesystem::path(options_.console_dir) / "index.html",
                                       ec)) {
    server_->set_mount_point(
        "/", options_.console_dir,
        {{"Cache-Control", "no-cache"},
         {"Content-Security-Policy",
          "default-src 'self'; img-src 'self' data: blob:; style-src 'self' 'unsafe-inline'"}});
  } else {
    const std::string missing =
        options_.console_dir.empty()
            ? std::string("no console directory configured (--console-dir)")
            : absl::StrCat("no index.html in the console directory '", options_.console_dir,
                           "' (build clients/console or set --console-dir)");
    server_->Get("/", [missing](const httplib::Request&, httplib::Response& res) {
      Reply(res, absl::NotFoundError(absl::StrCat("operator console not installed: ", missing)));
    });
  }

  server_->Get("/healthz", [this](const httplib::Request&, httplib::Response& res) {
    const bool serving = serving_.load();
    res.status = serving ? 200 : 503;
    res.set_content(serving ? "{\"status\":\"SERVING\"}" : "{\"status\":\"NOT_SERVING\"}", kJson);
  });
  // Unknown paths / methods / oversized bodies: a JSON error body when the
  // handler left none.
  server_->set_error_handler(
      httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
        if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
        absl::Status st;
        if (res.status == 404) {
          st = absl::NotFoundError(absl::StrCat("no route ", req.method, " ", req.path,
                                                " (RPCs are POST /v1/<Service>/<Method>)"));
        } else if (res.status == 400) {
          st = absl::InvalidArgumentError(
              "malformed HTTP request (a POST needs a body with a Content-Length or chunked)");
        } else if (res.status == 413) {
          st = absl::ResourceExhaustedError("request body exceeds the server's size limit");
        } else {
          st = absl::UnknownError(absl::StrCat("HTTP ", res.status));
        }
        res.set_content(ErrorJson(st), kJson);
        return httplib::Server::HandlerResponse::Handled;
      }));
}

void HttpGateway::RegisterSessionRoutes() {
  ServiceCore& core = core_;
  // Who the token is, with the CSRF token the console must send.
  auto describe = [&core](const std::string& token, httplib::Response& res) -> absl::Status {
    SEAPLAN_ASSIGN_OR_RETURN(Caller caller, core.authenticator().AuthenticateToken(token));
    const std::string body = absl::StrCat("{\"csrfToken\":", JsonString(auth::CsrfTokenFor(token)),
                                          ",\"tokenId\":", JsonString(caller.token_id),
                                          ",\"role\":", JsonString(auth::RoleName(caller.role)),
                                          ",\"vesselId\":", JsonString(caller.vessel_id), "}");
    res.status = 200;
    res.set_header("Cache-Control", "no-store");
    res.set_content(body, kJson);
    return absl::OkStatus();
  };
  server_->Post("/auth/login", [describe](const httplib::Request& req, httplib::Response& res) {
    const auto started = StopToken::Clock::now();
    absl::Status status = [&]() -> absl::Status {
      google::protobuf::Struct body;
      const auto parsed = google::protobuf::util::JsonStringToMessage(req.body, &body);
      const auto field = body.fields().find("token");
      if (!parsed.ok() || field == body.fields().end() || !field->second.has_string_value()) {
        return absl::InvalidArgumentError("expected a JSON body {\"token\": \"seaplan_...\"}");
      }
      const std::string token(absl::StripAsciiWhitespace(field->second.string_value()));
      SEAPLAN_RETURN_IF_ERROR(describe(token, res));
      res.set_header("Set-Cookie", absl::StrCat(kSessionCookie, "=", token,
                                                "; Path=/; HttpOnly; SameSite=Strict; ",
                                                "Max-Age=", kSessionMaxAgeS));
      return absl::OkStatus();
    }();
    if (!status.ok()) Reply(res, status);
    LogCall("http", "auth/login", status, started);
  });
  server_->Get("/auth/session", [describe](const httplib::Request& req, httplib::Response& res) {
    const std::string token = CookieValue(req, kSessionCookie);
    absl::Status status =
        token.empty() ? absl::UnauthenticatedError("not signed in") : describe(token, res);
    if (!status.ok()) Reply(res, status);
  });
  server_->Post("/auth/logout", [](const httplib::Request& req, httplib::Response& res) {
    const std::string token = CookieValue(req, kSessionCookie);
    if (!token.empty() && !auth::CsrfTokenMatches(token, req.get_header_value(kCsrfHeader))) {
      Reply(res, absl::PermissionDeniedError(
                     absl::StrCat("missing or wrong ", kCsrfHeader, " header for the session")));
      return;
    }
    res.set_header("Set-Cookie",
                   absl::StrCat(kSessionCookie, "=; Path=/; HttpOnly; SameSite=Strict; Max-Age=0"));
    res.status = 200;
    res.set_content("{}", kJson);
  });
}

}  // namespace seaplan::server
