#include "knoblab/store/sqlite.hpp"

#include <sqlite3.h>

#include <cstdio>
#include <string>

#include <utility>

namespace knoblab::store::sqlite {

namespace {
[[noreturn]] void throw_sqlite(sqlite3* db, int rc, std::string_view context) {
  std::string msg(context);
  msg += ": ";
  msg += db ? sqlite3_errmsg(db) : sqlite3_errstr(rc);
  const int code = db ? sqlite3_extended_errcode(db) : rc;
  throw StoreError(msg, code);
}
}  // namespace

// ---- Connection -----------------------------------------------------------

bool is_busy(const StoreError& e) { return (e.sqlite_code() & 0xff) == SQLITE_BUSY; }

Connection Connection::open(const std::filesystem::path& path) {
  return open(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
}

Connection Connection::open_read_only(const std::filesystem::path& path) {
  return open(path, SQLITE_OPEN_READONLY);
}

Connection Connection::open_immutable(const std::filesystem::path& path) {
  // A URI: percent-encode what would end the path or start the query.
  std::string uri = "file:";
  for (unsigned char c : path.string()) {
    if (c == '%' || c == '?' || c == '#' || c < 0x20) {
      char esc[4];
      std::snprintf(esc, sizeof esc, "%%%02X", c);
      uri += esc;
    } else {
      uri += static_cast<char>(c);
    }
  }
  return open(uri + "?immutable=1", SQLITE_OPEN_READONLY | SQLITE_OPEN_URI);
}

Connection Connection::open(const std::filesystem::path& path, int flags) {
  sqlite3* db = nullptr;
  const int rc = sqlite3_open_v2(path.c_str(), &db, flags | SQLITE_OPEN_EXRESCODE, nullptr);
  if (rc != SQLITE_OK) {
    // sqlite hands back a handle even on failure, to carry the message.
    std::string msg = "cannot open database " + path.string() + ": " +
                      (db ? sqlite3_errmsg(db) : sqlite3_errstr(rc));
    sqlite3_close(db);
    throw StoreError(msg, rc);
  }
  sqlite3_extended_result_codes(db, 1);
  return Connection(db);
}

Connection::Connection(Connection&& other) noexcept : db_(std::exchange(other.db_, nullptr)) {}

Connection& Connection::operator=(Connection&& other) noexcept {
  if (this != &other) {
    sqlite3_close_v2(db_);
    db_ = std::exchange(other.db_, nullptr);
  }
  return *this;
}

// close_v2: a Statement that outlives us keeps the handle alive until it goes.
Connection::~Connection() { sqlite3_close_v2(db_); }

void Connection::exec(std::string_view sql) {
  const std::string text(sql);
  char* err = nullptr;
  const int rc = sqlite3_exec(db_, text.c_str(), nullptr, nullptr, &err);
  if (rc != SQLITE_OK) {
    std::string msg = err ? err : sqlite3_errstr(rc);
    sqlite3_free(err);
    throw StoreError("sql failed (" + text.substr(0, 60) + "): " + msg,
                     sqlite3_extended_errcode(db_));
  }
}

Statement Connection::prepare(std::string_view sql) {
  sqlite3_stmt* stmt = nullptr;
  const int rc = sqlite3_prepare_v3(db_, sql.data(), static_cast<int>(sql.size()),
                                    SQLITE_PREPARE_PERSISTENT, &stmt, nullptr);
  if (rc != SQLITE_OK) throw_sqlite(db_, rc, "prepare (" + std::string(sql.substr(0, 60)) + ")");
  return Statement(stmt);
}

std::int64_t Connection::query_int(std::string_view sql) {
  auto st = prepare(sql);
  if (!st.step()) throw StoreError("query returned no row: " + std::string(sql));
  return st.column_int(0);
}

std::string Connection::query_text(std::string_view sql) {
  auto st = prepare(sql);
  if (!st.step()) throw StoreError("query returned no row: " + std::string(sql));
  return st.column_text(0);
}

std::int64_t Connection::last_insert_rowid() const { return sqlite3_last_insert_rowid(db_); }

std::int64_t Connection::changes() const { return sqlite3_changes64(db_); }

bool Connection::in_transaction() const { return sqlite3_get_autocommit(db_) == 0; }

void Connection::set_busy_timeout(int ms) {
  if (const int rc = sqlite3_busy_timeout(db_, ms); rc != SQLITE_OK) fail(rc, "busy_timeout");
}

void Connection::fail(int rc, std::string_view context) const { throw_sqlite(db_, rc, context); }

// ---- Statement ------------------------------------------------------------

Statement::Statement(Statement&& other) noexcept : stmt_(std::exchange(other.stmt_, nullptr)) {}

Statement& Statement::operator=(Statement&& other) noexcept {
  if (this != &other) {
    sqlite3_finalize(stmt_);
    stmt_ = std::exchange(other.stmt_, nullptr);
  }
  return *this;
}

Statement::~Statement() { sqlite3_finalize(stmt_); }

void Statement::fail(int rc) const {
  const char* sql = sqlite3_sql(stmt_);
  throw_sqlite(sqlite3_db_handle(stmt_), rc, std::string(sql ? sql : "").substr(0, 60));
}

Statement& Statement::bind_double(int index, double value) {
  if (const int rc = sqlite3_bind_double(stmt_, index, value); rc != SQLITE_OK) fail(rc);
  return *this;
}

Statement& Statement::bind_int(int index, std::int64_t value) {
  if (const int rc = sqlite3_bind_int64(stmt_, index, value); rc != SQLITE_OK) fail(rc);
  return *this;
}

Statement& Statement::bind_text(int index, std::string_view value) {
  // An empty view may have a null data(), which sqlite would bind as NULL.
  const char* text = value.data() ? value.data() : "";
  const int rc =
      sqlite3_bind_text64(stmt_, index, text, value.size(), SQLITE_TRANSIENT, SQLITE_UTF8);
  if (rc != SQLITE_OK) fail(rc);
  return *this;
}

Statement& Statement::bind_blob(int index, std::span<const std::uint8_t> bytes) {
  // A null pointer would bind NULL; an empty span may well have one.
  static constexpr std::uint8_t kEmpty = 0;
  const void* data = bytes.empty() ? &kEmpty : bytes.data();
  const int rc = sqlite3_bind_blob64(stmt_, index, data, bytes.size(), SQLITE_TRANSIENT);
  if (rc != SQLITE_OK) fail(rc);
  return *this;
}

Statement& Statement::bind_null(int index) {
  if (const int rc = sqlite3_bind_null(stmt_, index); rc != SQLITE_OK) fail(rc);
  return *this;
}

bool Statement::step() {
  const int rc = sqlite3_step(stmt_);
  if (rc == SQLITE_ROW) return true;
  if (rc == SQLITE_DONE) {
    sqlite3_reset(stmt_);
    return false;
  }
  // The message must be read before reset, which would replace it.
  const char* sql = sqlite3_sql(stmt_);
  std::string context = std::string(sql ? sql : "").substr(0, 60);
  sqlite3* db = sqlite3_db_handle(stmt_);
  std::string msg = context + ": " + sqlite3_errmsg(db);
  const int code = sqlite3_extended_errcode(db);
  sqlite3_reset(stmt_);
  throw StoreError(msg, code);
}

void Statement::run() {
  if (step()) {
    sqlite3_reset(stmt_);
    throw StoreError("statement returned rows where none were expected");
  }
}

void Statement::reset() {
  sqlite3_reset(stmt_);
  sqlite3_clear_bindings(stmt_);
}

int Statement::column_count() const { return sqlite3_column_count(stmt_); }

bool Statement::is_null(int column) const {
  return sqlite3_column_type(stmt_, column) == SQLITE_NULL;
}
double Statement::column_double(int column) const { return sqlite3_column_double(stmt_, column); }
std::int64_t Statement::column_int(int column) const { return sqlite3_column_int64(stmt_, column); }
std::string Statement::column_text(int column) const {
  const auto* text = sqlite3_column_text(stmt_, column);
  if (!text) return {};
  return std::string(reinterpret_cast<const char*>(text),
                     static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column)));
}

std::vector<std::uint8_t> Statement::column_blob(int column) const {
  // Pointer first, then size (sqlite's documented order); empty = null pointer.
  const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(stmt_, column));
  const auto size = static_cast<std::size_t>(sqlite3_column_bytes(stmt_, column));
  if (!data) return {};
  return std::vector<std::uint8_t>(data, data + size);
}

// ---- Transaction ----------------------------------------------------------

Transaction::Transaction(Connection& db, Kind kind) : db_(db) {
  db_.exec(kind == kWrite ? "BEGIN IMMEDIATE" : "BEGIN");
}

Transaction::~Transaction() {
  if (!open_) return;
  // ROLLBACK can fail only if sqlite already rolled back itself (e.g. after
  // SQLITE_FULL); either way nothing of this transaction remains.
  sqlite3_exec(db_.handle(), "ROLLBACK", nullptr, nullptr, nullptr);
}

void Transaction::commit() {
  db_.exec("COMMIT");
  open_ = false;
}

}  // namespace knoblab::store::sqlite
