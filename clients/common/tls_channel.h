// Client side of the server's TLS, shared by seaplan (remote commands) and
// seaplan-sim: the command-line options and the gRPC channel credentials.
//
//   --ca-cert FILE      SEAPLAN_CA_CERT      CA that signed the server's certificate (PEM):
//                                            TLS to the server; none: plaintext
//   --client-cert FILE  SEAPLAN_CLIENT_CERT  this client's certificate (PEM), for mutual TLS
//   --client-key FILE   SEAPLAN_CLIENT_KEY   its private key (PEM)
#pragma once

#include <memory>
#include <string>

#include "seaplan/common/status.h"

namespace CLI {
class App;
}
namespace grpc {
class ChannelCredentials;
}

namespace seaplan::client {

struct TlsFiles {
  std::string ca_cert;
  std::string client_cert;
  std::string client_key;
  bool enabled() const { return !ca_cert.empty(); }
};

// Adds the three options to `app` (environment variables as fallbacks).
// In its own object file: `seaplan`, which links no gRPC, parses them too.
void AddTlsOptions(CLI::App& app, TlsFiles* files);

// The files readable and PEM, a client certificate with its key and a CA:
// InvalidArgument naming the option otherwise. (No gRPC: for `seaplan`.)
Status CheckTlsFiles(const TlsFiles& files);
// A PEM file's text; InvalidArgument naming `option` when unreadable.
StatusOr<std::string> ReadPemFile(const std::string& path, const std::string& option);

// Plaintext credentials without a CA; TLS (mutual TLS with a client
// certificate) otherwise. InvalidArgument naming the file that cannot be
// read or is not PEM, or a certificate given without its key.
StatusOr<std::shared_ptr<grpc::ChannelCredentials>> ChannelCredentials(const TlsFiles& files);

}  // namespace seaplan::client
