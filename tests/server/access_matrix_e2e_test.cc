// Every RPC of every seaplan.v1 service the server registers (listed from
// the proto descriptors, so a new RPC is covered, and fails here until the
// access table has an entry for it), called over gRPC and over HTTP with
// every role and with no, an expired, a revoked and a malformed token. The
// exact outcome is checked: UNAUTHENTICATED / 401 for bad credentials,
// PERMISSION_DENIED / 403 for a role the table does not allow (and for a
// vessel token on another vessel's mission), and otherwise OK / 200: every
// call carries a valid request, so an allowed caller gets the answer, not
// just past the checks. Then the audit log: who did what is readable by an
// admin.
//
// The expected outcomes come from the role table in server/README.md (parsed
// here), and the code's table (server/auth/policy.cc) must say the same.
//
// Its own binary: it must not use the fixtures' default admin token
// (InProcessServer(..., AdminTokenUse::kNone)).
#include <google/protobuf/descriptor.h>
#include <google/protobuf/dynamic_message.h>
#include <google/protobuf/util/json_util.h>
#include <grpcpp/generic/generic_stub.h>
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/v1/access.grpc.pb.h"
#include "server/auth/authenticator.h"
#include "server/grpc/services.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::MethodDescriptor;

enum class Expect { kUnauthenticated, kDenied, kPasses };

const char* ExpectName(Expect e) {
  switch (e) {
    case Expect::kUnauthenticated:
      return "UNAUTHENTICATED";
    case Expect::kDenied:
      return "PERMISSION_DENIED";
    case Expect::kPasses:
      return "OK";
  }
  return "?";
}

// One credential of the matrix.
struct Credential {
  std::string name;
  std::string authorization;       // header value; empty: none sent
  std::optional<auth::Role> role;  // nullopt: a bad credential
  bool other_vessel = false;       // a vessel token of another vessel
};

// One row of server/README.md's role table, per RPC.
struct DocumentedRule {
  std::set<auth::Role> roles;
  bool vessel_scoped = false;
  bool audited = false;
};

// "| ChartService/GetChart, ListCharts | yes | yes | yes | own vessel | |"
// rows, one entry per RPC ("ChartService/ListCharts" ...).
std::map<std::string, DocumentedRule> ReadDocumentedTable() {
  std::map<std::string, DocumentedRule> table;
  const std::string readme =
      seaplan::testing::ReadFile(seaplan::testing::SourceDir() / "server" / "README.md");
  for (absl::string_view line : absl::StrSplit(readme, '\n')) {
    std::vector<std::string> cells;
    for (absl::string_view cell : absl::StrSplit(line, '|')) {
      cells.emplace_back(absl::StripAsciiWhitespace(cell));
    }
    // "", rpcs, admin, operator, viewer, vessel, audit, ""
    if (cells.size() != 8 || cells[1].find("Service/") == std::string::npos) continue;
    DocumentedRule rule;
    const auth::Role columns[] = {auth::Role::kAdmin, auth::Role::kOperator, auth::Role::kViewer,
                                  auth::Role::kVessel};
    for (int i = 0; i < 4; ++i) {
      const std::string& cell = cells[2 + i];
      if (cell == "yes" || cell == "own vessel") rule.roles.insert(columns[i]);
      if (cell == "own vessel") rule.vessel_scoped = true;
    }
    rule.audited = cells[6] == "yes";
    std::vector<std::string> names = absl::StrSplit(cells[1], ", ");
    const std::string service = names[0].substr(0, names[0].find('/') + 1);
    for (std::size_t i = 0; i < names.size(); ++i) {
      table[i == 0 ? names[0] : service + names[i]] = rule;
    }
  }
  return table;
}

