// The gRPC services of seaplan.v1: thin adapters from grpc::ServerContext
// and messages to the transport-agnostic core (server/core). Each method
// builds a CallContext (caller from the `authorization` metadata, deadline,
// cancellation), calls the one core handler,
// maps the status with ToGrpcStatus and logs one line.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <vector>

#include "seaplan/v1/access.grpc.pb.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"
#include "seaplan/v1/planning.grpc.pb.h"
#include "seaplan/v1/route.grpc.pb.h"
#include "server/core/service_core.h"

namespace seaplan::server {

// The five services, to register on a grpc::ServerBuilder.
class GrpcServices {
 public:
  explicit GrpcServices(ServiceCore& core);
  ~GrpcServices();
  // Fully qualified names ("seaplan.v1.PlanningService", ...).
  static std::vector<std::string> ServiceNames();
  // Every service, to pass to ServerBuilder::RegisterService.
  std::vector<grpc::Service*> services();

 private:
  class Planning;
  class Charts;
  class Routes;
  class Missions;
  class Access;
  std::unique_ptr<Planning> planning_;
  std::unique_ptr<Charts> charts_;
  std::unique_ptr<Routes> routes_;
  std::unique_ptr<Missions> missions_;
  std::unique_ptr<Access> access_;
};

}  // namespace seaplan::server
