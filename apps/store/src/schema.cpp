// The migration list. Never edit a released step: append a new one.
#include "knoblab/store/schema.hpp"

#include <array>
#include <string>

namespace knoblab::store {

namespace {

#define KNOBLAB_NOW "(strftime('%Y-%m-%dT%H:%M:%fZ', 'now'))"

constexpr std::array kMigrations = {
    // 1: the tables. JSON columns are checked with json_valid so a caller's
    // bad string fails at insert time, not when someone reads it years later.
    R"sql(
CREATE TABLE knobs (
  id          INTEGER PRIMARY KEY,
  name        TEXT NOT NULL UNIQUE CHECK (length(name) > 0),
  description TEXT NOT NULL DEFAULT '',
  created_at  TEXT NOT NULL DEFAULT )sql" KNOBLAB_NOW R"sql(
);
CREATE TABLE captures (
  id           INTEGER PRIMARY KEY,
  knob_id      INTEGER REFERENCES knobs(id) ON DELETE RESTRICT,
  mode         TEXT NOT NULL CHECK (mode IN ('lab', 'tripod')),
  rate_hz      REAL NOT NULL CHECK (rate_hz > 0),
  stimulus     TEXT NOT NULL DEFAULT '{}' CHECK (json_valid(stimulus)),
  orientation  TEXT NOT NULL DEFAULT '{}' CHECK (json_valid(orientation)),
  calibration  TEXT NOT NULL DEFAULT '{}' CHECK (json_valid(calibration)),
  source       TEXT NOT NULL CHECK (length(source) > 0),
  status       TEXT NOT NULL CHECK (status IN ('recording', 'complete', 'incomplete')),
  writer_pid   INTEGER,
  writer_boot  TEXT,
  has_command  INTEGER NOT NULL DEFAULT 0 CHECK (has_command IN (0, 1)),
  started_at   TEXT NOT NULL DEFAULT )sql" KNOBLAB_NOW R"sql(,
  finished_at  TEXT,
  sample_count INTEGER NOT NULL DEFAULT 0 CHECK (sample_count >= 0),
  metadata     TEXT NOT NULL DEFAULT '{}' CHECK (json_valid(metadata))
);
CREATE TABLE samples (
  capture_id INTEGER NOT NULL REFERENCES captures(id) ON DELETE CASCADE,
  idx        INTEGER NOT NULL,
  t          REAL NOT NULL,
  theta      REAL NOT NULL,
  omega      REAL NOT NULL,
  alpha      REAL NOT NULL,
  torque     REAL NOT NULL,
  command    REAL,
  PRIMARY KEY (capture_id, idx)
) WITHOUT ROWID;
CREATE TABLE fits (
  id         INTEGER PRIMARY KEY,
  capture_id INTEGER NOT NULL REFERENCES captures(id) ON DELETE CASCADE,
  model      TEXT NOT NULL CHECK (length(model) > 0),
  params     TEXT NOT NULL CHECK (json_valid(params)),
  result     TEXT NOT NULL DEFAULT '{}' CHECK (json_valid(result)),
  created_at TEXT NOT NULL DEFAULT )sql" KNOBLAB_NOW R"sql(
);
)sql",
    // 2: indexes for the foreign keys (cascading deletes would scan without
    // them) and for recovery's "status = 'recording'" lookup on every open.
    R"sql(
CREATE INDEX captures_by_knob ON captures(knob_id);
CREATE INDEX captures_by_status ON captures(status);
CREATE INDEX fits_by_capture ON fits(capture_id);
)sql",
    // 3: the loop's per-sample state (amp enable, e-stop, fault: SampleFlag
    // bits) and the biometrics box's 32 Hz samples recorded beside a capture.
    R"sql(
ALTER TABLE samples ADD COLUMN flags INTEGER NOT NULL DEFAULT 0;
CREATE TABLE biometrics (
  capture_id       INTEGER NOT NULL REFERENCES captures(id) ON DELETE CASCADE,
  seq              INTEGER NOT NULL,
  t                REAL NOT NULL,
  emg_corrugator   REAL NOT NULL,
  emg_depressor    REAL NOT NULL,
  skin_conductance REAL NOT NULL,
  PRIMARY KEY (capture_id, seq)
) WITHOUT ROWID;
)sql",
    // 4: a fit's report files (plots, fit.json, render model), stored with the
    // fit row in one transaction. A name is one plain file name, since export
    // writes it into a directory. A rowid table: rows hold whole files, too
    // big for WITHOUT ROWID; the UNIQUE index serves the cascade from fits.
    R"sql(
