// Shared by the store tests: temp dirs, deterministic samples, a checksum of
// the whole database, a forked child's guard and pipe, StoreError messages.
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "knoblab/interchange/capture.hpp"
#include "knoblab/store/sqlite.hpp"
#include "knoblab/store/store.hpp"
#include "knoblab/store/types.hpp"

namespace knoblab::store::test {

// A fresh directory per test, removed afterwards (ctest runs tests in parallel).
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("knoblab_store_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" +
             info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Kills and reaps a forked child if the test bails out early.
struct Child {
  pid_t pid = -1;
  ~Child() {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
};

// Reads one int64 a child wrote to a pipe; false once the pipe is closed.
inline bool read_int64(int fd, std::int64_t& n) {
  std::size_t got = 0;
  auto* p = reinterpret_cast<char*>(&n);
  while (got < sizeof n) {
    const ssize_t r = ::read(fd, p + got, sizeof n - got);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    got += static_cast<std::size_t>(r);
  }
  return true;
}

// The message of the StoreError f throws (a test failure if it throws none).
template <typename F>
std::string store_error(F&& f) {
  try {
    f();
  } catch (const StoreError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no StoreError";
  return {};
}

// Sample idx of a synthetic capture: every value recomputable from idx alone.
inline Sample sample_at(std::int64_t idx) {
  const double i = static_cast<double>(idx);
  // (No -0.0 anywhere: sqlite cannot keep its sign.)
  return {i * 1e-4, std::sin(i * 1e-3), 0.25 + i * 0.5, -0.5 - i * 1e-3, 1.0 / (i + 1.0),
          static_cast<double>(idx % 7) - 3.0};
}

// n samples of sample_at as an interchange capture (command column or not).
inline interchange::Capture synthetic_capture(std::size_t n, bool command = true) {
  interchange::Capture c;
  c.has_command = command;
  for (std::size_t i = 0; i < n; ++i) {
    const Sample s = sample_at(static_cast<std::int64_t>(i));
    c.t.push_back(s.t);
    c.theta.push_back(s.theta);
    c.omega.push_back(s.omega);
    c.alpha.push_back(s.alpha);
    c.torque.push_back(s.torque);
    if (command) c.command.push_back(s.command);
  }
  return c;
}

// Row counts and a hash of every value of every table (and the schema).
inline std::string checksum(sqlite::Connection& db) {
  std::string out;
  auto tables = db.prepare("SELECT name FROM sqlite_schema WHERE type = 'table' ORDER BY name");
  std::size_t hash = std::hash<std::string>{}(db.query_text(
      "SELECT group_concat(sql, ';') FROM (SELECT sql FROM sqlite_schema ORDER BY name)"));
  while (tables.step()) {
    const std::string name = tables.column_text(0);
    auto rows = db.prepare("SELECT * FROM \"" + name + "\" ORDER BY 1, 2");
    std::size_t count = 0;
    while (rows.step()) {
      ++count;
      for (int c = 0; c < rows.column_count(); ++c)
        hash = hash * 1000003u ^
               std::hash<std::string>{}(rows.is_null(c) ? "\x01NULL" : rows.column_text(c));
    }
    out += name + "=" + std::to_string(count) + " ";
  }
  return out + "hash=" + std::to_string(hash);
}

}  // namespace knoblab::store::test
