// RunHooks in a Ceres solve: the solver stops at its next iteration once
// the run is cancelled (SOLVER_ABORT); the caller then calls hooks.check(),
// which throws Cancelled, before it looks at the summary. For the libraries
// that link Ceres (fit, discovery).
#pragma once

#include <ceres/iteration_callback.h>

#include "knoblab/fit/run_hooks.hpp"

namespace knoblab::fit {

class CancelCallback final : public ceres::IterationCallback {
 public:
  explicit CancelCallback(const RunHooks& hooks) : hooks_(hooks) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
    return hooks_.cancelled && hooks_.cancelled() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
  }

 private:
  const RunHooks& hooks_;
};

}  // namespace knoblab::fit