CREATE TABLE fit_files (
  fit_id INTEGER NOT NULL REFERENCES fits(id) ON DELETE CASCADE,
  name   TEXT NOT NULL CHECK (length(name) > 0 AND instr(name, '/') = 0
                             AND name NOT IN ('.', '..')),
  bytes  BLOB NOT NULL CHECK (typeof(bytes) = 'blob'),
  UNIQUE (fit_id, name)
);
)sql",
    // 5: why a capture is incomplete, in words a person reads in `knoblab
    // list` ("fault: estop", "ring dropped 12 samples", "store busy", ...).
    // NULL for a capture that ended normally and for incomplete captures
    // stored before this version; only incomplete captures carry one.
    R"sql(
ALTER TABLE captures ADD COLUMN end_reason TEXT
  CHECK (end_reason IS NULL OR (length(end_reason) > 0 AND status = 'incomplete'));
)sql",
    // 6: a discrepancy run's result (docs/discrepancy.md's JSON), kept beside
    // its capture like a fit. The held-out capture, when one was held out
    // whole, is only a reference: deleting it keeps the result (it was true
    // of the data at the time) and forgets where the held-out rows came from.
    // Both foreign keys indexed, as in step 2, so deleting a capture finds
    // its rows without a scan.
    R"sql(
CREATE TABLE discrepancies (
  id                 INTEGER PRIMARY KEY,
  capture_id         INTEGER NOT NULL REFERENCES captures(id) ON DELETE CASCADE,
  heldout_capture_id INTEGER REFERENCES captures(id) ON DELETE SET NULL,
  result             TEXT NOT NULL CHECK (json_valid(result)),
  created_at         TEXT NOT NULL DEFAULT )sql" KNOBLAB_NOW R"sql(
);
CREATE INDEX discrepancies_by_capture ON discrepancies(capture_id);
CREATE INDEX discrepancies_by_heldout ON discrepancies(heldout_capture_id);
)sql",
    // 7: where each result came from: the knoblab version that made it, the
    // SHA-256 of the capture's samples it analysed, the options it ran with
    // (created_at says when). NULL all three for results stored before this
    // version, which nobody can vouch for now; a row has all or none. And a
    // discrepancy result's report files, kept like a fit's (step 4).
    R"sql(
ALTER TABLE fits ADD COLUMN tool_version TEXT
  CHECK (tool_version IS NULL OR length(tool_version) > 0);
ALTER TABLE fits ADD COLUMN input_sha256 TEXT
  CHECK (input_sha256 IS NULL OR (length(input_sha256) = 64 AND input_sha256 NOT GLOB '*[^0-9a-f]*'));
ALTER TABLE fits ADD COLUMN options TEXT
  CHECK ((options IS NULL OR CASE WHEN json_valid(options) THEN json_type(options) = 'object' ELSE 0 END)
         AND (tool_version IS NULL) = (options IS NULL) AND (input_sha256 IS NULL) = (options IS NULL));
ALTER TABLE discrepancies ADD COLUMN tool_version TEXT
  CHECK (tool_version IS NULL OR length(tool_version) > 0);
ALTER TABLE discrepancies ADD COLUMN input_sha256 TEXT
  CHECK (input_sha256 IS NULL OR (length(input_sha256) = 64 AND input_sha256 NOT GLOB '*[^0-9a-f]*'));
ALTER TABLE discrepancies ADD COLUMN options TEXT
  CHECK ((options IS NULL OR CASE WHEN json_valid(options) THEN json_type(options) = 'object' ELSE 0 END)
         AND (tool_version IS NULL) = (options IS NULL) AND (input_sha256 IS NULL) = (options IS NULL));
