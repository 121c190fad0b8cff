// The apparatus as hapticd: renders with load_model (and render mode),
// records trials with start_trial/stop_trial, and reads the knob from the
// telemetry ring (1 kHz records). Lost hapticd, a latched fault or a ring
// that stops moving is an ApparatusError: the trial in progress is dropped
// and the session resumes at it once hapticd is back.
#pragma once

#include <chrono>
#include <deque>
#include <memory>
#include <string>

#include "knoblab/control/client.hpp"
#include "knoblab/control/telemetry_reader.hpp"
#include "knoblab/studyrun/apparatus.hpp"

namespace knoblab::studyrun {

class HapticdApparatus final : public Apparatus {
 public:
  // Connects (throws ApparatusError naming the socket and the reason).
  // Telemetry silent for `silence_limit` means hapticd hangs. A killed
  // hapticd is seen sooner, by its control socket closing (its ring is never
  // closed). On a busy emulated machine (the image test's guest on a slow
  // host) hapticd's telemetry has stopped for more than 5 s, so the limit is
  // tens of seconds.
  explicit HapticdApparatus(const std::string& socket_path,
                            std::chrono::milliseconds silence_limit = std::chrono::seconds(30));
  // Stops a trial's recording left running by a session that was stopped or
  // failed mid-trial: hapticd would refuse the next start_trial, the resumed
  // session's, as busy.
  ~HapticdApparatus() override;
  HapticdApparatus(const HapticdApparatus&) = delete;
  HapticdApparatus& operator=(const HapticdApparatus&) = delete;
  void render(const study::Rendering& rendering) override;
  void start_trial(const TrialLabel& label) override;
  TrialRecording stop_trial() override;
  KnobReading next() override;

  // The load_model arguments for a rendering (the protocol's detent count
  // is hapticd's P_pos = 1/detents per revolution).
  static nlohmann::json model_args(const study::Rendering& rendering);

 private:
  nlohmann::json call(std::string_view cmd, nlohmann::json args = nlohmann::json::object());
  void take(const control::Event& event, bool fault_throws);
  std::optional<control::Event> wait_event(std::chrono::milliseconds timeout);

  control::Client client_;
  std::unique_ptr<control::TelemetryReader> telemetry_;
  std::deque<control::TelemetryRecord> pending_;
  std::chrono::milliseconds silence_limit_;
  std::chrono::steady_clock::time_point last_record_, last_poll_;
  std::optional<study::Rendering> rendered_;
  bool render_mode_ = false;
  std::optional<TrialRecording> stopped_;  // from the trial event
  bool recording_ = false;                 // a trial started and not yet stopped
};

}  // namespace knoblab::studyrun
