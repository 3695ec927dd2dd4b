#include "server/http/json_codec.h"

#include <google/protobuf/struct.pb.h>
#include <gtest/gtest.h>

#include <string>

#include "seaplan/v1/chart.pb.h"

namespace seaplan::server {
namespace {

// Map fields through the JSON the gateway reads and writes, read back by
// our code: one of ours (an obstacle summary's counts per layer) and one of
// the installed library's own messages (Struct, the /auth/login body). In
// the ThreadSanitizer build these also check that our code and libprotobuf
// agree on where a map field's data lies (proto/tsan_protobuf_abi.h).
TEST(JsonCodecTest, OurMapFieldsRoundTrip) {
  v1::ObstacleSummary summary;
  ASSERT_TRUE(MessageFromJson(R"({"obstacleCount": 3, "countByLayer": {"LNDARE": 2, "OBSTRN": 1}})",
                              &summary)
                  .ok());
  EXPECT_EQ(summary.obstacle_count(), 3);
  ASSERT_EQ(summary.count_by_layer().size(), 2u);
  EXPECT_EQ(summary.count_by_layer().at("LNDARE"), 2);
  EXPECT_EQ(summary.count_by_layer().at("OBSTRN"), 1);

  (*summary.mutable_count_by_layer())["DEPARE"] = 5;
  std::string json;
  ASSERT_TRUE(MessageToJson(summary, &json).ok());
  EXPECT_NE(json.find(R"("DEPARE":5)"), std::string::npos) << json;
  v1::ObstacleSummary back;
  ASSERT_TRUE(MessageFromJson(json, &back).ok()) << json;
  EXPECT_EQ(back.count_by_layer().size(), 3u);
  EXPECT_EQ(back.count_by_layer().at("DEPARE"), 5);
  EXPECT_EQ(back.count_by_layer().at("OBSTRN"), 1);
}

TEST(JsonCodecTest, LibraryStructFieldsAreFound) {
  google::protobuf::Struct body;
  ASSERT_TRUE(MessageFromJson(R"({"token": "seaplan_abc", "remember": true})", &body).ok());
  ASSERT_EQ(body.fields().size(), 2u);
  const auto token = body.fields().find("token");
  ASSERT_NE(token, body.fields().end());
  EXPECT_EQ(token->second.string_value(), "seaplan_abc");
  EXPECT_TRUE(body.fields().at("remember").bool_value());
  EXPECT_EQ(body.fields().find("missing"), body.fields().end());
}

}  // namespace
}  // namespace seaplan::server
