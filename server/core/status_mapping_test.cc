#include "server/grpc/status_mapping.h"

#include <gtest/gtest.h>

#include "server/core/status_details.h"
#include "server/http/status_mapping.h"

namespace seaplan::server {
namespace {

TEST(StatusMappingTest, HttpCodes) {
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kOk), 200);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kInvalidArgument), 400);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kNotFound), 404);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kFailedPrecondition), 412);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kAborted), 409);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kResourceExhausted), 429);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kDeadlineExceeded), 504);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kCancelled), 499);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kUnavailable), 503);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kUnimplemented), 501);
  EXPECT_EQ(ToHttpStatus(absl::StatusCode::kInternal), 500);
}

TEST(StatusMappingTest, DiagnosticsTravelThroughBothMappers) {
  v1::DiagnosticList list;
  v1::Diagnostic* d = list.add_diagnostics();
  d->set_file("domain");
  d->set_line(12);
  d->set_column(5);
  d->set_message("undeclared \"predicate\"");
  absl::Status st = WithDiagnostics(absl::InvalidArgumentError("malformed PDDL"), list);

  grpc::Status g = ToGrpcStatus(st);
  EXPECT_EQ(g.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(g.error_message(), "malformed PDDL");
  v1::DiagnosticList back;
  ASSERT_TRUE(back.ParseFromString(g.error_details()));
  ASSERT_EQ(back.diagnostics_size(), 1);
  EXPECT_EQ(back.diagnostics(0).line(), 12);

  const std::string json = ErrorJson(st);
  EXPECT_NE(json.find("\"code\":\"INVALID_ARGUMENT\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"@type\":\"type.googleapis.com/seaplan.v1.DiagnosticList\""),
            std::string::npos)
      << json;
  EXPECT_NE(json.find("\"line\":12"), std::string::npos) << json;
  EXPECT_NE(json.find("undeclared \\\"predicate\\\""), std::string::npos) << json;

  EXPECT_EQ(ErrorJson(absl::NotFoundError("x")),
            "{\"code\":\"NOT_FOUND\",\"message\":\"x\",\"details\":[]}");
  EXPECT_TRUE(ToGrpcStatus(absl::OkStatus()).ok());
}

}  // namespace
}  // namespace seaplan::server
