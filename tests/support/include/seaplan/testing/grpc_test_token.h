// UseTestAdminTokenByDefault(): every gRPC call of this process that carries
// no `authorization` metadata of its own carries the fixtures' admin token
// (test_token.h), through a process-wide client interceptor, and the
// clients the test starts get it through SEAPLAN_TOKEN. The fixtures call
// it, so tests written before the server required tokens run unchanged;
// tests of access control set their own metadata, or never call it in their
// process. Header-only.
#pragma once

#include <grpcpp/grpcpp.h>
#include <grpcpp/support/client_interceptor.h>

#include <mutex>

#include "seaplan/testing/test_token.h"

namespace seaplan::testing {
namespace internal {

class DefaultTokenInterceptor final : public grpc::experimental::Interceptor {
 public:
  void Intercept(grpc::experimental::InterceptorBatchMethods* methods) override {
    if (methods->QueryInterceptionHookPoint(
            grpc::experimental::InterceptionHookPoints::PRE_SEND_INITIAL_METADATA)) {
      auto* metadata = methods->GetSendInitialMetadata();
      if (metadata != nullptr && metadata->find("authorization") == metadata->end()) {
        metadata->insert({"authorization", "Bearer " + TestAdminToken()});
      }
    }
    methods->Proceed();
  }
};

class DefaultTokenFactory final : public grpc::experimental::ClientInterceptorFactoryInterface {
 public:
  grpc::experimental::Interceptor* CreateClientInterceptor(
      grpc::experimental::ClientRpcInfo*) override {
    return new DefaultTokenInterceptor();
  }
};

}  // namespace internal

inline void UseTestAdminTokenByDefault() {
  static std::once_flag once;
  std::call_once(once, [] {
    static internal::DefaultTokenFactory factory;
    grpc::experimental::RegisterGlobalClientInterceptorFactory(&factory);
  });
  PassTestAdminTokenToChildren();
}

}  // namespace seaplan::testing
