// The real seaplan-server and seaplan-sim with vessel tokens: a mass-1
// token may read its vessel's mission but may not create missions, and a
// mass-2 token is refused on mass-1's mission, by the server and at once by
// the sim (not retried as a shore outage).
#include <gtest/gtest.h>

#include <regex>

#include "e2e_support.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/v1/access.grpc.pb.h"

namespace seaplan::e2e {
namespace {

using seaplan::testing::BinDir;
using seaplan::testing::SourceDir;

std::string VesselToken(v1::AccessService::Stub& access, const std::string& vessel) {
  grpc::ClientContext ctx;  // the fixtures' admin token
  v1::CreateTokenRequest req;
  req.set_role(v1::ROLE_VESSEL);
  req.set_vessel_id(vessel);
  v1::CreateTokenResponse resp;
  const grpc::Status st = access.CreateToken(&ctx, req, &resp);
  EXPECT_TRUE(st.ok()) << st.error_message();
  return resp.bearer();
}

grpc::StatusCode GetMissionAs(v1::MissionService::Stub& missions, const std::string& token,
                              const std::string& mission_id) {
  grpc::ClientContext ctx;
  ctx.AddMetadata("authorization", "Bearer " + token);
  v1::GetMissionRequest req;
  req.set_mission_id(mission_id);
  v1::Mission mission;
  return missions.GetMission(&ctx, req, &mission).error_code();
}

TEST(VesselTokenE2eTest, VesselTokensReachOnlyTheirOwnVesselsMissions) {
  if (!fs::exists(BinDir() / "seaplan-server") || !fs::exists(BinDir() / "seaplan-sim")) {
    GTEST_SKIP() << "seaplan-server or seaplan-sim not built in " << BinDir();
  }
  const fs::path dir =
      fs::temp_directory_path() / ("seaplan-vessel-token-" + std::to_string(getpid()));
  fs::remove_all(dir);
  ServerProcess server;
  ASSERT_TRUE(server.Start(BinDir() / "seaplan-server", dir / "server"));
  auto channel = grpc::CreateChannel(server.address(), grpc::InsecureChannelCredentials());
  auto access = v1::AccessService::NewStub(channel);
  auto missions = v1::MissionService::NewStub(channel);
  const std::string mass1 = VesselToken(*access, "mass-1");
  const std::string mass2 = VesselToken(*access, "mass-2");

  // The operator's side (the fixtures' admin token) runs case A for mass-1.
  const std::string scenario = (SourceDir() / "examples/scenarios/case-a.scenario").string();
  const std::string sim = (BinDir() / "seaplan-sim").string();
  ProcessResult run = RunProcess({sim, "--server", server.address(), "--scenario", scenario,
                                  "--report-dir", (dir / "admin").string()},
                                 {}, dir / "admin.out", std::chrono::seconds(300));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(run.output, match, std::regex("mission (m-[0-9a-f]+)")))
      << run.output;
  const std::string mission_id = match[1];

  EXPECT_EQ(GetMissionAs(*missions, mass1, mission_id), grpc::StatusCode::OK);
  EXPECT_EQ(GetMissionAs(*missions, mass2, mission_id), grpc::StatusCode::PERMISSION_DENIED);

  // The sim with mass-2's token gives up at once, saying why.
  ProcessResult other =
      RunProcess({sim, "--server", server.address(), "--token", mass2, "--mission-id", mission_id,
                  "--scenario", scenario, "--report-dir", (dir / "other").string()},
                 {}, dir / "other.out", std::chrono::seconds(60));
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_FALSE(other.timed_out);
  EXPECT_NE(other.output.find("PERMISSION_DENIED"), std::string::npos) << other.output;
  EXPECT_NE(other.output.find("mass-2"), std::string::npos) << other.output;

  // A vessel token creates no missions, not even for its own vessel.
  ProcessResult create =
      RunProcess({sim, "--server", server.address(), "--token", mass1, "--scenario", scenario,
                  "--report-dir", (dir / "create").string()},
                 {}, dir / "create.out", std::chrono::seconds(60));
  EXPECT_EQ(create.exit_code, 1) << create.output;
  EXPECT_NE(create.output.find("PERMISSION_DENIED"), std::string::npos) << create.output;
  server.Stop();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace seaplan::e2e
