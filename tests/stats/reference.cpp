#include "reference.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <format>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace knoblab::stats::test {
namespace {

namespace fs = std::filesystem;

std::string shell_quote(const std::string& s) {
  std::string quoted = "'";
  for (const char c : s) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// A file per test and process, so parallel ctest runs (and two build trees)
// never share one.
fs::path write_csv(const Table& data) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  static int count = 0;
  const fs::path path = fs::path(::testing::TempDir()) /
                        std::format("knoblab-stats-{}.{}-{}-{}.csv", info->test_suite_name(),
                                    info->name(), getpid(), count++);
  std::ofstream out(path);
  for (const auto& row : data) {
    for (std::size_t j = 0; j < row.size(); ++j) out << (j ? "," : "") << std::format("{}", row[j]);
    out << "\n";
  }
  if (!out) throw std::runtime_error("cannot write " + path.string());
  return path;
}

Values run(const std::string& interpreter, const std::string& script, const std::string& args,
           const Table& data) {
  if (interpreter.empty() || interpreter.ends_with("-NOTFOUND"))
    throw std::runtime_error("the reference interpreter for " + script +
                             " was not found when the tests were configured; the cross-check "
                             "cannot run (it is in scripts/sysroot/packages.txt)");
  const fs::path csv = write_csv(data);
  const std::string command = shell_quote(interpreter) + " " +
                              shell_quote((fs::path(KNOBLAB_STATS_REFERENCE_DIR) / script).string()) +
                              " " + args + " " + shell_quote(csv.string());
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + command);
  std::string output;
  char buffer[4096];
  while (const std::size_t got = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, got);
  const int status = pclose(pipe);
  fs::remove(csv);
  if (status != 0) throw std::runtime_error(command + " failed (status " + std::to_string(status) + ")");

  Values values;
  std::istringstream lines(output);
  std::string name, value;
  while (lines >> name >> value) values[name] = std::stod(value);  // stod reads "inf", "nan" too
  if (values.empty()) throw std::runtime_error(command + " printed no values");
  return values;
}

}  // namespace

Values scipy_reference(const std::string& check, const Table& data) {
  return run(KNOBLAB_PYTHON3, "scipy_reference.py", shell_quote(check), data);
}

Values r_rm_anova_reference(const Table& data) {
  return run(KNOBLAB_RSCRIPT, "rm_anova_reference.R", "", data);
}

Table columns(const std::vector<double>& x, const std::vector<double>& y) {
  Table rows;
  for (std::size_t i = 0; i < x.size(); ++i) rows.push_back({x[i], y.at(i)});
  return rows;
}

void expect_relative(double actual, const Values& reference, const std::string& name, double relative) {
  const auto it = reference.find(name);
  ASSERT_NE(it, reference.end()) << "the reference printed no " << name;
  const double expected = it->second;
  const double tolerance = relative * (expected == 0 ? 1.0 : std::abs(expected));
  EXPECT_NEAR(actual, expected, tolerance) << name << std::format(": ours {:.17g}, reference {:.17g}", actual, expected);
}

}  // namespace knoblab::stats::test