class AccessMatrixTest : public ::testing::Test {
 protected:
  void SetUp() override {
    engine_ = std::make_shared<FakeMissionEngine>();
    server_ = std::make_unique<InProcessServer>(engine_, 2, InProcessServer::AdminTokenUse::kNone);
    auth_ = std::make_unique<auth::Authenticator>(server_->store().tokens());
    Add("admin", auth::Role::kAdmin);
    Add("operator", auth::Role::kOperator);
    Add("viewer", auth::Role::kViewer);
    Add("vessel", auth::Role::kVessel, "ship0");
    Add("vessel-of-another-ship", auth::Role::kVessel, "mass-2", true);
    credentials_.push_back({"no token", "", std::nullopt});
    // Expired: stored with an expiry in the past.
    auto expired = auth::GenerateToken();
    ASSERT_TRUE(expired.ok());
    storage::TokenRecord record;
    record.id = expired->id;
    record.secret_hash = expired->secret_hash;
    record.role = "admin";
    record.created_at_ms = auth_->Now() - 10'000;
    record.expires_at_ms = auth_->Now() - 5'000;
    ASSERT_TRUE(server_->store().tokens().Insert(record).ok());
    credentials_.push_back({"expired admin token", "Bearer " + expired->bearer, std::nullopt});
    auto revoked = auth_->Issue(auth::Role::kAdmin, "", "revoked", 0, "");
    ASSERT_TRUE(revoked.ok());
    ASSERT_TRUE(server_->store().tokens().Revoke(revoked->record.id, auth_->Now()).ok());
    credentials_.push_back({"revoked admin token", "Bearer " + revoked->bearer, std::nullopt});
    credentials_.push_back({"malformed token", "Bearer seaplan_not-a-token", std::nullopt});

    // A mission of vessel ship0 for the mission RPCs.
    mission_id_ = CreateMission("matrix");
    ASSERT_FALSE(mission_id_.empty());
    chart_id_ = UploadHarbourChart();
  }

  // The harbour chart of engine/chart's test data, uploaded by the admin.
  std::string UploadHarbourChart() {
    auto charts = v1::ChartService::NewStub(server_->channel());
    grpc::ClientContext ctx;
    SetDeadline(&ctx, 30000);
    ctx.AddMetadata("authorization", admin_);
    v1::UploadChartResponse uploaded;
    const grpc::Status st = charts->UploadChart(&ctx, HarbourChartUpload(), &uploaded);
    EXPECT_TRUE(st.ok()) << st.error_message();
    return uploaded.chart().chart_id();
  }

  // A mission of vessel ship0, created by the admin; empty on failure.
  std::string CreateMission(const std::string& name) {
    auto missions = v1::MissionService::NewStub(server_->channel());
    grpc::ClientContext ctx;
    SetDeadline(&ctx, 30000);
    ctx.AddMetadata("authorization", admin_);
    v1::CreateMissionRequest create;
    *create.mutable_spec() = SampleSpec(name);
    v1::Mission mission;
    const grpc::Status st = missions->CreateMission(&ctx, create, &mission);
    EXPECT_TRUE(st.ok()) << st.error_message();
    return mission.mission_id();
  }

  void Add(const std::string& name, auth::Role role, const std::string& vessel = "",
           bool other_vessel = false) {
    auto issued = auth_->Issue(role, vessel, name, 0, "");
    ASSERT_TRUE(issued.ok()) << issued.status();
    credentials_.push_back({name, "Bearer " + issued->bearer, role, other_vessel});
    if (role == auth::Role::kAdmin) admin_ = "Bearer " + issued->bearer;
  }

