// Transport security end to end: a throwaway CA made with the openssl
// command at test time, servers in-process on loopback with TLS or mutual
// TLS on both transports, and clients that have the right, a wrong or no
// certificate.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "seaplan/testing/test_token.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

std::string Slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A CA, a server certificate for 127.0.0.1 / localhost, client certificates
// for vessels "ship0" and "mass-2", and a rogue CA's certificate that also
// claims to be "ship0".
class TestPki {
 public:
  TestPki() {
    ok_ = Run("openssl version") && MakeCa("ca", "seaplan test CA") &&
          MakeCa("rogue-ca", "rogue CA") &&
          Issue("ca", "server", "localhost", "subjectAltName=IP:127.0.0.1,DNS:localhost") &&
          Issue("ca", "ship0", "ship0", "extendedKeyUsage=clientAuth") &&
          Issue("ca", "mass-2", "mass-2", "extendedKeyUsage=clientAuth") &&
          Issue("rogue-ca", "rogue-ship0", "ship0", "extendedKeyUsage=clientAuth");
  }
  bool ok() const { return ok_; }
  std::string pem(const std::string& name) const {
    return (dir_.path() / (name + ".pem")).string();
  }
  std::string key(const std::string& name) const {
    return (dir_.path() / (name + ".key")).string();
  }

  std::shared_ptr<grpc::Channel> Channel(int port, const std::string& client = "") const {
    grpc::SslCredentialsOptions options;
    options.pem_root_certs = Slurp(pem("ca"));
    if (!client.empty()) {
      options.pem_cert_chain = Slurp(pem(client));
      options.pem_private_key = Slurp(key(client));
    }
    grpc::ChannelArguments args;
    args.SetSslTargetNameOverride("localhost");
    return grpc::CreateCustomChannel("127.0.0.1:" + std::to_string(port),
                                     grpc::SslCredentials(options), args);
  }
  std::unique_ptr<httplib::SSLClient> Https(int port, const std::string& client = "") const {
    auto https = client.empty() ? std::make_unique<httplib::SSLClient>("127.0.0.1", port)
                                : std::make_unique<httplib::SSLClient>("127.0.0.1", port,
                                                                       pem(client), key(client));
    https->set_ca_cert_path(pem("ca").c_str());
    https->enable_server_certificate_verification(true);
    https->set_read_timeout(30, 0);
    // The fixtures' admin token: what is tested here is the transport.
    https->set_bearer_token_auth(seaplan::testing::TestAdminToken());
    return https;
  }

 private:
  bool Run(const std::string& command) const {
    const std::string full = "cd '" + dir_.path().string() + "' && " + command + " >/dev/null 2>&1";
    return std::system(full.c_str()) == 0;
  }
  bool MakeCa(const std::string& name, const std::string& cn) const {
    return Run(
        "openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -keyout " +
        name + ".key -out " + name + ".pem -days 2 -subj '/CN=" + cn + "'");
  }
  bool Issue(const std::string& ca, const std::string& name, const std::string& cn,
             const std::string& extension) const {
    std::ofstream(dir_.path() / (name + ".ext")) << extension << "\n";
    return Run("openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -keyout " +
               name + ".key -out " + name + ".csr -subj '/CN=" + cn + "'") &&
           Run("openssl x509 -req -in " + name + ".csr -CA " + ca + ".pem -CAkey " + ca +
               ".key -CAcreateserial -days 2 -out " + name + ".pem -extfile " + name + ".ext");
  }

  TempDir dir_;
  bool ok_ = false;
};

// Skips (with the reason) where the openssl command is missing; it is a
// build dependency (scripts/install-deps.sh), so CI fails instead.
#define REQUIRE_PKI(pki)                                                             \
  if (!(pki).ok()) {                                                                 \
    if (std::getenv("CI") != nullptr) FAIL() << "cannot make test certificates";     \
    GTEST_SKIP() << "the openssl command is missing: cannot make test certificates"; \
  }

std::function<void(ServerOptions&)> WithTls(const TestPki& pki, bool mutual,
                                            bool require_client_cert = true) {
  return [&pki, mutual, require_client_cert](ServerOptions& options) {
    options.tls.cert_file = pki.pem("server");
    options.tls.key_file = pki.key("server");
    if (mutual) options.tls.client_ca_file = pki.pem("ca");
    options.tls.require_client_cert = require_client_cert;
  };
}

grpc::Status ListMissions(const std::shared_ptr<grpc::Channel>& channel) {
  auto missions = v1::MissionService::NewStub(channel);
  ClientContext ctx;
  SetDeadline(&ctx, 10000);
  v1::ListMissionsRequest req;
  v1::ListMissionsResponse resp;
  return missions->ListMissions(&ctx, req, &resp);
}

