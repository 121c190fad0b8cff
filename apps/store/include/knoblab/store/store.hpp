// The knoblab database: one sqlite file in WAL mode holding knobs, captures
// with their samples, results - fits and discrepancy results - with their
// report files and provenance, and the user studies' sessions with their
// trials and notes (docs/store.md).
// Typical use:
//
//   auto store = Store::open("knoblab.db");
//   auto w = store.begin_capture({.knob = "fan", .rate_hz = 10000, .source = "hapticd"});
//   for (...) w.append(sample);
//   w.finish();
//   interchange::write_csv(store.load_samples(w.capture_id()), "fan.csv");
//
// A Store is one connection: use it from one thread at a time. Several
// processes may open the same file; sqlite serialises their writes, and
// every writer here keeps its transactions short (a batch of samples), so
// none waits on another for long. Readers never wait on writers (WAL).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <span>
#include <string_view>
#include <vector>

#include "knoblab/interchange/capture.hpp"
#include "knoblab/store/capture_writer.hpp"
#include "knoblab/store/error.hpp"
#include "knoblab/store/sqlite.hpp"
#include "knoblab/store/study_types.hpp"
#include "knoblab/store/types.hpp"

namespace knoblab::store {

struct OpenOptions {
  int busy_timeout_ms = 5000;  // wait this long for another writer's lock
  bool recover = true;         // run recover_interrupted() after opening
  // Open for reading only (list, export): the connection never writes, so it
  // never waits for another writer's lock, and writes fail. The file must
  // exist; one with an older schema is first upgraded by a brief read-write
  // open. No recovery.
  bool read_only = false;
  // false: a missing file is an error ("no such store"), not a new empty
  // store (a command that adds to an existing store, e.g. a fit of a capture).
  bool create = true;
};

struct ImportOptions {
  // Each transaction ends once it has run this long (its commit comes on
  // top), so another writer - hapticd recording - never waits much longer.
  std::chrono::milliseconds max_transaction{100};
  // Pause after each commit: sqlite's write lock is not fair, and a writer
  // polling from its busy handler gets in only while nobody holds it.
  std::chrono::milliseconds pause{20};
  // Called after each commit with the samples committed so far.
  std::function<void(std::int64_t committed)> on_commit;
};

class Store {
 public:
  // Opens (creating if needed) and migrates an older schema. Takes the write
  // lock only when there is something to write (a migration, a dead writer's
  // capture to mark). Throws StoreError, e.g. for a database written by a
  // newer knoblab.
  static Store open(const std::filesystem::path& path, const OpenOptions& options = {});

  Store(Store&&) noexcept;
  Store& operator=(Store&&) noexcept;
  ~Store();

  int schema_version();

  // Replaces OpenOptions::busy_timeout_ms for this connection.
  void set_busy_timeout(int ms);

  // Marks captures left 'recording' by a process that no longer exists as
  // 'incomplete' (their committed samples stay), with an end_reason saying
  // so. Returns their ids.
  std::vector<std::int64_t> recover_interrupted();

  // Id of the knob with this name, creating it if needed.
  std::int64_t knob_id(std::string_view name, std::string_view description = {});
  std::vector<KnobInfo> list_knobs();

  // Inserts a 'recording' capture row and returns its writer.
  CaptureWriter begin_capture(const NewCapture& info, WriterOptions options = {});

  // All of `capture` as one 'complete' capture (its flags too, when it has
  // them), written in short transactions so other writers go on meanwhile:
  // the row first, 'recording' with our pid; the samples in committed batches
  // (see ImportOptions); 'complete' last. Readers see it 'recording' with the
  // samples committed so far. On any error the partial capture - and a knob
  // it created - is removed again; if the process dies instead, the next
  // open marks it 'incomplete'. Throws std::invalid_argument (before writing
  // anything) for a capture interchange::validate() rejects, StoreError for
  // database failures.
  std::int64_t import_capture(const interchange::Capture& capture, const NewCapture& info,
                              const ImportOptions& options = {});

  std::vector<CaptureInfo> list_captures();  // by id
  std::optional<CaptureInfo> capture_info(std::int64_t id);

  // Committed samples in order; metadata carries the capture's fields
  // (capture_id, knob, mode, rate_hz, source, status, end_reason when there
  // is one, times, sample_count, stimulus, orientation, calibration,
  // metadata). Throws for an unknown id.
  // Note: sqlite stores -0.0 as 0.0; all other values come back bit-exact.
  interchange::Capture load_samples(std::int64_t id);

  // With its samples, biometrics, fits and their files, and its discrepancy
  // results; results that held it out are kept, without a held-out capture.
  // Refuses a capture still 'recording'.
  void delete_capture(std::int64_t id);

  // A fit of a capture, its report files and its provenance, in one
  // transaction: on any error (unknown capture, invalid JSON, a bad or
  // duplicate file name, a provenance field out of shape) nothing is left
  // behind, and a crash never leaves a fit without its files. knoblab's
  // commands always give the provenance; none leaves its columns NULL.
  std::int64_t insert_fit(std::int64_t capture_id, std::string_view model,
                          std::string_view params_json, std::string_view result_json = "{}",
                          std::span<const FitFile> files = {},
                          const std::optional<Provenance>& provenance = std::nullopt);
  std::vector<FitInfo> list_fits(std::int64_t capture_id);  // by id
  std::vector<FitInfo> list_all_fits();                     // of every capture, by id
  std::optional<FitInfo> fit_info(std::int64_t fit_id);

