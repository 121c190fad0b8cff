// pointing_reference.R, the pointing report computed independently in base
// R, run at test time on a tidy CSV the test wrote (as tests/stats runs its
// R and scipy references: a missing Rscript fails the test, it is never a
// skip; files are named per test and process so parallel runs and two build
// trees never share one).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <format>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/study/tidy.hpp"

namespace knoblab::study::test {

inline std::string shell_quote(const std::string& s) {
  std::string quoted = "'";
  for (const char c : s) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// A path in the test's temporary directory, unique to this test and process.
inline std::filesystem::path temp_path(const std::string& suffix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  static int count = 0;
  return std::filesystem::path(::testing::TempDir()) /
         std::format("knoblab-study-{}.{}-{}-{}{}", info->test_suite_name(), info->name(), getpid(), count++, suffix);
}

// Writes `rows` with write_pointing_csv, runs the R reference on them (with
// the level order when given) and returns its JSON.
inline nlohmann::json r_pointing_reference(const std::vector<PointingRow>& rows,
                                           const std::vector<std::string>& level_order = {}) {
  const std::string rscript = KNOBLAB_STUDY_RSCRIPT;
  if (rscript.empty() || rscript.ends_with("-NOTFOUND"))
    throw std::runtime_error("Rscript was not found when the tests were configured; the cross-check cannot run "
                             "(r-base-core is in scripts/sysroot/packages.txt)");
  const std::filesystem::path csv = temp_path(".csv"), json = temp_path(".json");
  {
    std::ofstream out(csv);
    write_pointing_csv(out, rows);
    if (!out) throw std::runtime_error("cannot write " + csv.string());
  }
  std::string levels;
  for (const std::string& l : level_order) levels += (levels.empty() ? "" : ",") + l;
  const std::string command = shell_quote(rscript) + " " + shell_quote(KNOBLAB_STUDY_POINTING_REFERENCE) + " " +
                              shell_quote(csv.string()) + " " + shell_quote(json.string()) +
                              (levels.empty() ? "" : " " + shell_quote(levels)) + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run " + command);
  std::string output;
  std::array<char, 4096> buffer{};
  while (const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), pipe)) output.append(buffer.data(), got);
  const int status = pclose(pipe);
  std::filesystem::remove(csv);
  if (status != 0) throw std::runtime_error(command + " failed (status " + std::to_string(status) + "):\n" + output);
  std::ifstream in(json);
  const nlohmann::json result = nlohmann::json::parse(in);
  in.close();
  std::filesystem::remove(json);
  return result;
}

using json = nlohmann::json;

inline constexpr double kRelative = 1e-6;

// Every key and value of `ours` (but its notes, sentences for people) is in
// `ref` with the same value, numbers to kRelative, and `ref` has nothing
// more; returns how many numbers were compared.
inline std::size_t expect_same(const json& ours, const json& ref, const std::string& path) {
  std::size_t numbers = 0;
  if (ours.is_object()) {
    if (!ref.is_object()) {
      ADD_FAILURE() << path << ": R gives " << ref.dump() << ", not an object";
      return 0;
    }
    for (const auto& [key, value] : ours.items()) {
      if (key == "notes") continue;
      if (!ref.contains(key)) {
        ADD_FAILURE() << path << "." << key << ": not in R's report";
        continue;
      }
      numbers += expect_same(value, ref.at(key), path + "." + key);
    }
    for (const auto& [key, value] : ref.items())
      if (!ours.contains(key)) ADD_FAILURE() << path << "." << key << ": only in R's report, " << value.dump();
  } else if (ours.is_array()) {
    if (!ref.is_array() || ref.size() != ours.size()) {
      ADD_FAILURE() << path << ": " << ours.size() << " items, R gives " << ref.dump();
      return 0;
    }
    for (std::size_t i = 0; i < ours.size(); ++i)
      numbers += expect_same(ours[i], ref[i], std::format("{}[{}]", path, i));
  } else if (ours.is_number()) {
    if (!ref.is_number()) {
      ADD_FAILURE() << path << ": ours " << ours.dump() << ", R gives " << ref.dump();
      return 0;
    }
    const double a = ours.get<double>(), b = ref.get<double>();
    const double tolerance = b == 0 ? 1e-12 : kRelative * std::abs(b);
    EXPECT_LE(std::abs(a - b), tolerance) << path << std::format(": ours {:.17g}, R {:.17g}", a, b);
    ++numbers;
  } else {
    EXPECT_EQ(ours, ref) << path;
  }
  return numbers;
}

}  // namespace knoblab::study::test
