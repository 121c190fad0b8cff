// Opening (pragmas, migrations), knobs, capture rows, biometrics.
#include "knoblab/interchange/utf8.hpp"
#include "knoblab/store/store.hpp"

#include <sqlite3.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "internal.hpp"
#include "knoblab/store/schema.hpp"

namespace knoblab::store {

Store::Store(std::shared_ptr<sqlite::Connection> db) : db_(std::move(db)) {}
Store::Store(Store&&) noexcept = default;
Store& Store::operator=(Store&&) noexcept = default;
Store::~Store() = default;

namespace {

// Switching to WAL needs an exclusive lock, and sqlite answers SQLITE_BUSY
// at once (no busy handler) when another connection is opening the same
// fresh file right now; so wait for our turn here.
std::string enable_wal(sqlite::Connection& db, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    try {
      return db.query_text("PRAGMA journal_mode = WAL");
    } catch (const StoreError& e) {
      if ((e.sqlite_code() & 0xff) != SQLITE_BUSY || std::chrono::steady_clock::now() > deadline)
        throw;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace

Store Store::open_read_only(const std::filesystem::path& path, const OpenOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw StoreError(path.string() + ": no such store (reading never creates one)");
  auto db = std::make_shared<sqlite::Connection>(sqlite::Connection::open_read_only(path));
  db->set_busy_timeout(options.busy_timeout_ms);
  int version = 0;
  bool immutable = false;
  try {
    version = store::schema_version(*db);
  } catch (const StoreError& e) {
    // On read-only media (a write-protected card, a ro mount) sqlite cannot
    // create the WAL index beside the file. Nothing can write there either,
    // so reading it as immutable is exact, unless a log of commits not yet
    // in the file was left behind: those would be missed, so say so instead.
    const int primary = e.sqlite_code() & 0xff;
    if (primary != SQLITE_CANTOPEN && primary != SQLITE_READONLY) throw;
    const auto wal = std::filesystem::path(path.string() + "-wal");
    if (std::filesystem::exists(wal, ec) && std::filesystem::file_size(wal, ec) > 0)
      throw StoreError(path.string() + ": on read-only media with a write-ahead log (" + wal.filename().string() +
                           ") sqlite cannot read without writing beside it; copy the store with its -wal file "
                           "to writable media",
                       e.sqlite_code());
    db = std::make_shared<sqlite::Connection>(sqlite::Connection::open_immutable(path));
    version = store::schema_version(*db);
    immutable = true;
  }
  check_schema_not_newer(version);
  if (version < latest_schema_version() && immutable)
    throw StoreError(path.string() + ": schema version " + std::to_string(version) +
                     " needs an upgrade, which read-only media cannot take; copy the store to writable media");
  if (version < latest_schema_version()) {
    // This binary's queries need the current schema: upgrade once, briefly
    // read-write, then read as asked.
    db.reset();
    OpenOptions rw = options;
    rw.read_only = false;
    rw.recover = false;
    Store::open(path, rw);
    db = std::make_shared<sqlite::Connection>(sqlite::Connection::open_read_only(path));
    db->set_busy_timeout(options.busy_timeout_ms);
  }
  db->exec("PRAGMA foreign_keys = ON");
  return Store(std::move(db));
}

Store Store::open(const std::filesystem::path& path, const OpenOptions& options) {
  if (options.read_only) {
    try {
      return open_read_only(path, options);
    } catch (const StoreError& e) {
      const std::string what = e.what();
      if (what.starts_with(path.string())) throw;
      throw StoreError(path.string() + ": " + what, e.sqlite_code());
    }
  }
  if (!options.create && !std::filesystem::exists(path))
    throw StoreError(path.string() + ": no such store (give the path of an existing one)");
  auto db = std::make_shared<sqlite::Connection>(sqlite::Connection::open(path));
  try {
    db->set_busy_timeout(options.busy_timeout_ms);
    db->exec("PRAGMA foreign_keys = ON");
    // Before anything writes: never touch a database from a newer knoblab.
    const int version = store::schema_version(*db);
    check_schema_not_newer(version);
    // WAL: readers (list, export) never block the capture writer. Asked only
    // when not yet set: switching needs a lock, asking does not.
    if (db->query_text("PRAGMA journal_mode") != "wal") {
      const std::string mode = enable_wal(*db, options.busy_timeout_ms);
      if (mode != "wal") throw StoreError("cannot switch to WAL journal mode (got '" + mode + "')");
    }
    // FULL: every committed batch is on disk, even across a power cut.
    db->exec("PRAGMA synchronous = FULL");
    // A current schema is the common case: no transaction, so opening never
    // waits for another process's write lock.
    if (version < latest_schema_version()) migrate(*db);
  } catch (const StoreError& e) {
    throw StoreError(path.string() + ": " + e.what(), e.sqlite_code());
  }
  Store store(std::move(db));
  if (options.recover) {
    try {
      store.recover_interrupted();
    } catch (const StoreError& e) {
      // Another writer holds the lock longer than our timeout: the dead
      // writer's capture stays 'recording' until a later open marks it;
      // this open still works.
      if (!sqlite::is_busy(e)) throw StoreError(path.string() + ": " + e.what(), e.sqlite_code());
    }
  }
  return store;
}

int Store::schema_version() { return store::schema_version(*db_); }

void Store::set_busy_timeout(int ms) { db_->set_busy_timeout(ms); }

std::string Store::integrity_check() { return db_->query_text("PRAGMA integrity_check"); }

// ---- knobs ----------------------------------------------------------------

std::optional<std::int64_t> detail::resolve_knob(sqlite::Connection& db, std::string_view name,
                                                 std::string_view description, bool* created) {
  if (name.empty()) return std::nullopt;
  // A knob name is one line of readable text: it is printed in listings,
  // reports and file metadata, where a control character would garble them.
  if (const auto bad = interchange::first_invalid_utf8(name))
    throw std::invalid_argument("knob name is not valid UTF-8 (byte " + std::to_string(*bad + 1) + ")");
  if (const auto ctl = interchange::first_control_char(name))
    throw std::invalid_argument("knob name holds a control character (byte " + std::to_string(*ctl + 1) +
                                "); give one line of text");
  db.prepare("INSERT INTO knobs (name, description) VALUES (?1, ?2) ON CONFLICT (name) DO NOTHING")
      .bind_text(1, name)
      .bind_text(2, description)
      .run();
  if (created) *created = db.changes() == 1;
  auto st = db.prepare("SELECT id FROM knobs WHERE name = ?1");
  st.bind_text(1, name);
  if (!st.step()) throw StoreError("knob '" + std::string(name) + "' vanished");
  return st.column_int(0);
}

std::int64_t Store::knob_id(std::string_view name, std::string_view description) {
  if (name.empty()) throw std::invalid_argument("knob name must not be empty");
  sqlite::Transaction tx(*db_);
  const auto id = *detail::resolve_knob(*db_, name, description);
  tx.commit();
  return id;
}

std::vector<KnobInfo> Store::list_knobs() {
  std::vector<KnobInfo> knobs;
  auto st = db_->prepare("SELECT id, name, description, created_at FROM knobs ORDER BY id");
  while (st.step())
    knobs.push_back({st.column_int(0), st.column_text(1), st.column_text(2), st.column_text(3)});
  return knobs;
}

// ---- captures -------------------------------------------------------------

std::int64_t detail::insert_capture_row(sqlite::Connection& db, const NewCapture& info,
                                        std::string_view status, bool has_command,
                                        bool* created_knob) {
  const auto knob = resolve_knob(db, info.knob, {}, created_knob);
  auto st = db.prepare(
      "INSERT INTO captures (knob_id, mode, rate_hz, stimulus, orientation, calibration, source,"
      " status, writer_pid, writer_boot, has_command, metadata)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)");
  if (knob)
    st.bind_int(1, *knob);
  else
    st.bind_null(1);
  st.bind_text(2, info.mode)
      .bind_double(3, info.rate_hz)
      .bind_text(4, info.stimulus)
      .bind_text(5, info.orientation)
      .bind_text(6, info.calibration)
      .bind_text(7, info.source)
      .bind_text(8, status);
  if (status == "recording") {
    st.bind_int(9, ::getpid());
    const auto boot = boot_id();
    if (!boot.empty()) st.bind_text(10, boot);  // else stays NULL
  }
  st.bind_int(11, has_command ? 1 : 0);
  st.bind_text(12, info.metadata.empty() ? std::string_view("{}") : info.metadata);
  st.run();
  return db.last_insert_rowid();
}

std::optional<std::int64_t> detail::knob_of_capture(sqlite::Connection& db, std::int64_t id) {
  auto st = db.prepare("SELECT knob_id FROM captures WHERE id = ?1");
  st.bind_int(1, id);
  std::optional<std::int64_t> knob;
  if (st.step() && !st.is_null(0)) knob = st.column_int(0);
  st.reset();
  return knob;
}

void detail::remove_unfinished_capture(sqlite::Connection& db, std::int64_t id,
                                       std::optional<std::int64_t> created_knob) {
  sqlite::Transaction tx(db);
  db.prepare("DELETE FROM captures WHERE id = ?1").bind_int(1, id).run();
  if (created_knob)
    db.prepare(
          "DELETE FROM knobs WHERE id = ?1"
          " AND NOT EXISTS (SELECT 1 FROM captures WHERE knob_id = ?1)")
        .bind_int(1, *created_knob)
        .run();
  tx.commit();
}

CaptureWriter Store::begin_capture(const NewCapture& info, WriterOptions options) {
  if (options.batch_size == 0) throw std::invalid_argument("batch_size must be at least 1");
  if (info.source.empty())
    throw std::invalid_argument("NewCapture.source is required (e.g. 'simulate', 'hapticd')");
  sqlite::Transaction tx(*db_);
  bool created_knob = false;
  const auto id = detail::insert_capture_row(*db_, info, "recording", info.has_command, &created_knob);
  const auto knob = created_knob ? detail::knob_of_capture(*db_, id) : std::nullopt;
  tx.commit();
  return CaptureWriter(db_, id, info.has_command, std::move(options), knob);
}

void detail::delete_capture_row(sqlite::Connection& db, std::int64_t id) {
  auto st = db.prepare("SELECT status FROM captures WHERE id = ?1");
  st.bind_int(1, id);
  if (!st.step()) throw StoreError("no capture with id " + std::to_string(id));
  if (st.column_text(0) == "recording")
    throw StoreError("capture " + std::to_string(id) + " is still recording");
  st.reset();
  db.prepare("DELETE FROM captures WHERE id = ?1").bind_int(1, id).run();
}

void Store::delete_capture(std::int64_t id) {
  sqlite::Transaction tx(*db_);
  detail::delete_capture_row(*db_, id);
  tx.commit();
}

// ---- biometrics ----------------------------------------------------------

void Store::append_biometrics(std::int64_t capture_id, std::span<const BiometricSample> samples) {
  sqlite::Transaction tx(*db_);
  auto st = db_->prepare(
      "INSERT INTO biometrics (capture_id, seq, t, emg_corrugator, emg_depressor, skin_conductance)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
  for (const BiometricSample& b : samples) {
    st.bind_int(1, capture_id)
        .bind_int(2, b.seq)
        .bind_double(3, b.t)
        .bind_double(4, b.emg_corrugator)
        .bind_double(5, b.emg_depressor)
        .bind_double(6, b.skin_conductance);
    st.run();
  }
  tx.commit();
}

std::vector<BiometricSample> Store::load_biometrics(std::int64_t capture_id) {
  std::vector<BiometricSample> out;
  auto st = db_->prepare(
      "SELECT seq, t, emg_corrugator, emg_depressor, skin_conductance FROM biometrics"
      " WHERE capture_id = ?1 ORDER BY seq");
  st.bind_int(1, capture_id);
  while (st.step())
    out.push_back({st.column_int(0), st.column_double(1), st.column_double(2), st.column_double(3),
                   st.column_double(4)});
  return out;
}

}  // namespace knoblab::store
