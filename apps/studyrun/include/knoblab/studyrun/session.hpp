// Runs a participant's session of a study: trial after trial of the
// participant's plan, from the first one the store does not hold yet, each
// committed to the store in one transaction the moment it ends — its
// condition, times, the task's measures, the ratings, the 100 ms trace of the
// knob (thesis §4.5.1.2), the biometric scores with their markers, and the
// capture hapticd recorded. A session cut by a crash, a killed process or a
// power cut is resumed by running it again: it starts at the trial that was
// in progress, which had not been committed.
//
// Each trial: the bare knob; the trial's recording starts; a quiet baseline
// when biometrics are recorded; the task runs on the knob's readings (the
// condition is rendered from its onset); the bare knob again; the recording
// stops; the participant rates; the trial is committed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "knoblab/store/store.hpp"
#include "knoblab/study/plan.hpp"
#include "knoblab/study/protocol.hpp"
#include "knoblab/studyrun/apparatus.hpp"
#include "knoblab/studyrun/display.hpp"
#include "knoblab/studyrun/participant.hpp"

namespace knoblab::studyrun {

struct SessionOptions {
  bool simulated = false;        // stored with the session
  double baseline_s = 2.0;       // quiet time before onset when biometrics are recorded
  double trace_period_s = 0.1;   // the trace's sampling (§4.5.1.2: every 100 ms)
  // Stop after this many trials this run (0: run to the end); the session
  // stays open and resumes where it stopped.
  std::size_t max_trials = 0;
  std::function<bool()> cancelled;  // asked with every reading: true stops the session
  std::function<void(const Display&)> on_display;  // the participant view, when it changes
  std::function<void(const study::Trial&, std::size_t of)> on_trial_start;
  std::function<void(const store::StudyTrial&)> on_trial_committed;
};

struct SessionResult {
  std::int64_t session_id = 0;
  std::size_t resumed_at = 0;     // the first trial run this time (1-based)
  std::size_t trials_run = 0;
  bool finished = false;          // every trial of the plan is committed
};

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("the session was stopped; it resumes at the trial that was running") {}
};

// `protocol_json` is the protocol file's text, stored with the session.
// Throws ApparatusError when the knob is lost, Cancelled when asked to stop,
// store errors as they come; in each case every trial committed so far stays.
SessionResult run_session(store::Store& store, const study::Protocol& protocol, const std::string& protocol_json,
                          const std::string& participant, std::size_t participant_index, Apparatus& apparatus,
                          Participant& participant_model, const SessionOptions& options = {});

// The seed of trial `index` of a plan: what the task draws (a list target).
std::uint64_t trial_seed(const study::Plan& plan, std::size_t index);

}  // namespace knoblab::studyrun
