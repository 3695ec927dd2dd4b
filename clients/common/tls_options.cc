#include <CLI/CLI.hpp>
#include <fstream>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "tls_channel.h"

namespace seaplan::client {

StatusOr<std::string> ReadPemFile(const std::string& path, const std::string& option) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::InvalidArgumentError(absl::StrCat(option, ": cannot read '", path, "'"));
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().find("-----BEGIN ") == std::string::npos)
    return absl::InvalidArgumentError(absl::StrCat(option, ": '", path, "' is not a PEM file"));
  return text.str();
}

Status CheckTlsFiles(const TlsFiles& files) {
  if (files.client_cert.empty() != files.client_key.empty())
    return absl::InvalidArgumentError("--client-cert and --client-key go together");
  if (!files.enabled()) {
    if (!files.client_cert.empty())
      return absl::InvalidArgumentError("--client-cert needs --ca-cert (TLS)");
    return absl::OkStatus();
  }
  SEAPLAN_RETURN_IF_ERROR(ReadPemFile(files.ca_cert, "--ca-cert").status());
  if (!files.client_cert.empty()) {
    SEAPLAN_RETURN_IF_ERROR(ReadPemFile(files.client_cert, "--client-cert").status());
    SEAPLAN_RETURN_IF_ERROR(ReadPemFile(files.client_key, "--client-key").status());
  }
  return absl::OkStatus();
}

void AddTlsOptions(CLI::App& app, TlsFiles* files) {
  app.add_option("--ca-cert", files->ca_cert,
                 "CA certificate (PEM) that signed the server's: connect with TLS")
      ->envname("SEAPLAN_CA_CERT");
  app.add_option("--client-cert", files->client_cert,
                 "this client's certificate (PEM) for mutual TLS (CN = vessel id)")
      ->envname("SEAPLAN_CLIENT_CERT");
  app.add_option("--client-key", files->client_key, "private key (PEM) of --client-cert")
      ->envname("SEAPLAN_CLIENT_KEY");
}

}  // namespace seaplan::client