  // A valid request for `method`: the fixture's mission, vessel and chart,
  // and what the RPC needs besides. A call that ends or removes something
  // (CancelMission, DeleteChart, RevokeToken) gets a target of its own, so
  // every allowed call succeeds whatever ran before it.
  std::unique_ptr<Message> RequestFor(const MethodDescriptor& method) {
    std::unique_ptr<Message> request(google::protobuf::MessageFactory::generated_factory()
                                         ->GetPrototype(method.input_type())
                                         ->New());
    const std::string& name = method.name();
    if (name == "Plan" || name == "PlanStream") {
      v1::PlanRequest plan;
      plan.set_domain(kDomain);
      plan.set_problem(kProblem);
      request->CopyFrom(plan);
    } else if (name == "Validate") {
      v1::ValidateRequest validate;
      validate.set_domain(kDomain);
      validate.set_problem(kProblem);
      validate.set_plan("0.000: (sail) [1.000]\n");
      request->CopyFrom(validate);
    } else if (name == "UploadChart") {
      request->CopyFrom(HarbourChartUpload());
    } else if (name == "PlanRoute") {
      v1::PlanRouteRequest route;
      *route.mutable_start() = LatLon(62.4703, 6.1080);
      *route.mutable_goal() = LatLon(62.4718, 6.1117);
      route.mutable_options()->set_particles(4);
      route.mutable_options()->set_iterations(4);
      route.mutable_options()->set_segments(4);
      route.mutable_options()->set_safety_distance_m(5);
      request->CopyFrom(route);
    } else if (name == "EstimateRisk") {
      v1::EstimateRiskRequest risk;
      *risk.add_track()->mutable_position() = LatLon(62.4705, 6.1085);
      *risk.add_track()->mutable_position() = LatLon(62.4712, 6.1090);
      request->CopyFrom(risk);
    } else if (name == "CreateMission") {
      v1::CreateMissionRequest create;
      *create.mutable_spec() = SampleSpec("created by the matrix");
      request->CopyFrom(create);
    } else if (name == "ReportFeedback") {
      v1::ReportFeedbackRequest report;
      report.mutable_feedback()->set_kind(v1::Feedback::KIND_POSITION);
      report.mutable_feedback()->set_plan_version(1);
      *report.mutable_feedback()->mutable_state()->mutable_position() = LatLon(63.45, 10.3);
      request->CopyFrom(report);
    } else if (name == "ReportVesselState") {
      v1::ReportVesselStateRequest state;
      *state.mutable_state()->mutable_position() = LatLon(63.45, 10.3);
      request->CopyFrom(state);
    } else if (name == "CreateToken") {
      v1::CreateTokenRequest token;
      token.set_role(v1::ROLE_VIEWER);
      token.set_description("created by the matrix");
      request->CopyFrom(token);
    }
    const auto* d = request->GetDescriptor();
    const auto* r = request->GetReflection();
    auto set = [&](const char* field, const std::string& value) {
      const FieldDescriptor* f = d->FindFieldByName(field);
      if (f != nullptr && f->type() == FieldDescriptor::TYPE_STRING)
        r->SetString(request.get(), f, value);
    };
    set("mission_id", name == "CancelMission" ? CreateMission("to cancel") : mission_id_);
    if (name != "CreateToken") set("vessel_id", "ship0");  // a viewer token: no vessel
    set("chart_id", name == "DeleteChart" ? UploadHarbourChart() : chart_id_);
    set("reason", "access matrix");
    if (name == "RevokeToken") {
      auto victim = auth_->Issue(auth::Role::kViewer, "", "to revoke", 0, "");
      EXPECT_TRUE(victim.ok());
      set("token_id", victim->record.id);
    }
    if (const FieldDescriptor* f = d->FindFieldByName("sequence_number")) {
      r->SetInt64(request.get(), f, ++sequence_);
    }
    return request;
  }

  // One durative action that reaches the goal: planned and validated at once.
  static constexpr char kDomain[] =
      "(define (domain matrix) (:requirements :durative-actions) (:predicates (at-sea))\n"
      " (:durative-action sail :parameters () :duration (= ?duration 1)\n"
      "  :condition () :effect (at end (at-sea))))";
  static constexpr char kProblem[] =
      "(define (problem one) (:domain matrix) (:init) (:goal (at-sea)))";

