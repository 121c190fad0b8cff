// The control protocol's commands (docs/protocol.md) mapped onto the daemon:
// each becomes a CoreCommand for the loop, a note for the recorder, or an
// answer from state the loop publishes. Runs on the server's thread.
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "knoblab/control/command_handler.hpp"
#include "knoblab/control/server.hpp"
#include "knoblab/hapticd/recorder.hpp"
#include "knoblab/hapticd/render_params.hpp"
#include "knoblab/hapticd/supervisor.hpp"

namespace knoblab::hapticd {

class Daemon;

// `load_model` / `set_params` arguments (already checked against the
// protocol schema) applied to `base`: load_model replaces the model
// (partial = false), set_params changes only the keys given.
RenderParams render_params_from_args(const nlohmann::json& args, RenderParams base, bool partial);

// Why the device must not render `p`, or nullopt when it may: every value
// finite, those the physics needs non-negative so, and no torque term that
// alone exceeds the torque limit (the supervisor would clip it, so the knob
// would not feel like the model the researcher asked for).
std::optional<ParamProblem> render_params_problem(const RenderParams& p, const SafetyLimits& limits);

class ControlHandler final : public control::CommandHandler {
 public:
  ControlHandler(Daemon& daemon, const RenderParams& initial) : daemon_(daemon), params_(initial) {}

  control::Reply handle(const control::Request& request) override;
  void on_watchdog_expired(control::WatchdogReason reason) override;

  // From the writer thread: state changes and finished recordings as events.
  void publish_events(control::Server& server, const std::vector<FinishedRecording>& finished);

 private:
  control::Reply render(const nlohmann::json& args, bool partial);
  control::Reply start_capture(const nlohmann::json& args);
  control::Reply start_trial(const nlohmann::json& args);
  control::Reply load_tiles(const nlohmann::json& args);
  void publish_stats(control::Server& server);
  nlohmann::json state_json() const;
  std::optional<control::Reply> refused_while_faulted() const;

  Daemon& daemon_;
  std::mutex mutex_;         // handle() and publish_events() run on different threads
  RenderParams params_{};    // the last model sent to the loop
  std::uint32_t last_faults_ = 0;
  std::uint64_t last_presses_ = 0;  // capture-button presses already published
  std::uint32_t trial_id_ = 0;  // the running trial's recording (0: none)
  nlohmann::json trial_;        // its study, participant, condition
  std::vector<control::Event> pending_trial_events_;  // published by the writer thread
  nlohmann::json tiles_ = {{"position", 0}, {"time", 0}};  // the loaded set's size
  std::chrono::steady_clock::time_point next_stats_{};
  int last_mode_ = -1;
};

}  // namespace knoblab::hapticd
