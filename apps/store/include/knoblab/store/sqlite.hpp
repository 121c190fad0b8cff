// Minimal RAII over the sqlite C API: one owner per handle, every failure a
// StoreError carrying sqlite's own message. Not thread-safe: one Connection
// per thread.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "knoblab/store/error.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace knoblab::store::sqlite {

class Statement;

// SQLITE_BUSY (any extended code): another connection holds the lock; the
// same operation may succeed later.
bool is_busy(const StoreError& e);

class Connection {
 public:
  // Opens read-write, creating the file if needed.
  static Connection open(const std::filesystem::path& path);
  // Opens an existing file read-only: every write fails with SQLITE_READONLY,
  // and the connection never takes the write lock.
  static Connection open_read_only(const std::filesystem::path& path);
  // Opens a file on read-only media, where sqlite cannot make the WAL index
  // (-shm) it needs beside the file: sqlite's immutable=1, no locks at all.
  static Connection open_immutable(const std::filesystem::path& path);

  Connection(Connection&& other) noexcept;
  Connection& operator=(Connection&& other) noexcept;
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
  ~Connection();

  // Runs one or more statements that return nothing of interest.
  void exec(std::string_view sql);
  Statement prepare(std::string_view sql);

  // First column of the first row of a query (a PRAGMA, a count).
  std::int64_t query_int(std::string_view sql);
  std::string query_text(std::string_view sql);

  std::int64_t last_insert_rowid() const;
  std::int64_t changes() const;  // rows changed by the last statement
  bool in_transaction() const;
  // How long a statement waits for another connection's lock before it fails
  // with SQLITE_BUSY (sqlite's busy handler, polling).
  void set_busy_timeout(int ms);
  sqlite3* handle() const { return db_; }

  [[noreturn]] void fail(int rc, std::string_view context) const;

 private:
  explicit Connection(sqlite3* db) : db_(db) {}
  static Connection open(const std::filesystem::path& path, int flags);
  sqlite3* db_ = nullptr;
};

class Statement {
 public:
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&& other) noexcept;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement();

  // Parameters are 1-based, as in sqlite.
  Statement& bind_double(int index, double value);
  Statement& bind_int(int index, std::int64_t value);
  Statement& bind_text(int index, std::string_view value);
  // Always a BLOB, also when empty (never NULL).
  Statement& bind_blob(int index, std::span<const std::uint8_t> bytes);
  Statement& bind_null(int index);

  // true while rows come; on completion the statement resets itself (ending
  // its implicit read transaction) and keeps its bindings for a rerun.
  bool step();
  // Step a statement that returns no rows.
  void run();
  void reset();  // back to the start, bindings cleared

  // Columns are 0-based, as in sqlite.
  int column_count() const;
  bool is_null(int column) const;
  double column_double(int column) const;
  std::int64_t column_int(int column) const;
  std::string column_text(int column) const;
  std::vector<std::uint8_t> column_blob(int column) const;

 private:
  friend class Connection;
  explicit Statement(sqlite3_stmt* stmt) : stmt_(stmt) {}
  [[noreturn]] void fail(int rc) const;
  sqlite3_stmt* stmt_ = nullptr;
};

// ROLLBACK on destruction unless committed.
class Transaction {
 public:
  // kWrite: BEGIN IMMEDIATE, taking the write lock now so a busy database
  // fails here rather than halfway through. kRead: BEGIN, a consistent
  // snapshot for several queries (WAL readers never block the writer).
  enum Kind { kWrite, kRead };
  explicit Transaction(Connection& db, Kind kind = kWrite);
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  ~Transaction();
  void commit();

 private:
  Connection& db_;
  bool open_ = true;
};

}  // namespace knoblab::store::sqlite