  // Over gRPC with the generic stub: the status, or OK once a stream's
  // first message arrived.
  int CallGrpc(const MethodDescriptor& method, const Message& request,
               const std::string& authorization, std::string* message) {
    grpc::GenericStub stub(server_->channel());
    grpc::CompletionQueue cq;
    grpc::ClientContext ctx;
    SetDeadline(&ctx, 20000);
    if (!authorization.empty()) ctx.AddMetadata("authorization", authorization);
    const std::string path = "/" + method.service()->full_name() + "/" + std::string(method.name());
    const std::string bytes = request.SerializeAsString();
    grpc::Slice slice(bytes);
    grpc::ByteBuffer send(&slice, 1);
    grpc::Status status;
    void* tag = nullptr;
    bool ok = false;
    auto wait = [&] { EXPECT_TRUE(cq.Next(&tag, &ok)); };
    if (!method.server_streaming()) {
      auto call = stub.PrepareUnaryCall(&ctx, path, send, &cq);
      call->StartCall();
      grpc::ByteBuffer reply;
      call->Finish(&reply, &status, reinterpret_cast<void*>(1));
      wait();
    } else {
      auto call = stub.PrepareCall(&ctx, path, &cq);
      call->StartCall(reinterpret_cast<void*>(1));
      wait();
      call->WriteLast(send, grpc::WriteOptions(), reinterpret_cast<void*>(2));
      wait();
      grpc::ByteBuffer reply;
      call->Read(&reply, reinterpret_cast<void*>(3));
      wait();
      const bool got_message = ok;
      if (got_message) ctx.TryCancel();
      call->Finish(&status, reinterpret_cast<void*>(4));
      wait();
      if (got_message) status = grpc::Status::OK;
    }
    cq.Shutdown();
    while (cq.Next(&tag, &ok)) {
    }
    *message = status.error_message();
    return status.error_code();
  }

  // Over HTTP: the status code.
  int CallHttp(const MethodDescriptor& method, const Message& request,
               const std::string& authorization, std::string* body) {
    std::string json;
    EXPECT_TRUE(google::protobuf::util::MessageToJsonString(request, &json).ok());
    httplib::Client http = server_->http();
    httplib::Headers headers{{"X-Seaplan-Timeout-Ms", "1500"}};
    if (!authorization.empty()) headers.emplace("Authorization", authorization);
    const std::string path =
        "/v1/" + std::string(method.service()->name()) + "/" + std::string(method.name());
    auto res = http.Post(path, headers, json, "application/json");
    if (!res) return -1;
    *body = res->body.substr(0, 300);
    if (res->status == 401) {
      EXPECT_EQ(res->get_header_value("WWW-Authenticate"), "Bearer") << path;
    }
    return res->status;
  }

  static Expect Expected(const DocumentedRule& rule, const Credential& c) {
    if (!c.role) return Expect::kUnauthenticated;
    if (!rule.roles.count(*c.role)) return Expect::kDenied;
    if (c.other_vessel && rule.vessel_scoped) return Expect::kDenied;
    return Expect::kPasses;
  }

  std::shared_ptr<FakeMissionEngine> engine_;
  std::unique_ptr<InProcessServer> server_;
  std::unique_ptr<auth::Authenticator> auth_;
  std::vector<Credential> credentials_;
  std::string admin_;
  std::string mission_id_;
  std::string chart_id_;
  std::int64_t sequence_ = 0;
};

