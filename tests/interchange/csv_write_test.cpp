// Writing: exact round trip, refusal of unwritable captures, atomic replace.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "knoblab/interchange/csv.hpp"

namespace ki = knoblab::interchange;
namespace fs = std::filesystem;
using ::testing::HasSubstr;

namespace {

// A double from random bits within the format's ±1e12: every exponent up to
// that and every mantissa gets a turn.
double random_finite(std::mt19937_64& rng) {
  for (;;) {
    const double d = std::bit_cast<double>(rng());
    if (std::isfinite(d) && std::abs(d) <= ki::kMaxMagnitude) return d;
  }
}

ki::Capture random_capture(std::size_t n, bool command) {
  std::mt19937_64 rng(42);
  ki::Capture c;
  c.metadata = {{"knob", "fan: 51 mm"}, {"", "free comment"}, {"calibration", "{\"C_cal\":1.5}"}};
  c.has_command = command;
  double t = -1e-3;
  for (std::size_t i = 0; i < n; ++i) {
    t = std::nextafter(t, 1.0) + static_cast<double>(rng() % 1000) * 1e-7;  // strictly increasing
    c.t.push_back(t);
    c.theta.push_back(random_finite(rng));
    c.omega.push_back(random_finite(rng));
    c.alpha.push_back(random_finite(rng));
    c.torque.push_back(random_finite(rng));
    if (command) c.command.push_back(random_finite(rng));
  }
  // Edge values that shortest-form printing must still get exactly right.
  const double edges[] = {-0.0, 0.0, std::numeric_limits<double>::denorm_min(),
                          -std::numeric_limits<double>::denorm_min(),
                          std::numeric_limits<double>::min(), ki::kMaxMagnitude,
                          -std::nextafter(ki::kMaxMagnitude, 0.0), 0.1, 1.0 / 3.0};
  for (std::size_t k = 0; k < std::size(edges) && k < n; ++k) c.torque[k] = edges[k];
  return c;
}

void expect_bitwise_equal(const std::vector<double>& a, const std::vector<double>& b,
                          const char* name) {
  ASSERT_EQ(a.size(), b.size()) << name;
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i]))
        << name << "[" << i << "] " << a[i] << " vs " << b[i];
}

fs::path temp_dir() {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = fs::temp_directory_path() /
                   ("knoblab_write_" + std::to_string(::getpid()) + "_" + test->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(CsvWrite, RoundTripIsBitwiseIdentical) {
  for (bool command : {false, true}) {
    const auto c = random_capture(5000, command);
    std::stringstream ss;
    ki::write_csv(c, ss);
    const auto r = ki::parse_csv(ss, "mem");
    EXPECT_EQ(r.metadata, c.metadata);
    EXPECT_EQ(r.has_command, command);
    EXPECT_FALSE(r.omega_derived);
    EXPECT_FALSE(r.alpha_derived);
    expect_bitwise_equal(r.t, c.t, "t");
    expect_bitwise_equal(r.theta, c.theta, "theta");
    expect_bitwise_equal(r.omega, c.omega, "omega");
    expect_bitwise_equal(r.alpha, c.alpha, "alpha");
    expect_bitwise_equal(r.torque, c.torque, "torque");
    expect_bitwise_equal(r.command, c.command, "command");
  }
}

TEST(CsvWrite, ExactTextFormat) {
  ki::Capture c;
  c.metadata = {{"knob", "A"}, {"", "note"}};
  c.t = {0, 0.0001, 0.0002};
  c.theta = {0.5, -0.25, 1e-20};
  c.omega = {1, 2, 3};
  c.alpha = {0, 0, 0};
  c.torque = {0.1, 0.2, 0.3};
  std::ostringstream out;
  ki::write_csv(c, out);
  EXPECT_EQ(out.str(),
            "# knob: A\n# note\nt,theta,omega,alpha,torque\n"
            "0,0.5,1,0,0.1\n1e-04,-0.25,2,0,0.2\n2e-04,1e-20,3,0,0.3\n");
}

TEST(CsvWrite, RefusesWhatTheReaderWouldReject) {
  const auto good = random_capture(10, false);
  auto c = good;
  c.torque.pop_back();
  EXPECT_THROW({ std::ostringstream o; ki::write_csv(c, o); }, std::invalid_argument);
  c = good;
  c.theta[3] = std::nan("");
  EXPECT_THROW({ std::ostringstream o; ki::write_csv(c, o); }, std::invalid_argument);
  c = good;
  c.t[5] = c.t[4];
  EXPECT_THROW({ std::ostringstream o; ki::write_csv(c, o); }, std::invalid_argument);
  c = good;
  c.has_command = true;  // but no command values
  EXPECT_THROW({ std::ostringstream o; ki::write_csv(c, o); }, std::invalid_argument);
  c = random_capture(2, false);
  EXPECT_THROW({ std::ostringstream o; ki::write_csv(c, o); }, std::invalid_argument);
  for (auto meta : {std::pair<std::string, std::string>{"a", "two\nlines"},
                    {"a:b", "c"},
                    {"", "x: y"},
                    {"nul", std::string(1, '\0')}}) {
    c = good;
    c.metadata = {meta};
    EXPECT_THROW({ std::ostringstream o; ki::write_csv(c, o); }, std::invalid_argument)
        << meta.first;
  }
}

TEST(CsvWrite, ToPathReplacesAtomicallyAndLeavesNoTempFiles) {
  const auto dir = temp_dir();
  const auto path = dir / "k.csv";
  const auto c = random_capture(1000, true);
  ki::write_csv(c, path);
  const auto r = ki::read_csv(path);
  expect_bitwise_equal(r.theta, c.theta, "theta");

  // Overwrite with a different capture.
  auto c2 = random_capture(10, false);
  ki::write_csv(c2, path);
  EXPECT_EQ(ki::read_csv(path).size(), 10u);

  // A refused capture leaves the old file untouched and no temp file behind.
  auto bad = c2;
  bad.omega[1] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ki::write_csv(bad, path), std::invalid_argument);
  EXPECT_EQ(ki::read_csv(path).size(), 10u);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);
  fs::remove_all(dir);
}

TEST(CsvWrite, ToUnwritablePathThrowsSystemError) {
  const auto c = random_capture(10, false);
  EXPECT_THROW(ki::write_csv(c, fs::path("/nonexistent/dir/k.csv")), std::system_error);
}