CREATE TABLE discrepancy_files (
  discrepancy_id INTEGER NOT NULL REFERENCES discrepancies(id) ON DELETE CASCADE,
  name           TEXT NOT NULL CHECK (length(name) > 0 AND instr(name, '/') = 0
                                     AND name NOT IN ('.', '..')),
  bytes          BLOB NOT NULL CHECK (typeof(bytes) = 'blob'),
  UNIQUE (discrepancy_id, name)
);
)sql",
    // 8: the user studies (docs/store.md "Study sessions"): one session per
    // participant of a study, with the protocol file as run; each trial in
    // one row, committed whole when it ends, so a session cut short resumes
    // at the first plan index without a row; the experimenter's notes. Times
    // are unix seconds. The participant is the pseudonymous code of
    // docs/studies.md (at least one digit: never a name). What ran is fixed
    // once a session is open, and the triggers keep trials inside the plan,
    // out of a finished session, and a session unfinished until every trial
    // is in. A trial's capture is only a reference, like a held-out capture
    // (step 6): deleting it keeps the trial. Rowid tables: a trial row holds
    // its whole trace.
    R"sql(
CREATE TABLE study_sessions (
  session_id        INTEGER PRIMARY KEY,
  study             TEXT NOT NULL CHECK (length(study) BETWEEN 1 AND 64
                                         AND study NOT GLOB '*[^A-Za-z0-9._-]*'),
  participant       TEXT NOT NULL CHECK (length(participant) BETWEEN 1 AND 16
                                         AND participant NOT GLOB '*[^A-Za-z0-9_-]*'
                                         AND participant GLOB '*[0-9]*'),
  participant_index INTEGER NOT NULL CHECK (participant_index >= 0),
  protocol_json     TEXT NOT NULL
    CHECK (CASE WHEN json_valid(protocol_json)
                THEN json_type(protocol_json) = 'object' AND json_extract(protocol_json, '$.study') IS study
                ELSE 0 END),
  protocol_sha256   TEXT NOT NULL
    CHECK (length(protocol_sha256) = 64 AND protocol_sha256 NOT GLOB '*[^0-9a-f]*'),
  plan_trials       INTEGER NOT NULL CHECK (plan_trials > 0),
  simulated         INTEGER NOT NULL CHECK (simulated IN (0, 1)),
  started_unix      REAL NOT NULL,
  finished_unix     REAL CHECK (finished_unix IS NULL OR finished_unix >= started_unix),
  knoblab_version   TEXT CHECK (knoblab_version IS NULL OR length(knoblab_version) > 0),
  UNIQUE (study, participant)
);
CREATE TABLE study_trials (
  session_id      INTEGER NOT NULL REFERENCES study_sessions(session_id) ON DELETE CASCADE,
  trial_index     INTEGER NOT NULL CHECK (trial_index >= 1),
  block           INTEGER NOT NULL CHECK (block >= 1),
  stage           TEXT NOT NULL CHECK (length(stage) > 0),
  practice        INTEGER NOT NULL CHECK (practice IN (0, 1)),
  repetition      INTEGER NOT NULL CHECK (repetition >= 0),
  condition_json  TEXT NOT NULL
    CHECK (CASE WHEN json_valid(condition_json) THEN json_type(condition_json) = 'object' ELSE 0 END),
  started_unix    REAL NOT NULL,
  ended_unix      REAL NOT NULL CHECK (ended_unix >= started_unix),
  result_json     TEXT NOT NULL CHECK (json_valid(result_json)),
  ratings_json    TEXT NOT NULL CHECK (json_valid(ratings_json)),
  biometrics_json TEXT NOT NULL CHECK (json_valid(biometrics_json)),
  trace_json      TEXT NOT NULL CHECK (json_valid(trace_json)),
  capture_id      INTEGER REFERENCES captures(id) ON DELETE SET NULL,
  PRIMARY KEY (session_id, trial_index)
);
CREATE INDEX study_trials_by_capture ON study_trials(capture_id);
CREATE TABLE study_notes (
  note_id     INTEGER PRIMARY KEY,
  session_id  INTEGER NOT NULL REFERENCES study_sessions(session_id) ON DELETE CASCADE,
  trial_index INTEGER CHECK (trial_index IS NULL OR trial_index >= 1),
  noted_unix  REAL NOT NULL,
  text        TEXT NOT NULL,
  tags_json   TEXT NOT NULL DEFAULT '[]'
    CHECK (CASE WHEN json_valid(tags_json) THEN json_type(tags_json) = 'array' ELSE 0 END),
  CHECK (length(text) > 0 OR json_array_length(tags_json) > 0)
);
CREATE INDEX study_notes_by_session ON study_notes(session_id);
CREATE TRIGGER study_sessions_fixed
BEFORE UPDATE OF study, participant, participant_index, protocol_json, protocol_sha256,
                 plan_trials, simulated, started_unix ON study_sessions