TEST_F(AccessMatrixTest, EveryRpcWithEveryCredentialOverBothTransports) {
  const std::map<std::string, DocumentedRule> documented = ReadDocumentedTable();
  ASSERT_FALSE(documented.empty()) << "no role table found in server/README.md";
  int rpcs = 0, checks = 0;
  for (const std::string& service_name : GrpcServices::ServiceNames()) {
    const auto* service =
        google::protobuf::DescriptorPool::generated_pool()->FindServiceByName(service_name);
    ASSERT_NE(service, nullptr) << service_name;
    for (int m = 0; m < service->method_count(); ++m) {
      const MethodDescriptor& method = *service->method(m);
      const std::string name = std::string(service->name()) + "/" + std::string(method.name());
      const auth::MethodRule* rule = auth::FindRule(name);
      ASSERT_NE(rule, nullptr) << name
                               << " has no entry in the access table (server/auth/policy.cc)";
      const auto doc = documented.find(name);
      ASSERT_NE(doc, documented.end()) << name << " is missing from server/README.md's role table";
      for (auth::Role role : auth::kAllRoles) {
        EXPECT_EQ(rule->Allows(role), doc->second.roles.count(role) == 1)
            << name << ", role " << auth::RoleName(role) << ": policy.cc and README differ";
      }
      EXPECT_EQ(rule->vessel_scoped, doc->second.vessel_scoped) << name;
      EXPECT_EQ(rule->audited, doc->second.audited) << name;
      ++rpcs;
      for (const Credential& c : credentials_) {
        const Expect expect = Expected(doc->second, c);
        // A request each: an allowed gRPC call may end the target of its own.
        std::string message, body;
        const int code = CallGrpc(method, *RequestFor(method), c.authorization, &message);
        const int status = CallHttp(method, *RequestFor(method), c.authorization, &body);
        const std::string where = name + " with " + c.name + ": expected " + ExpectName(expect);
        switch (expect) {
          case Expect::kUnauthenticated:
            EXPECT_EQ(code, grpc::StatusCode::UNAUTHENTICATED) << where << " (gRPC) " << message;
            EXPECT_EQ(status, 401) << where << " (HTTP) " << body;
            break;
          case Expect::kDenied:
            EXPECT_EQ(code, grpc::StatusCode::PERMISSION_DENIED) << where << " (gRPC) " << message;
            EXPECT_EQ(status, 403) << where << " (HTTP) " << body;
            break;
          case Expect::kPasses:
            EXPECT_EQ(code, grpc::StatusCode::OK) << where << " (gRPC) " << message;
            EXPECT_EQ(status, 200) << where << " (HTTP) " << body;
            break;
        }
        checks += 2;
      }
    }
  }
  // Every documented RPC exists.
  EXPECT_EQ(rpcs, static_cast<int>(documented.size()));
  EXPECT_GE(rpcs, 22);
  EXPECT_EQ(checks, rpcs * static_cast<int>(credentials_.size()) * 2);
  std::printf("access matrix: %d RPCs x %zu credentials x 2 transports = %d calls\n", rpcs,
              credentials_.size(), checks);
}