  // A fit's files by name; empty for a fit without files or an unknown id.
  std::vector<FitFileInfo> list_fit_files(std::int64_t fit_id);
  // Throws StoreError for an unknown fit or name.
  std::vector<std::uint8_t> load_fit_file(std::int64_t fit_id, std::string_view name);
  // All of a fit's files, by name, from one snapshot. Throws StoreError for an
  // unknown fit.
  std::vector<FitFile> load_fit_files(std::int64_t fit_id);

  // A discrepancy result of a capture (discovery::to_json), with the capture
  // held out whole when there was one, its report files and its provenance,
  // in one transaction as insert_fit. Throws StoreError, storing nothing,
  // for an unknown capture or held-out capture, invalid JSON, a bad file
  // name or provenance.
  std::int64_t insert_discrepancy(std::int64_t capture_id, std::string_view result_json,
                                  std::optional<std::int64_t> heldout_capture_id = std::nullopt,
                                  std::span<const ResultFile> files = {},
                                  const std::optional<Provenance>& provenance = std::nullopt);
  std::vector<DiscrepancyInfo> list_discrepancies(std::int64_t capture_id);  // by id
  std::vector<DiscrepancyInfo> list_all_discrepancies();                     // of every capture, by id
  std::optional<DiscrepancyInfo> discrepancy_info(std::int64_t id);
  // A discrepancy result's files by name (empty for none or an unknown id);
  // all of them from one snapshot (throws StoreError for an unknown id).
  std::vector<ResultFileInfo> list_discrepancy_files(std::int64_t id);
  std::vector<ResultFile> load_discrepancy_files(std::int64_t id);

  // Biometrics recorded beside a capture, appended in one transaction.
  void append_biometrics(std::int64_t capture_id, std::span<const BiometricSample> samples);
  std::vector<BiometricSample> load_biometrics(std::int64_t capture_id);

  // ---- user studies (schema 8; docs/store.md "Study sessions") ----
  // Each write is one short transaction; on a store another writer keeps
  // busy past the busy timeout it throws a StoreError that sqlite::is_busy
  // recognises, having written nothing: call it again.

  // Opens the participant's session of this study: creates it (started now,
  // with this knoblab's version and the protocol's SHA-256), or returns the
  // existing one to resume - finished or not. Refuses (StoreError, saying
  // what differs) when the existing session ran a different protocol file
  // (its bytes' SHA-256 differs), has a different plan size or participant
  // index, or is of a simulated participant and this one is not (or the
  // other way round); and a participant that is not a pseudonymous code, a
  // bad study id, plan_trials 0, a protocol that is not a JSON object whose
  // "study" is `study`.
  StudySession open_study_session(const NewStudySession& session);
  std::optional<StudySession> study_session(std::int64_t session_id);
  std::vector<StudySession> study_sessions(std::string_view study);  // all participants, by session_id

  // The whole trial in one transaction, or nothing: a crash leaves it
  // committed whole or not at all. Refuses (StoreError, storing nothing) an
  // unknown session, an index already committed (the stored trial is kept),
  // one outside 1 … plan_trials, a finished session, a JSON field that is not
  // valid JSON (condition_json: not an object), times not finite or ending
  // before they start, an unknown capture.
  void commit_study_trial(const StudyTrial& trial);
  std::vector<StudyTrial> study_trials(std::int64_t session_id);  // by trial_index
  // Where a session resumes: the first plan index (1-based) with no committed
  // trial; none when all are committed. Throws StoreError for an unknown session.
  std::optional<std::size_t> next_study_trial(std::int64_t session_id);
  // Sets finished_unix (now). Refuses while any trial of the plan is missing;
  // a session already finished keeps its first finish time.
  void finish_study_session(std::int64_t session_id);

  // The experimenter's note, about the session or one trial of its plan
  // (committed or not), finished or not; returns its id. Refuses an unknown
  // session, a trial outside the plan, tags that are not a JSON array of
  // strings, a note with neither text nor tags.
  std::int64_t add_study_note(const StudyNote& note);
  std::vector<StudyNote> study_notes(std::int64_t session_id);  // by note_id

  // A participant's withdrawal from a study (their right to have their data
  // deleted), in one transaction: their session, its trials and notes, and
  // every capture of those trials with what cascades from it (as
  // delete_capture) - except a capture another participant's trial also
  // refers to, which is kept. Finished or not. Freed pages are overwritten
  // with zeros (sqlite's secure_delete) and the write-ahead log is
  // checkpointed and emptied when no other connection is using it, so the
  // deleted rows do not linger readable in the file. Refuses (StoreError,
  // deleting nothing) a participant without a session of this study, naming
  // the codes that have one, and a capture still 'recording'.
  StudyWithdrawal withdraw_study_participant(std::string_view study, std::string_view participant);
  // What withdraw_study_participant would delete now, from one snapshot;
  // deletes nothing (works on a read-only store). Refuses as it does.
  StudyWithdrawal study_withdrawal(std::string_view study, std::string_view participant);

  std::string integrity_check();  // "ok" when sqlite finds nothing wrong

  sqlite::Connection& connection() { return *db_; }

 private:
  explicit Store(std::shared_ptr<sqlite::Connection> db);
  static Store open_read_only(const std::filesystem::path& path, const OpenOptions& options);

  // Shared with the writers, so a writer outliving its Store stays valid.
  std::shared_ptr<sqlite::Connection> db_;
};

}  // namespace knoblab::store
