// The shipped unit puts only the loop thread on the isolated CPU: the
// process's CPUAffinity (inherited by the writer, control and Modbus
// threads) must leave out the CPU the loop pins itself to with --cpu.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace {

std::string unit_text() {
  std::ifstream f(KNOBLAB_HAPTICD_UNIT);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// "0 2-3" → {0, 2, 3}
std::set<int> cpu_list(const std::string& text) {
  std::set<int> cpus;
  std::istringstream in(text);
  std::string item;
  while (in >> item) {
    for (std::size_t at = 0; at <= item.size();) {
      const std::size_t comma = item.find(',', at);
      const std::string part = item.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
      if (!part.empty()) {
        const std::size_t dash = part.find('-');
        const int lo = std::stoi(part.substr(0, dash));
        const int hi = dash == std::string::npos ? lo : std::stoi(part.substr(dash + 1));
        for (int c = lo; c <= hi; ++c) cpus.insert(c);
      }
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
  }
  return cpus;
}

TEST(HapticdUnit, OnlyTheLoopThreadRunsOnTheIsolatedCpu) {
  const std::string unit = unit_text();
  ASSERT_FALSE(unit.empty());
  std::smatch m;
  // ExecStart continues over backslash-newlines; the loop's CPU is its --cpu.
  const std::string joined = std::regex_replace(unit, std::regex("\\\\\n"), " ");
  ASSERT_TRUE(std::regex_search(joined, m, std::regex("ExecStart=[^\n]*--cpu[ =]([0-9]+)")));
  const int loop_cpu = std::stoi(m[1]);
  ASSERT_TRUE(std::regex_search(unit, m, std::regex("\nCPUAffinity=([^\n]*)")))
      << "without CPUAffinity the other threads may land on the loop's CPU too";
  const std::set<int> process_cpus = cpu_list(m[1]);
  EXPECT_FALSE(process_cpus.empty());
  EXPECT_EQ(process_cpus.count(loop_cpu), 0u) << "CPUAffinity puts every thread on the loop's CPU " << loop_cpu;
}

}  // namespace