TEST(TlsE2eTest, BothTransportsServeTlsAndRefusePlaintextClients) {
  TestPki pki;
  REQUIRE_PKI(pki);
  InProcessServer s(nullptr, 1, WithTls(pki, /*mutual=*/false));
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  // TLS clients that trust the CA.
  const grpc::Status over_tls = ListMissions(pki.Channel(s.server().grpc_port()));
  EXPECT_TRUE(over_tls.ok()) << over_tls.error_message();
  auto https = pki.Https(s.http_port());
  auto res = https->Post("/v1/MissionService/ListMissions", "{}", "application/json");
  ASSERT_TRUE(res) << httplib::to_string(res.error())
                   << " verify=" << https->get_openssl_verify_result();
  EXPECT_EQ(res->status, 200) << res->body;
  auto health = https->Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  // Plaintext clients get nothing.
  auto plain = grpc::CreateChannel(s.grpc_target(), grpc::InsecureChannelCredentials());
  EXPECT_EQ(ListMissions(plain).error_code(), StatusCode::UNAVAILABLE);
  httplib::Client plain_http("127.0.0.1", s.http_port());
  plain_http.set_read_timeout(10, 0);
  auto plain_res = plain_http.Post("/v1/MissionService/ListMissions", "{}", "application/json");
  EXPECT_FALSE(plain_res && plain_res->status == 200);
  // A client that does not trust the server's CA refuses it.
  grpc::SslCredentialsOptions other;
  other.pem_root_certs = Slurp(pki.pem("rogue-ca"));
  grpc::ChannelArguments args;
  args.SetSslTargetNameOverride("localhost");
  auto distrusting = grpc::CreateCustomChannel(s.grpc_target(), grpc::SslCredentials(other), args);
  EXPECT_EQ(ListMissions(distrusting).error_code(), StatusCode::UNAVAILABLE);
}

TEST(TlsE2eTest, MutualTlsRefusesClientsWithoutOrWithAForeignCertificate) {
  TestPki pki;
  REQUIRE_PKI(pki);
  InProcessServer s(nullptr, 1, WithTls(pki, /*mutual=*/true));
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  const int grpc_port = s.server().grpc_port();
  EXPECT_TRUE(ListMissions(pki.Channel(grpc_port, "ship0")).ok());
  EXPECT_EQ(ListMissions(pki.Channel(grpc_port)).error_code(), StatusCode::UNAVAILABLE);
  EXPECT_EQ(ListMissions(pki.Channel(grpc_port, "rogue-ship0")).error_code(),
            StatusCode::UNAVAILABLE);

  const std::string path = "/v1/MissionService/ListMissions";
  auto good = pki.Https(s.http_port(), "ship0")->Post(path, "{}", "application/json");
  ASSERT_TRUE(good) << httplib::to_string(good.error());
  EXPECT_EQ(good->status, 200);
  EXPECT_FALSE(pki.Https(s.http_port())->Post(path, "{}", "application/json"));
  EXPECT_FALSE(pki.Https(s.http_port(), "rogue-ship0")->Post(path, "{}", "application/json"));
}

