// What a transport tells the core about one call, and the helpers the core
// uses to honour deadlines and cancellation.
#pragma once

#include <functional>
#include <string>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "server/auth/policy.h"

namespace seaplan::server {

// Who is calling: token id, role, vessel (auth::Caller). The transports set
// it from the call's credential; the default (empty token id) is the
// server's own work, which every check lets through.
using Caller = auth::Caller;

struct CallContext {
  // "grpc" or "http" (for logs).
  std::string transport;
  // Carries the client's deadline and is cancelled when the client goes
  // away or the server shuts down. A child of the server's root token.
  StopToken stop;
  // Polled by the core while it waits for work; true when the client is
  // gone (gRPC: ServerContext::IsCancelled()). May be empty.
  std::function<bool()> client_gone;
  // Set by the transport once the credential is checked; handlers of
  // vessel-scoped RPCs check the mission's vessel against it.
  Caller caller;

  // Who calls, as far as the transport knows (set by it after NewCall).
  // The subject CN of the client's verified TLS certificate (mutual TLS),
  // which names a vessel; empty without one.
  std::string client_cert_subject;
  // The caller's rate-limit key (caller_limits.h: CallerKey).
  std::string caller_key;
  // The RPC, "Service/Method" (set by the transport with the caller); an
  // audited one's handler writes its audit row (audit_entry.h).
  std::string method;

  // Cancels `stop` when the client is gone. Cheap; call it often. A
  // transport also reports the client "gone" when its deadline passes (gRPC
  // does); within kDeadlineSlack of the deadline that is left to the
  // deadline itself, so the work ends as DEADLINE_EXCEEDED, not CANCELLED.
  void ForwardCancellation() const {
    if (!client_gone || !client_gone()) return;
    if (StopToken::Clock::now() + kDeadlineSlack >= stop.deadline()) return;
    stop.Cancel();
  }
  static constexpr std::chrono::milliseconds kDeadlineSlack{100};
};

// A stream's sink: writes one message; false when the client is gone.
template <typename Message>
using StreamSink = std::function<bool(const Message&)>;

// The error for work that `stop` ended: DeadlineExceeded for the client's
// deadline, Unavailable when the server is shutting down (`shutting_down`),
// Cancelled otherwise (the client went away).
absl::Status StopStatus(const StopToken& stop, bool shutting_down, const std::string& what);

}  // namespace seaplan::server
