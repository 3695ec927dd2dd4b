// TLS settings shared by both transports (gRPC and the HTTP gateway).
#pragma once

#include <string>

namespace seaplan::server {

struct TlsOptions {
  std::string cert_file;  // the server's certificate chain (PEM); empty: plaintext
  std::string key_file;   // its private key (PEM)
  // Mutual TLS when set: client certificates are verified against this CA
  // (PEM). A verified certificate's subject CN names a vessel
  // (CallContext::client_cert_subject).
  std::string client_ca_file;
  // With client_ca_file: refuse clients without a certificate (false: ask
  // for one, verify it when given, accept clients without).
  bool require_client_cert = true;

  bool enabled() const { return !cert_file.empty(); }
};

}  // namespace seaplan::server