TEST(TlsE2eTest, AVesselCertificateActsOnlyOnItsOwnVesselsMissions) {
  TestPki pki;
  REQUIRE_PKI(pki);
  auto engine = std::make_shared<FakeMissionEngine>();
  // Operators without a certificate are let in (their access is a matter of
  // credentials); a certificate, when given, is verified and binds a vessel.
  InProcessServer s(engine, 1, WithTls(pki, /*mutual=*/true, /*require_client_cert=*/false));
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  const int grpc_port = s.server().grpc_port();
  auto operator_missions = v1::MissionService::NewStub(pki.Channel(grpc_port));
  auto create = [&](const std::string& vessel) {
    ClientContext ctx;
    SetDeadline(&ctx, 10000);
    v1::CreateMissionRequest req;
    *req.mutable_spec() = SampleSpec(vessel + "-mission");
    req.mutable_spec()->set_vessel_id(vessel);
    v1::Mission mission;
    EXPECT_TRUE(operator_missions->CreateMission(&ctx, req, &mission).ok());
    return mission.mission_id();
  };
  const std::string own = create("ship0");
  const std::string other = create("mass-2");

  auto ship0 = v1::MissionService::NewStub(pki.Channel(grpc_port, "ship0"));
  auto feedback = [&](const std::string& mission_id, const std::string& vessel, int sequence) {
    ClientContext ctx;
    SetDeadline(&ctx, 10000);
    v1::ReportFeedbackRequest req;
    req.set_mission_id(mission_id);
    req.set_vessel_id(vessel);
    req.set_sequence_number(sequence);
    req.mutable_feedback()->set_kind(v1::Feedback::KIND_POSITION);
    req.mutable_feedback()->set_plan_version(1);
    v1::ReportFeedbackResponse resp;
    return ship0->ReportFeedback(&ctx, req, &resp);
  };
  EXPECT_TRUE(feedback(own, "ship0", 1).ok());
  EXPECT_EQ(feedback(other, "mass-2", 2).error_code(), StatusCode::PERMISSION_DENIED);
  EXPECT_EQ(feedback(own, "mass-2", 3).error_code(), StatusCode::PERMISSION_DENIED);
  {
    ClientContext ctx;
    SetDeadline(&ctx, 10000);
    v1::WatchMissionRequest req;
    req.set_mission_id(other);
    auto reader = ship0->WatchMission(&ctx, req);
    v1::MissionEvent event;
    EXPECT_FALSE(reader->Read(&event)) << "no event of another vessel's mission";
    EXPECT_EQ(reader->Finish().error_code(), StatusCode::PERMISSION_DENIED);
  }
  {
    ClientContext ctx;
    SetDeadline(&ctx, 10000);
    v1::ReportVesselStateRequest req;
    req.set_mission_id(other);
    req.mutable_state()->mutable_position()->set_latitude_deg(63.4);
    req.mutable_state()->mutable_position()->set_longitude_deg(10.4);
    v1::ReportVesselStateResponse resp;
    EXPECT_EQ(ship0->ReportVesselState(&ctx, req, &resp).error_code(),
              StatusCode::PERMISSION_DENIED);
  }
  {
    ClientContext ctx;
    SetDeadline(&ctx, 10000);
    v1::RequestReplanRequest req;
    req.set_mission_id(other);
    v1::RequestReplanResponse resp;
    EXPECT_EQ(ship0->RequestReplan(&ctx, req, &resp).error_code(), StatusCode::PERMISSION_DENIED);
  }
  // The same over HTTPS.
  auto https = pki.Https(s.http_port(), "ship0");
  auto denied = https->Post("/v1/MissionService/ReportFeedback",
                            "{\"missionId\":\"" + other +
                                "\",\"vesselId\":\"mass-2\",\"sequenceNumber\":\"4\","
                                "\"feedback\":{\"kind\":\"KIND_POSITION\",\"planVersion\":1}}",
                            "application/json");
  ASSERT_TRUE(denied);
  EXPECT_EQ(denied->status, 403) << denied->body;
  EXPECT_NE(denied->body.find("ship0"), std::string::npos) << denied->body;
  auto allowed = https->Post("/v1/MissionService/ReportFeedback",
                             "{\"missionId\":\"" + own +
                                 "\",\"vesselId\":\"ship0\",\"sequenceNumber\":\"5\","
                                 "\"feedback\":{\"kind\":\"KIND_POSITION\",\"planVersion\":1}}",
                             "application/json");
  ASSERT_TRUE(allowed);
  EXPECT_EQ(allowed->status, 200) << allowed->body;
}

TEST(TlsE2eTest, ANonLoopbackAddressWithoutTlsIsRefusedUnlessInsecure) {
  EXPECT_TRUE(IsLoopbackAddress("127.0.0.1:50051"));
  EXPECT_TRUE(IsLoopbackAddress("127.8.9.10:0"));
  EXPECT_TRUE(IsLoopbackAddress("localhost:80"));
  EXPECT_TRUE(IsLoopbackAddress("[::1]:80"));
  EXPECT_FALSE(IsLoopbackAddress("0.0.0.0:50051"));
  EXPECT_FALSE(IsLoopbackAddress("[::]:50051"));
  EXPECT_FALSE(IsLoopbackAddress("10.0.0.5:50051"));
  EXPECT_FALSE(IsLoopbackAddress("ships.example:50051"));
  for (const char* which : {"grpc", "http"}) {
    InProcessServer s(nullptr, 1, [which](ServerOptions& options) {
      (std::string(which) == "grpc" ? options.grpc_address : options.http_address) = "0.0.0.0:0";
    });
    EXPECT_EQ(s.start_status().code(), absl::StatusCode::kFailedPrecondition) << which;
    EXPECT_NE(s.start_status().message().find("--insecure"), std::string_view::npos)
        << s.start_status();
  }
}

TEST(TlsE2eTest, UnusableTlsFilesAreAClearErrorAtStart) {
  TestPki pki;
  REQUIRE_PKI(pki);
  InProcessServer missing(nullptr, 1, [](ServerOptions& options) {
    options.tls.cert_file = "/nonexistent/server.pem";
    options.tls.key_file = "/nonexistent/server.key";
  });
  EXPECT_EQ(missing.start_status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(missing.start_status().message().find("/nonexistent/server.pem"),
            std::string_view::npos)
      << missing.start_status();
  // A key that does not belong to the certificate (HTTP checks the pair).
  InProcessServer mismatched(nullptr, 1, [&pki](ServerOptions& options) {
    options.tls.cert_file = pki.pem("server");
    options.tls.key_file = pki.key("ship0");
  });
  EXPECT_FALSE(mismatched.start_status().ok());
}

}  // namespace
}  // namespace seaplan::server::testing