TEST_F(AccessMatrixTest, AuditLogSaysWhoDidWhatAndOnlyAdminsReadIt) {
  // An operator cancels the mission over HTTP; the admin creates and
  // revokes a token over gRPC.
  const std::string operator_auth = credentials_[1].authorization;
  httplib::Client http = server_->http();
  auto cancelled =
      http.Post("/v1/MissionService/CancelMission", {{"Authorization", operator_auth}},
                "{\"missionId\":\"" + mission_id_ + "\",\"reason\":\"storm\"}", "application/json");
  ASSERT_TRUE(cancelled);
  ASSERT_EQ(cancelled->status, 200) << cancelled->body;

  auto access = v1::AccessService::NewStub(server_->channel());
  v1::CreateTokenResponse created;
  {
    grpc::ClientContext ctx;
    ctx.AddMetadata("authorization", admin_);
    v1::CreateTokenRequest req;
    req.set_role(v1::ROLE_VESSEL);
    req.set_vessel_id("mass-1");
    req.set_description("mass-1 onboard");
    ASSERT_TRUE(access->CreateToken(&ctx, req, &created).ok());
    EXPECT_EQ(created.token().role(), v1::ROLE_VESSEL);
    EXPECT_EQ(created.token().vessel_id(), "mass-1");
    EXPECT_EQ(created.bearer().rfind("seaplan_" + created.token().token_id() + "_", 0), 0u);
  }
  {
    grpc::ClientContext ctx;
    ctx.AddMetadata("authorization", admin_);
    v1::RevokeTokenRequest req;
    req.set_token_id(created.token().token_id());
    v1::RevokeTokenResponse resp;
    ASSERT_TRUE(access->RevokeToken(&ctx, req, &resp).ok());
    EXPECT_NE(resp.token().revoked_at_ms(), 0);
  }
  // The revoked token no longer works, at once.
  {
    grpc::ClientContext ctx;
    ctx.AddMetadata("authorization", "Bearer " + created.bearer());
    v1::WhoAmIResponse who;
    EXPECT_EQ(access->WhoAmI(&ctx, {}, &who).error_code(), grpc::StatusCode::UNAUTHENTICATED);
  }
  // A viewer cannot read the log; the admin can, over both transports.
  {
    grpc::ClientContext ctx;
    ctx.AddMetadata("authorization", credentials_[2].authorization);
    v1::ListAuditEventsResponse resp;
    EXPECT_EQ(access->ListAuditEvents(&ctx, {}, &resp).error_code(),
              grpc::StatusCode::PERMISSION_DENIED);
  }
  v1::ListAuditEventsResponse log;
  {
    grpc::ClientContext ctx;
    ctx.AddMetadata("authorization", admin_);
    ASSERT_TRUE(access->ListAuditEvents(&ctx, {}, &log).ok());
  }
  const std::string operator_id = credentials_[1].authorization.substr(7 + 8, 16);
  const std::string admin_id = admin_.substr(7 + 8, 16);
  std::vector<std::string> seen;
  for (const auto& e : log.events()) {
    seen.push_back(e.action() + " " + e.target() + " by " + e.token_id());
    EXPECT_GT(e.time_ms(), 0);
  }
  auto has = [&](const std::string& line) {
    return std::find(seen.begin(), seen.end(), line) != seen.end();
  };
  // SetUp created the mission with the admin token.
  EXPECT_TRUE(has("MissionService/CreateMission " + mission_id_ + " by " + admin_id))
      << ::testing::PrintToString(seen);
  EXPECT_TRUE(has("MissionService/CancelMission " + mission_id_ + " by " + operator_id))
      << ::testing::PrintToString(seen);
  EXPECT_TRUE(has("AccessService/CreateToken " + created.token().token_id() + " by " + admin_id));
  EXPECT_TRUE(has("AccessService/RevokeToken " + created.token().token_id() + " by " + admin_id));
  for (const auto& e : log.events()) {
    if (e.action() == "MissionService/CancelMission") {
      EXPECT_EQ(e.role(), v1::ROLE_OPERATOR);
      EXPECT_EQ(e.detail(), "storm");
    }
  }
  auto over_http = http.Post("/v1/AccessService/ListAuditEvents", {{"Authorization", admin_}}, "{}",
                             "application/json");
  ASSERT_TRUE(over_http);
  EXPECT_EQ(over_http->status, 200);
  EXPECT_NE(over_http->body.find("MissionService/CancelMission"), std::string::npos);
  // No secret is ever in the log.
  EXPECT_EQ(over_http->body.find(created.bearer()), std::string::npos);
}

