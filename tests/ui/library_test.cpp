// The knob library read from a real store, and fits and discrepancy runs
// done by the real knoblab command: results the CLI stores, read back as
// the screens show them; progress as it runs; a cancelled job stores
// nothing; a failing one says why.
#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>

#include <fstream>
#include <functional>

#include "job_runner.hpp"
#include "knob_library.hpp"
#include "knoblab/store/store.hpp"
#include "library_reader.hpp"
#include "event_loop.hpp"
#include "process.hpp"

namespace knoblab::ui {
namespace {

using test::run_knoblab;
using test::ScratchDir;

bool spin_until(const std::function<bool()>& done, int ms = 120000) { return test_loop::spin_until(done, ms); }

// A store with one simulated capture of moderate-detents (3 s).
class Library : public ::testing::Test {
 protected:
  void SetUp() override {
    db_ = (dir_ / "lab.sqlite").string();
    const auto r = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "3", "--db", db_});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  ScratchDir dir_;
  std::string db_;
};

TEST_F(Library, ACaptureWithoutResultsIsListedWithNoFitAndNoDiscrepancy) {
  const auto entries = read_library(db_);
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].capture_id, 1);
  EXPECT_EQ(entries[0].knob, "moderate-detents");
  EXPECT_EQ(entries[0].status, "complete");
  EXPECT_GT(entries[0].samples, 1000);
  const nlohmann::json j = entry_json(entries[0]);
  EXPECT_TRUE(j["fit"].is_null());
  EXPECT_TRUE(j["discrepancy"].is_null());
}

TEST_F(Library, TheLatestFitAndDiscrepancyOfACaptureAreShownWithTheirFigures) {
  ASSERT_EQ(run_knoblab({"fit", "--capture", "1", "--db", db_}).exit_code, 0);
  const auto again = run_knoblab({"fit", "--capture", "1", "--db", db_, "--json", (dir_ / "fit.json").string()});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  ASSERT_EQ(run_knoblab({"discrepancy", "--capture", "1", "--db", db_}).exit_code, 0);
  const auto entries = read_library(db_);
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].fit_id, 2);  // the later of the two
  EXPECT_EQ(entries[0].discrepancy_id, 1);
  const nlohmann::json j = entry_json(entries[0]);
  const nlohmann::json cli = nlohmann::json::parse(test::read_file(dir_ / "fit.json"));
  ASSERT_EQ(j["fit"]["params"].size(), cli["params"].size());
  for (const auto& p : j["fit"]["params"]) {
    const std::string name = p["name"];
    EXPECT_EQ(p["value"], cli["params"][name]) << name;
    EXPECT_EQ(p["ci95"], cli["ci95"][name]) << name;
  }
  EXPECT_TRUE(j["discrepancy"]["findings"].is_array());
  EXPECT_GT(j["discrepancy"]["base_heldout_rmse_Nm"].get<double>(), 0.0);
}

TEST(LibraryFile, AMissingStoreIsAnEmptyLibraryAndAnUnreadableOneSaysWhy) {
  ScratchDir dir;
  EXPECT_TRUE(read_library(dir / "none.sqlite").empty());
  std::ofstream(dir / "junk.sqlite") << "this is not a database, not even close to one. ";
  try {
    read_library(dir / "junk.sqlite");
    ADD_FAILURE() << "a junk file read as a library";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read the knob library"), std::string::npos) << e.what();
  }
}

TEST_F(Library, TheQmlLibraryReadsOffTheUiThreadAndSaysWhenDone) {
  KnobLibrary lib(QString::fromStdString(db_));
  lib.refresh();
  EXPECT_TRUE(lib.loading());
  ASSERT_TRUE(spin_until([&] { return !lib.loading(); }));
  ASSERT_EQ(lib.entries().size(), 1);
  EXPECT_EQ(lib.entry(1).value("knob").toString(), "moderate-detents");
  EXPECT_TRUE(lib.entry(7).isEmpty());
}

TEST_F(Library, AFitRunByTheUiIsTheCliFitStoredBesideTheCaptureWithItsStagesShown) {
  JobRunner jobs(KNOBLAB_CLI_PATH, QString::fromStdString(db_));
  QStringList stages;
  QObject::connect(&jobs, &JobRunner::progressChanged, [&] {
    if (!jobs.stage().isEmpty() && (stages.isEmpty() || stages.last() != jobs.stage())) stages << jobs.stage();
  });
  bool finished = false, ok = false;
  QVariantMap result;
  QObject::connect(&jobs, &JobRunner::finished,
                   [&](const QString& kind, qint64 id, bool good, const QVariantMap& r, const QString& error) {
                     finished = true, ok = good, result = r;
                     EXPECT_EQ(kind, "fit");
                     EXPECT_EQ(id, 1);
                     EXPECT_TRUE(error.isEmpty()) << error.toStdString();
                   });
  ASSERT_TRUE(jobs.fit(1));
  EXPECT_TRUE(jobs.running());
  EXPECT_FALSE(jobs.discrepancy(1)) << "one job at a time";
  ASSERT_TRUE(spin_until([&] { return finished; }));
  EXPECT_TRUE(ok);
  EXPECT_FALSE(jobs.running());
  EXPECT_TRUE(stages.contains("fitting")) << stages.join(" | ").toStdString();
  // What the job returned is what the store now holds.
  auto s = store::Store::open(db_);
  const auto fits = s.list_fits(1);
  ASSERT_EQ(fits.size(), 1u);
  const nlohmann::json stored = nlohmann::json::parse(fits[0].result);
  EXPECT_DOUBLE_EQ(result.value("params").toMap().value("A_pos").toDouble(), stored["params"]["A_pos"].get<double>());
}

TEST_F(Library, ACancelledDiscrepancyRunStoresNothing) {
  JobRunner jobs(KNOBLAB_CLI_PATH, QString::fromStdString(db_));
  bool finished = false, ok = true;
  QString why;
  QObject::connect(&jobs, &JobRunner::finished,
                   [&](const QString&, qint64, bool good, const QVariantMap&, const QString& error) {
                     finished = true, ok = good, why = error;
                   });
  ASSERT_TRUE(jobs.discrepancy(1));
  // Under way (its first stage reported), then cancelled.
  ASSERT_TRUE(spin_until([&] { return !jobs.stage().isEmpty() && jobs.stage() != "starting"; }));
  jobs.cancel();
  ASSERT_TRUE(spin_until([&] { return finished; }));
  EXPECT_FALSE(ok);
  EXPECT_EQ(why, "cancelled");
  auto s = store::Store::open(db_);
  EXPECT_TRUE(s.list_discrepancies(1).empty());
}

TEST_F(Library, AJobOnACaptureThatIsNotThereSaysWhatTheCliSaid) {
  JobRunner jobs(KNOBLAB_CLI_PATH, QString::fromStdString(db_));
  QString why, said;
  bool finished = false;
  QObject::connect(&jobs, &JobRunner::finished,
                   [&](const QString&, qint64, bool, const QVariantMap&, const QString& error) { finished = true, why = error; });
  QObject::connect(&jobs, &JobRunner::message, [&](const QString& text, const QString&) { said = text; });
  ASSERT_TRUE(jobs.fit(42));
  ASSERT_TRUE(spin_until([&] { return finished; }));
  EXPECT_NE(why.indexOf("42"), -1) << why.toStdString();
  EXPECT_TRUE(said.startsWith("fit of capture 42 failed: ")) << said.toStdString();
}

}  // namespace
}  // namespace knoblab::ui
