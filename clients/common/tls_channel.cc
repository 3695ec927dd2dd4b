#include "tls_channel.h"

#include <grpcpp/security/credentials.h>

#include "absl/strings/str_cat.h"

namespace seaplan::client {

StatusOr<std::shared_ptr<grpc::ChannelCredentials>> ChannelCredentials(const TlsFiles& files) {
  SEAPLAN_RETURN_IF_ERROR(CheckTlsFiles(files));
  if (!files.enabled()) return grpc::InsecureChannelCredentials();
  grpc::SslCredentialsOptions options;
  SEAPLAN_ASSIGN_OR_RETURN(options.pem_root_certs, ReadPemFile(files.ca_cert, "--ca-cert"));
  if (!files.client_cert.empty()) {
    SEAPLAN_ASSIGN_OR_RETURN(options.pem_cert_chain,
                             ReadPemFile(files.client_cert, "--client-cert"));
    SEAPLAN_ASSIGN_OR_RETURN(options.pem_private_key,
                             ReadPemFile(files.client_key, "--client-key"));
  }
  return grpc::SslCredentials(options);
}

}  // namespace seaplan::client
