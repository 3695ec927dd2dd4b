// A gRPC channel whose calls present the client's API token.
#pragma once

#include <grpcpp/grpcpp.h>

#include <memory>
#include <string>

namespace seaplan::client {

// A channel to `address` whose calls carry `authorization: Bearer <token>`
// (none when `token` is empty).
std::shared_ptr<grpc::Channel> CreateChannelWithToken(
    const std::string& address, const std::shared_ptr<grpc::ChannelCredentials>& credentials,
    const grpc::ChannelArguments& args, const std::string& token);

}  // namespace seaplan::client
