// The in-process backend of the `seaplan` executable: the server's planning
// handlers (parse, ground, search, validate) and nothing else, so that
// `seaplan plan|validate` links only the planning engine libraries and
// starts in milliseconds. Charts, routes and risk run in seaplan-charts.
#include "backend.h"
#include "in_process.h"
#include "server/core/planning_handlers.h"
#include "server/core/work_pool.h"

namespace seaplan::cli {
namespace {

class PlanningBackend final : public InProcessBackend {
 public:
  // One worker: the CLI makes one call at a time.
  PlanningBackend() : pool_(1), planning_(pool_, root_) {}
  ~PlanningBackend() override {
    root_.Cancel();
    pool_.Shutdown();
  }

  absl::Status Plan(const v1::PlanRequest& request, v1::PlanResponse* response) override {
    return Assign(planning_.Plan(request, NewCall(root_)), response);
  }
  absl::Status PlanStream(
      const v1::PlanRequest& request,
      const std::function<void(const v1::PlanStreamEvent&)>& on_event) override {
    return planning_.PlanStream(request, NewCall(root_), [&](const v1::PlanStreamEvent& event) {
      on_event(event);
      return true;
    });
  }
  absl::Status Validate(const v1::ValidateRequest& request,
                        v1::ValidateResponse* response) override {
    return Assign(planning_.Validate(request, NewCall(root_)), response);
  }

 protected:
  absl::Status Refuse(const char* method) const override {
    return absl::UnimplementedError(std::string(method) +
                                    " is not linked into this executable (it runs in "
                                    "seaplan-charts or seaplan-remote)");
  }

 private:
  StopToken root_;
  server::WorkPool pool_;
  server::PlanningHandlers planning_;
};

}  // namespace

std::unique_ptr<Backend> MakePlanningBackend() {
  return std::make_unique<PlanningBackend>();
}

}  // namespace seaplan::cli
