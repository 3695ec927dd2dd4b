// Placeholder until the server core lands: replaced by the in-process core.
#include "backend.h"

namespace seaplan::cli {

std::unique_ptr<Backend> MakeLocalBackend() { return nullptr; }

}  // namespace seaplan::cli
