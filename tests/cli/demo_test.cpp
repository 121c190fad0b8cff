// knoblab demo end to end: the five thesis knobs captured, fitted, and
// discrepancy discovery on each: four with nothing missing, the
// non-sine knob with its detent shape and its backlash named.
#include <gtest/gtest.h>

#include <string>

#include "process.hpp"

namespace knoblab::test {
namespace {

// The demo's block for one knob in "What Eq. 6 leaves out": from its name
// to the next knob's line (two-space indent) or the blank line after.
std::string block(const std::string& out, const std::string& knob) {
  const std::size_t head = out.find("What Eq. 6 leaves out");
  const std::size_t at = out.find("\n  " + knob + " (capture", head);
  if (head == std::string::npos || at == std::string::npos) return {};
  std::size_t end = at + 1;
  while (true) {
    end = out.find('\n', end);
    if (end == std::string::npos || out.compare(end, 5, "\n    ") != 0) break;
    ++end;
  }
  return out.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
}

TEST(Demo, NamesWhatEachThesisKnobLacks) {
  ScratchDir dir;
  const RunResult r = run_knoblab({"demo", "--db", (dir / "demo.sqlite").string()});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  for (const char* knob : {"high-friction", "high-inertia", "subtle-detents", "moderate-detents"}) {
    const std::string b = block(r.out, knob);
    EXPECT_NE(b.find("nothing missing"), std::string::npos) << knob << "\n" << r.out;
  }
  const std::string ns = block(r.out, "non-sine-detents");
  EXPECT_NE(ns.find("detent_shape —"), std::string::npos) << r.out;
  EXPECT_NE(ns.find("backlash —"), std::string::npos) << r.out;
  EXPECT_EQ(ns.find("drift —"), std::string::npos) << r.out;  // nothing it does not have
}

}  // namespace
}  // namespace knoblab::test
