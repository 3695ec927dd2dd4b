// libFuzzer target: an HTTP/JSON gateway request body -> the request
// message, through the gateway's own codec (server/http/json_codec.h).
// Input: first byte picks the RPC's request type, the rest is the body.
// Any body ends in InvalidArgument or a message, never a crash; a message
// that parses prints as JSON and parses back to an equal message.
#include <google/protobuf/util/field_comparator.h>
#include <google/protobuf/util/message_differencer.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "seaplan/v1/chart.pb.h"
#include "seaplan/v1/mission.pb.h"
#include "seaplan/v1/planning.pb.h"
#include "seaplan/v1/route.pb.h"
#include "server/http/json_codec.h"

namespace {

using seaplan::server::MessageFromJson;
using seaplan::server::MessageToJson;
namespace v1 = seaplan::v1;

// Every request type the gateway accepts (server/http/gateway.cc).
const std::vector<const google::protobuf::Message*>& RequestTypes() {
  static const auto* types = new std::vector<const google::protobuf::Message*>{
      &v1::PlanRequest::default_instance(),
      &v1::ValidateRequest::default_instance(),
      &v1::UploadChartRequest::default_instance(),
      &v1::GetChartRequest::default_instance(),
      &v1::ListChartsRequest::default_instance(),
      &v1::GetObstaclesRequest::default_instance(),
      &v1::PlanRouteRequest::default_instance(),
      &v1::EstimateRiskRequest::default_instance(),
      &v1::CreateMissionRequest::default_instance(),
      &v1::GetMissionRequest::default_instance(),
      &v1::ListMissionsRequest::default_instance(),
      &v1::WatchMissionRequest::default_instance(),
      &v1::ReportFeedbackRequest::default_instance(),
      &v1::RequestReplanRequest::default_instance(),
      &v1::CancelMissionRequest::default_instance(),
      &v1::ReportVesselStateRequest::default_instance(),
  };
  return *types;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto& types = RequestTypes();
  const auto* prototype = types[data[0] % types.size()];
  const std::string body(reinterpret_cast<const char*>(data + 1), size - 1);
  std::unique_ptr<google::protobuf::Message> request(prototype->New());
  const absl::Status parsed = MessageFromJson(body, request.get());
  if (!parsed.ok()) {
    if (parsed.code() != absl::StatusCode::kInvalidArgument) std::abort();
    return 0;
  }
  std::string json;
  if (!MessageToJson(*request, &json).ok()) std::abort();
  std::unique_ptr<google::protobuf::Message> again(prototype->New());
  if (!MessageFromJson(json, again.get()).ok()) std::abort();
  // Values, not bits: NaN is never equal to itself, so NaNs compare equal
  // here.
  google::protobuf::util::DefaultFieldComparator comparator;
  comparator.set_treat_nan_as_equal(true);
  google::protobuf::util::MessageDifferencer differencer;
  differencer.set_field_comparator(&comparator);
  // "-0" parses back as +0, which proto3 does not store: unset and default
  // are the same value.
  differencer.set_message_field_comparison(google::protobuf::util::MessageDifferencer::EQUIVALENT);
  std::string differences;
  differencer.ReportDifferencesToString(&differences);
  if (!differencer.Compare(*request, *again)) {
    std::fprintf(stderr, "JSON round trip changed the message:\n%s\nprinted: %s\n",
                 differences.c_str(), json.c_str());
    std::abort();
  }
  return 0;
}
