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
