// knoblab demo end to end: the five thesis knobs captured, fitted, and
// discrepancy discovery on each: four with nothing missing, the
// non-sine knob with its detent shape and its backlash named.
#include <gtest/gtest.h>

#include <sstream>
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

// One parameter row of a knob's table: "  NAME  fitted  [lo, hi]  true! t7 t7".
std::string param_row(const std::string& out, const std::string& knob, const std::string& label) {
  const std::size_t at = out.find("\n" + knob + ": capture");
  const std::size_t row = out.find("\n  " + label, at);
  if (at == std::string::npos || row == std::string::npos) return {};
  return out.substr(row + 1, out.find('\n', row + 1) - row - 1);
}

TEST(Demo, ShowsFittedAndTrueValuesInOneSignConventionAndFlagsTruthOutsideTheInterval) {
  ScratchDir dir;
  const RunResult r = run_knoblab({"demo", "--db", (dir / "demo.sqlite").string()});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // The simulated moderate knob is A = −11 mN·m, S = −0.19 rad: the same detents
  // as the fit's A = 11, S = −0.19 + π.
  const std::string a = param_row(r.out, "moderate-detents", "A_pos");
  const std::string s = param_row(r.out, "moderate-detents", "S_pos");
  const auto truth_cell = [](const std::string& row) {
    std::istringstream after(row.substr(row.find(']') + 1));
    std::string cell;
    after >> cell;
    return cell;
  };
  EXPECT_EQ(truth_cell(a), "11") << a;
  EXPECT_EQ(truth_cell(s).substr(0, 4), "2.95") << s;
  EXPECT_NE(s.find("2.95"), s.rfind("2.95")) << s;  // fitted and true alike
  EXPECT_NE(r.out.find("one sign convention"), std::string::npos);
  // Every row whose truth lies outside its interval carries the mark, and the
  // knob's table says what it means.
  std::size_t marks = 0;
  for (std::size_t at = r.out.find("! "); at != std::string::npos; at = r.out.find("! ", at + 1)) ++marks;
  EXPECT_GE(marks, 2u) << r.out;
  EXPECT_NE(r.out.find("the true value lies outside the 95% CI"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace knoblab::test
