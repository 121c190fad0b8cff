// Plain records of the user studies' sessions, trials and notes (schema 8,
// docs/store.md "Study sessions"). Times are unix seconds (s since
// 1970-01-01T00:00:00Z, UTC), as a double; JSON fields are strings the caller
// builds, checked before anything is written.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace knoblab::store {

// What the caller says about the participant's session it opens.
struct NewStudySession {
  std::string study;                  // the protocol's id (its "study" key)
  std::string participant;            // a pseudonymous code (docs/studies.md), never a name
  std::size_t participant_index = 0;  // from 0, as study::plan took it
  std::string protocol_json;          // the protocol file as run, byte for byte
  std::size_t plan_trials = 0;        // trials in the participant's plan, > 0
  bool simulated = false;             // a simulated participant
};

// A session as stored.
struct StudySession {
  std::int64_t session_id = 0;
  std::string study, participant;
  std::size_t participant_index = 0;
  std::string protocol_json;
  std::string protocol_sha256;  // of protocol_json's bytes, 64 lowercase hex digits
  std::size_t plan_trials = 0;
  bool simulated = false;
  double started_unix = 0;                 // s, when the session was first opened
  std::optional<double> finished_unix;     // s; none while unfinished
  std::string knoblab_version;             // the knoblab that opened it
  std::size_t trials_committed = 0;        // trials in the store now
};

// One trial of a session, committed whole when it ends.
struct StudyTrial {
  std::int64_t session_id = 0;
  std::size_t trial_index = 0;   // 1-based index into the plan: 1 … plan_trials
  std::size_t block = 0;         // 1-based
  std::string stage;             // the stage's name
  bool practice = false;
  std::size_t repetition = 0;    // 1-based; 0 for a stage's practice trials
  std::string condition_json = "{}";  // JSON object {factor: level name}
  double started_unix = 0;       // s
  double ended_unix = 0;         // s, ≥ started_unix
  std::string result_json = "{}";      // the task's measures; any JSON, opaque to the store
  std::string ratings_json = "{}";     // any JSON (the ratings asked after the trial)
  std::string biometrics_json = "{}";  // scored EMG/SC and trial markers; any JSON, opaque
  std::string trace_json = "[]";       // the 100 ms telemetry trace; any JSON, opaque
  std::optional<std::int64_t> capture_id;  // hapticd's recording of the trial; none when
                                           // there was none, or it has since been deleted
};

// The experimenter's think-aloud note or tags, about the session or one trial.
struct StudyNote {
  std::int64_t note_id = 0;                // given by add_study_note
  std::int64_t session_id = 0;
  std::optional<std::size_t> trial_index;  // the trial it is about (1 … plan_trials), or none
  double noted_unix = 0;                   // s; add_study_note: 0 = now
  std::string text;                        // not empty
  std::string tags_json = "[]";            // JSON array of strings (free-text tags)
};

// What withdrawing a participant from a study deletes (or, previewed, would
// delete): their session with its trials and notes, and the captures of
// those trials with their samples, biometrics and results.
struct StudyWithdrawal {
  std::size_t sessions = 0;
  std::size_t trials = 0;
  std::size_t notes = 0;
  std::size_t captures = 0;
  std::int64_t samples = 0;          // in those captures
  std::size_t shared_captures = 0;   // kept: another participant's trial refers to them too
};

}  // namespace knoblab::store
