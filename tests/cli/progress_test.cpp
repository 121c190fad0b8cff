// The progress line: what Progress draws and erases, and that the real
// knoblab draws it on a terminal, never into a pipe, and not with --quiet.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "knoblab/store/store.hpp"
#include "process.hpp"
#include "progress.hpp"
#include "terminal.hpp"

namespace knoblab::test {
namespace {

// What a Progress wrote to its FILE.
class Drawn {
 public:
  Drawn() : file_(std::tmpfile()) {}
  ~Drawn() { std::fclose(file_); }
  std::FILE* file() const { return file_; }
  std::string text() const {
    std::fflush(file_);
    std::string out;
    std::rewind(file_);
    for (int c; (c = std::fgetc(file_)) != EOF;) out += static_cast<char>(c);
    return out;
  }

 private:
  std::FILE* file_;
};

TEST(ProgressLine, RedrawsOneLineInPlaceAndErasesIt) {
  Drawn d;
  {
    cli::Progress p("fit", true, d.file());
    p.show("fitting");
    p.show("fitting");  // unchanged: not drawn again
    p.show("trying candidates, round 1", 3, 15);
    p.show("importing", 1500, 300000);  // a large count as a percentage
    p.show("importing", 1700, 300000);  // under a percent more: not drawn again
    p.clear();
    p.clear();  // nothing left to erase
    p.show("intervals");
  }  // erased at the end
  EXPECT_EQ(d.text(),
            "\rknoblab fit: fitting\033[K"
            "\rknoblab fit: trying candidates, round 1: 3 of 15\033[K"
            "\rknoblab fit: importing: 0 %\033[K"
            "\r\033[K"
            "\rknoblab fit: intervals\033[K"
            "\r\033[K");
}

TEST(ProgressLine, DrawsNothingWhenNotEnabled) {
  Drawn d;
  {
    cli::Progress p("fit", false, d.file());
    p.show("fitting");
    p.show("candidates", 1, 2);
    p.clear();
  }
  EXPECT_EQ(d.text(), "");
}

TEST(ProgressLine, AsJsonEachStepIsOneLineThatAProgramCanRead) {
  Drawn d;
  {
    cli::Progress p("discrepancy", true, d.file(), cli::Progress::Style::json);
    p.show("fitting the base");
    p.show("fitting the base");  // unchanged: not repeated
    p.show("trying candidates, round 1", 3, 15);
    p.clear();  // lines are not erased
  }
  EXPECT_EQ(d.text(),
            "{\"progress\":{\"command\":\"discrepancy\",\"done\":0,\"stage\":\"fitting the base\",\"total\":0}}\n"
            "{\"progress\":{\"command\":\"discrepancy\",\"done\":3,\"stage\":\"trying candidates, round 1\","
            "\"total\":15}}\n");
}

class ProgressCli : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = (dir_ / "k.db").string();
    const RunResult r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "3", "--db", db_});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  ScratchDir dir_;
  std::string db_;
};

TEST_F(ProgressCli, AFitOnATerminalShowsItsStagesAndErasesTheLineBeforeItsResults) {
  TerminalRun run({"fit", "--capture", "1", "--db", db_});
  ASSERT_EQ(run.finish(), 0) << run.output();
  const std::string& out = run.output();
  for (const char* stage : {"reading the input", "preparing", "searching detents", "fitting", "intervals"})
    EXPECT_NE(out.find(std::string("\rknoblab fit: ") + stage + "\033[K"), std::string::npos) << stage << ": " << out;
  // Erased, then the results on a clean line.
  EXPECT_NE(out.find("\r\033[Kcapture 1 (moderate-detents)"), std::string::npos) << out;
  EXPECT_EQ(out.find("knoblab fit: ", out.find("capture 1 (moderate-detents)")), std::string::npos) << out;
}

TEST_F(ProgressCli, QuietOrAPipeShowsNoProgressLine) {
  TerminalRun quiet({"fit", "--capture", "1", "--db", db_, "--quiet"});
  ASSERT_EQ(quiet.finish(), 0) << quiet.output();
  EXPECT_EQ(quiet.output().find("knoblab fit: "), std::string::npos) << quiet.output();
  EXPECT_EQ(quiet.output().find('\033'), std::string::npos) << quiet.output();
  EXPECT_NE(quiet.output().find("stored as fit 1"), std::string::npos) << quiet.output();

  const RunResult piped = run_knoblab({"fit", "--capture", "1", "--db", db_});
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_EQ(piped.err, "");
  EXPECT_EQ(piped.out.find('\r'), std::string::npos);
}

TEST_F(ProgressCli, WithKnoblabProgressJsonAPipeGetsTheStagesAsJsonLines) {
  ::setenv("KNOBLAB_PROGRESS", "json", 1);
  const RunResult piped = run_knoblab({"fit", "--capture", "1", "--db", db_});
  ::unsetenv("KNOBLAB_PROGRESS");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_NE(piped.err.find("{\"progress\":{\"command\":\"fit\",\"done\":0,\"stage\":\"fitting\""), std::string::npos)
      << piped.err;
  EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
  EXPECT_NE(piped.out.find("stored as fit 1"), std::string::npos) << piped.out;
}

}  // namespace
}  // namespace knoblab::test
