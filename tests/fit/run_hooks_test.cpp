// fit_knob's RunHooks: the stages it reports, and a cancellation seen inside
// the Ceres solve (its IterationCallback) or between stages ends the fit
// with Cancelled instead of a result or a convergence error.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/validation_data.hpp"

namespace knoblab::fit {
namespace {

struct Recorder {
  std::vector<std::string> stages;
  int polls = 0;            // calls of `cancelled`
  int polls_in_fitting = 0;  // … since "fitting" was reported
};

RunHooks recording(Recorder& rec, const std::string& cancel_in, int after_polls = 0) {
  RunHooks h;
  h.progress = [&rec](std::string_view stage, std::size_t, std::size_t) {
    if (rec.stages.empty() || rec.stages.back() != stage) rec.stages.emplace_back(stage);
  };
  h.cancelled = [&rec, cancel_in, after_polls] {
    ++rec.polls;
    const bool in_stage = !rec.stages.empty() && rec.stages.back() == cancel_in;
    if (in_stage) ++rec.polls_in_fitting;
    return in_stage && rec.polls_in_fitting > after_polls;
  };
  return h;
}

TEST(FitRunHooks, AFitReportsItsStagesInOrderAndRunsToItsEnd) {
  const FitData d = make_validation_data({});
  Recorder rec;
  FitOptions opt;
  opt.hooks = recording(rec, "never");
  const FitResult r = fit_knob(d, opt);
  EXPECT_EQ(rec.stages, (std::vector<std::string>{"searching detents", "fitting", "stick band", "outliers",
                                                  "intervals"}));
  // Polled by Ceres every iteration, and between stages.
  EXPECT_GT(rec.polls, r.iterations);
  EXPECT_EQ(r.params.size(), 8u);
}

TEST(FitRunHooks, ACancellationDuringTheSolveStopsCeresAndThrowsCancelled) {
  const FitData d = make_validation_data({});
  Recorder rec;
  FitOptions opt;
  // Cancelled at the solver's second iteration: no later stage is reached.
  opt.hooks = recording(rec, "fitting", 1);
  EXPECT_THROW(fit_knob(d, opt), Cancelled);
  EXPECT_EQ(rec.stages, (std::vector<std::string>{"searching detents", "fitting"}));
  // The solve stopped at the poll that said so (its second iteration); the
  // check after it is the third. Without the callback the solve would not
  // poll, and the fit would go on to the stick band.
  EXPECT_EQ(rec.polls_in_fitting, 3);
}

TEST(FitRunHooks, ACancellationBeforeTheSolveThrowsCancelled) {
  const FitData d = make_validation_data({});
  Recorder rec;
  FitOptions opt;
  opt.hooks = recording(rec, "searching detents");
  EXPECT_THROW(fit_knob(d, opt), Cancelled);
  EXPECT_EQ(rec.stages, std::vector<std::string>{"searching detents"});
}

}  // namespace
}  // namespace knoblab::fit