BEGIN
  SELECT RAISE(ABORT, 'a study session''s protocol, participant and plan are fixed once it is open');
END;
CREATE TRIGGER study_sessions_finish_complete
BEFORE UPDATE OF finished_unix ON study_sessions
WHEN NEW.finished_unix IS NOT NULL
 AND (SELECT count(*) FROM study_trials WHERE session_id = NEW.session_id) < NEW.plan_trials
BEGIN
  SELECT RAISE(ABORT, 'a study session with trials missing cannot be finished');
END;
CREATE TRIGGER study_trials_in_open_session
BEFORE INSERT ON study_trials
WHEN (SELECT finished_unix FROM study_sessions WHERE session_id = NEW.session_id) IS NOT NULL
BEGIN
  SELECT RAISE(ABORT, 'a finished study session takes no more trials');
END;
CREATE TRIGGER study_trials_in_plan
BEFORE INSERT ON study_trials
WHEN NEW.trial_index > (SELECT plan_trials FROM study_sessions WHERE session_id = NEW.session_id)
BEGIN
  SELECT RAISE(ABORT, 'a study trial''s index is past the end of its session''s plan');
END;
CREATE TRIGGER study_trials_stay_in_plan
BEFORE UPDATE OF session_id, trial_index ON study_trials
WHEN NEW.trial_index > (SELECT plan_trials FROM study_sessions WHERE session_id = NEW.session_id)
BEGIN
  SELECT RAISE(ABORT, 'a study trial''s index is past the end of its session''s plan');
END;
CREATE TRIGGER study_notes_in_plan
BEFORE INSERT ON study_notes
WHEN NEW.trial_index > (SELECT plan_trials FROM study_sessions WHERE session_id = NEW.session_id)
BEGIN
  SELECT RAISE(ABORT, 'a study note''s trial index is past the end of its session''s plan');
END;
)sql",
};

#undef KNOBLAB_NOW

}  // namespace

int schema_version(sqlite::Connection& db) {
  return static_cast<int>(db.query_int("PRAGMA user_version"));
}

void check_schema_not_newer(int version) {
  if (version > latest_schema_version())
    throw StoreError("database schema version " + std::to_string(version) +
                     " is newer than this knoblab understands (" +
                     std::to_string(latest_schema_version()) +
                     "); refusing to open it - upgrade knoblab");
}

int latest_schema_version() { return static_cast<int>(kMigrations.size()); }

void migrate(sqlite::Connection& db, int target) {
  check_schema_not_newer(schema_version(db));
  for (int step = 1; step <= target; ++step) {
    sqlite::Transaction tx(db);
    // Recheck under the write lock: another process may have got here first.
    const int version = schema_version(db);
    check_schema_not_newer(version);
    if (version >= step) continue;
    try {
      db.exec(kMigrations[static_cast<std::size_t>(step - 1)]);
    } catch (const StoreError& e) {
      throw StoreError("schema migration to version " + std::to_string(step) +
                           " failed: " + e.what(),
                       e.sqlite_code());
    }
    // PRAGMA takes no parameters; the value is our own integer.
    db.exec("PRAGMA user_version = " + std::to_string(step));
    tx.commit();
  }
}

}  // namespace knoblab::store