// The console's session: a cookie that is HttpOnly and SameSite=Strict, and
// is only honoured together with its CSRF token.
TEST_F(AccessMatrixTest, ConsoleSessionCookieNeedsTheCsrfToken) {
  httplib::Client http = server_->http();
  const std::string viewer_token = credentials_[2].authorization.substr(7);
  auto bad = http.Post("/auth/login", "{\"token\":\"seaplan_wrong\"}", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 401);
  auto login = http.Post("/auth/login", "{\"token\":\"" + viewer_token + "\"}", "application/json");
  ASSERT_TRUE(login);
  ASSERT_EQ(login->status, 200) << login->body;
  const std::string cookie_header = login->get_header_value("Set-Cookie");
  EXPECT_NE(cookie_header.find("HttpOnly"), std::string::npos) << cookie_header;
  EXPECT_NE(cookie_header.find("SameSite=Strict"), std::string::npos) << cookie_header;
  const std::string cookie = cookie_header.substr(0, cookie_header.find(';'));
  ASSERT_EQ(cookie.rfind("seaplan_session=", 0), 0u) << cookie;
  // The body gives the CSRF token and who signed in; never the token itself.
  const std::string key = "\"csrfToken\":\"";
  const auto at = login->body.find(key);
  ASSERT_NE(at, std::string::npos) << login->body;
  const std::string csrf =
      login->body.substr(at + key.size(), login->body.find('"', at + key.size()) - at - key.size());
  EXPECT_EQ(csrf.size(), 43u);
  EXPECT_NE(login->body.find("\"role\":\"viewer\""), std::string::npos) << login->body;
  EXPECT_EQ(login->body.find(viewer_token), std::string::npos);

  const std::string list = "/v1/MissionService/ListMissions";
  auto no_csrf = http.Post(list, {{"Cookie", cookie}}, "{}", "application/json");
  ASSERT_TRUE(no_csrf);
  EXPECT_EQ(no_csrf->status, 403) << no_csrf->body;
  auto wrong_csrf =
      http.Post(list, {{"Cookie", cookie}, {"X-CSRF-Token", csrf + "x"}}, "{}", "application/json");
  ASSERT_TRUE(wrong_csrf);
  EXPECT_EQ(wrong_csrf->status, 403);
  auto ok = http.Post(list, {{"Cookie", cookie}, {"X-CSRF-Token", csrf}}, "{}", "application/json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200) << ok->body;
  // The session carries the viewer's role: no mission cancelling.
  auto cancel =
      http.Post("/v1/MissionService/CancelMission", {{"Cookie", cookie}, {"X-CSRF-Token", csrf}},
                "{\"missionId\":\"" + mission_id_ + "\"}", "application/json");
  ASSERT_TRUE(cancel);
  EXPECT_EQ(cancel->status, 403);
  // A reload asks for the session again.
  auto session = http.Get("/auth/session", {{"Cookie", cookie}});
  ASSERT_TRUE(session);
  EXPECT_EQ(session->status, 200);
  EXPECT_NE(session->body.find(csrf), std::string::npos);

  auto logout_without_csrf = http.Post("/auth/logout", {{"Cookie", cookie}}, "", "text/plain");
  ASSERT_TRUE(logout_without_csrf);
  EXPECT_EQ(logout_without_csrf->status, 403);
  auto logout =
      http.Post("/auth/logout", {{"Cookie", cookie}, {"X-CSRF-Token", csrf}}, "", "text/plain");
  ASSERT_TRUE(logout);
  EXPECT_EQ(logout->status, 200);
  EXPECT_NE(logout->get_header_value("Set-Cookie").find("Max-Age=0"), std::string::npos);
  // Without the cookie the browser no longer sends, nothing is allowed.
  auto after = http.Post(list, {{"X-CSRF-Token", csrf}}, "{}", "application/json");
  ASSERT_TRUE(after);
  EXPECT_EQ(after->status, 401);
  // Revoking the token ends every session signed in with it.
  ASSERT_TRUE(server_->store()
                  .tokens()
                  .Revoke(credentials_[2].authorization.substr(7 + 8, 16), auth_->Now())
                  .ok());
  auto revoked =
      http.Post(list, {{"Cookie", cookie}, {"X-CSRF-Token", csrf}}, "{}", "application/json");
  ASSERT_TRUE(revoked);
  EXPECT_EQ(revoked->status, 401);
  auto gone = http.Get("/auth/session", {{"Cookie", cookie}});
  ASSERT_TRUE(gone);
  EXPECT_EQ(gone->status, 401);
}

}  // namespace
}  // namespace seaplan::server::testing
