// A participant's withdrawal from a study: their session, trials, notes and
// their trials' captures (samples, biometrics, fits) go in one transaction;
// every other row stays exactly as it was, also the same code's session of
// another study; refusals delete nothing; the deleted bytes do not linger in
// the file.
#include <gmock/gmock.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::checksum;
using ks::test::store_error;
using ks::test::TempDir;
using ::testing::HasSubstr;

namespace {

constexpr std::size_t kPlan = 4;

ks::NewStudySession new_session(const std::string& study, const std::string& participant, std::size_t index) {
  ks::NewStudySession s;
  s.study = study;
  s.participant = participant;
  s.participant_index = index;
  s.protocol_json = R"({"study": ")" + study + R"(", "kind": "pointing"})";
  s.plan_trials = kPlan;
  return s;
}

// A finished capture of n samples with n / 10 biometric samples beside it.
std::int64_t recorded_capture(ks::Store& store, int n) {
  ks::NewCapture info;
  info.knob = "fan";
  info.rate_hz = 1000;
  info.source = "hapticd";
  auto w = store.begin_capture(info);
  for (int i = 0; i < n; ++i) w.append(ks::test::sample_at(i));
  w.finish();
  std::vector<ks::BiometricSample> bio;
  for (int i = 0; i < n / 10; ++i)
    bio.push_back({i, i / 32.0, 1e-6 * i, 2e-6 * i, 5e-6 + 1e-9 * i});
  store.append_biometrics(w.capture_id(), bio);
  return w.capture_id();
}

ks::StudyTrial trial(std::int64_t session, std::size_t index, std::optional<std::int64_t> capture,
                     const std::string& marker) {
  ks::StudyTrial t;
  t.session_id = session;
  t.trial_index = index;
  t.block = 1;
  t.stage = "all";
  t.repetition = 1;
  t.condition_json = R"({"knob":"A"})";
  t.started_unix = 1.7e9 + static_cast<double>(index) * 10.0 + 0.125;
  t.ended_unix = t.started_unix + 9.5;
  t.result_json = R"({"mt_s":)" + std::to_string(0.5 + static_cast<double>(index) / 64) + "}";
  t.trace_json = R"([{"t":0,"marker":")" + marker + R"("}])";
  t.capture_id = capture;
  return t;
}

struct Participant {
  std::int64_t session = 0;
  std::vector<std::int64_t> captures;
};

// Every trial of the plan with a capture of its own (the last trial without
// one: hapticd was not recording), two notes, a fit on the first capture;
// `finish` closes the session.
Participant run_participant(ks::Store& store, const std::string& study, const std::string& code, std::size_t index,
                            bool finish) {
  Participant p;
  p.session = store.open_study_session(new_session(study, code, index)).session_id;
  for (std::size_t i = 1; i <= kPlan; ++i) {
    std::optional<std::int64_t> capture;
    if (i < kPlan) {
      capture = recorded_capture(store, 100 + static_cast<int>(i));
      p.captures.push_back(*capture);
    }
    store.commit_study_trial(trial(p.session, i, capture, code + "-trace-" + study));
  }
  for (std::size_t i = 1; i <= 2; ++i) {
    ks::StudyNote n;
    n.session_id = p.session;
    if (i == 2) n.trial_index = 1;
    n.text = code + "-said-" + study + "-" + std::to_string(i);
    store.add_study_note(n);
  }
  const ks::FitFile file{"fit.json", {'{', '}'}};
  store.insert_fit(p.captures.front(), "kpd", R"({"k":1})", "{}", std::span(&file, 1));
  if (finish) store.finish_study_session(p.session);
  return p;
}

std::string id_list(const std::vector<std::int64_t>& ids) {
  std::string s;
  for (const auto id : ids) s += (s.empty() ? "" : ",") + std::to_string(id);
  return "(" + s + ")";
}

// Every row of `table` matching `where`, each value exactly: its type, and a
// REAL's bits, a TEXT's or BLOB's bytes. Sorted, so two snapshots compare as sets.
std::vector<std::string> rows(ks::sqlite::Connection& db, const std::string& table, const std::string& where) {
  std::vector<std::string> columns;
  auto info = db.prepare("SELECT name FROM pragma_table_info(?1) ORDER BY cid");
  info.bind_text(1, table);
  while (info.step()) columns.push_back(info.column_text(0));
  std::string select;
  for (const auto& c : columns) select += (select.empty() ? "" : ", ") + ("typeof(\"" + c + "\"), \"" + c + "\"");
  auto st = db.prepare("SELECT " + select + " FROM \"" + table + "\" WHERE " + where);
  std::vector<std::string> out;
  while (st.step()) {
    std::string row;
    for (int c = 0; c + 1 < st.column_count(); c += 2) {
      const std::string type = st.column_text(c);
      row += type + ":";
      if (type == "real")
        row += std::to_string(std::bit_cast<std::uint64_t>(st.column_double(c + 1)));
      else if (type == "integer")
        row += std::to_string(st.column_int(c + 1));
      else if (type != "null") {
        const auto bytes = st.column_blob(c + 1);
        row.append(bytes.begin(), bytes.end());
      }
      row += "|";
    }
    out.push_back(std::move(row));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Every table's rows but those `gone` selects (a table it does not name: all
// of them), by table name.
std::map<std::string, std::vector<std::string>> database_without(ks::sqlite::Connection& db,
                                                                 const std::map<std::string, std::string>& gone) {
  std::map<std::string, std::vector<std::string>> out;
  auto tables = db.prepare("SELECT name FROM sqlite_schema WHERE type = 'table' AND name NOT LIKE 'sqlite_%'");
  while (tables.step()) {
    const std::string name = tables.column_text(0);
    const auto g = gone.find(name);
    out[name] = rows(db, name, g == gone.end() ? "1" : "NOT (" + g->second + ")");
  }
  return out;
}

// The rows a withdrawn participant's session and captures own.
std::map<std::string, std::string> owned_by(const Participant& p) {
  const std::string session = "session_id = " + std::to_string(p.session);
  const std::string captures = "capture_id IN " + id_list(p.captures);
  return {{"study_sessions", session},
          {"study_trials", session},
          {"study_notes", session},
          {"captures", "id IN " + id_list(p.captures)},
          {"samples", captures},
          {"biometrics", captures},
          {"fits", captures},
          {"fit_files", "fit_id IN (SELECT id FROM fits WHERE " + captures + ")"}};
}

std::int64_t count(ks::Store& store, const std::string& sql) { return store.connection().query_int(sql); }

void expect_clean(ks::Store& store) {
  EXPECT_EQ(store.integrity_check(), "ok");
  EXPECT_FALSE(store.connection().prepare("PRAGMA foreign_key_check").step()) << "a dangling reference";
}

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(StoreStudyWithdraw, WithdrawingAParticipantDeletesAllTheirRowsAndLeavesEveryOtherRowByteIdentical) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  // P01's finished session is withdrawn: the triggers that keep a finished
  // session closed must not stand in the way.
  const Participant gone = run_participant(store, "pointing-1", "P01", 0, true);
  const Participant kept = run_participant(store, "pointing-1", "P02", 1, false);
  const Participant same_code_elsewhere = run_participant(store, "textures-1", "P01", 0, true);
  const auto expected = database_without(store.connection(), owned_by(gone));
  const std::int64_t gone_samples = count(store, "SELECT count(*) FROM samples WHERE capture_id IN " + id_list(gone.captures));
  ASSERT_GT(gone_samples, 0);

  const ks::StudyWithdrawal w = store.withdraw_study_participant("pointing-1", "P01");

  EXPECT_EQ(w.sessions, 1u);
  EXPECT_EQ(w.trials, kPlan);
  EXPECT_EQ(w.notes, 2u);
  EXPECT_EQ(w.captures, kPlan - 1);
  EXPECT_EQ(w.samples, gone_samples);
  EXPECT_EQ(w.shared_captures, 0u);
  EXPECT_EQ(database_without(store.connection(), {}), expected);
  EXPECT_FALSE(store.study_session(gone.session));
  for (const auto id : gone.captures) {
    EXPECT_FALSE(store.capture_info(id)) << "capture " << id;
    EXPECT_TRUE(store.load_biometrics(id).empty()) << "capture " << id;
  }
  EXPECT_EQ(count(store, "SELECT count(*) FROM samples WHERE capture_id IN " + id_list(gone.captures)), 0);
  EXPECT_EQ(store.study_trials(kept.session).size(), kPlan);
  EXPECT_EQ(store.study_sessions("textures-1").size(), 1u);
  EXPECT_EQ(store.study_trials(same_code_elsewhere.session).size(), kPlan);
  expect_clean(store);
}

TEST(StoreStudyWithdraw, ThePreviewCountsWhatTheWithdrawalDeletesAndChangesNothing) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  run_participant(store, "pointing-1", "P01", 0, false);
  run_participant(store, "pointing-1", "P02", 1, true);
  const std::string before = checksum(store.connection());

  const ks::StudyWithdrawal preview = store.study_withdrawal("pointing-1", "P02");

  EXPECT_EQ(checksum(store.connection()), before);
  const ks::StudyWithdrawal done = store.withdraw_study_participant("pointing-1", "P02");
  EXPECT_EQ(preview.sessions, done.sessions);
  EXPECT_EQ(preview.trials, done.trials);
  EXPECT_EQ(preview.notes, done.notes);
  EXPECT_EQ(preview.captures, done.captures);
  EXPECT_EQ(preview.samples, done.samples);
  EXPECT_EQ(done.trials, kPlan);
}

TEST(StoreStudyWithdraw, AnUnknownParticipantOrStudyIsRefusedNamingItAndNothingChanges) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  run_participant(store, "pointing-1", "P01", 0, false);
  run_participant(store, "pointing-1", "P02", 1, false);
  const std::string before = checksum(store.connection());

  const std::string unknown = store_error([&] { store.withdraw_study_participant("pointing-1", "P07"); });
  EXPECT_THAT(unknown, HasSubstr("participant 'P07' has no session of study 'pointing-1'"));
  EXPECT_THAT(unknown, HasSubstr("P01, P02"));
  EXPECT_THAT(store_error([&] { store.study_withdrawal("pointing-1", "P07"); }), HasSubstr("'P07'"));
  EXPECT_THAT(store_error([&] { store.withdraw_study_participant("pointing-2", "P01"); }),
              HasSubstr("the store has no sessions of that study"));

  EXPECT_EQ(checksum(store.connection()), before);
}

TEST(StoreStudyWithdraw, ACaptureAnotherParticipantsTrialAlsoRefersToIsKept) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const Participant gone = run_participant(store, "pointing-1", "P01", 0, false);
  const auto other = store.open_study_session(new_session("pointing-1", "P02", 1)).session_id;
  const std::int64_t shared = gone.captures.front();
  store.commit_study_trial(trial(other, 1, shared, "P02"));

  const ks::StudyWithdrawal w = store.withdraw_study_participant("pointing-1", "P01");

  EXPECT_EQ(w.captures, gone.captures.size() - 1);
  EXPECT_EQ(w.shared_captures, 1u);
  ASSERT_TRUE(store.capture_info(shared));
  EXPECT_GT(store.capture_info(shared)->sample_count, 0);
  EXPECT_EQ(store.study_trials(other).at(0).capture_id, shared);
  EXPECT_FALSE(store.capture_info(gone.captures.back()));
  expect_clean(store);
}

TEST(StoreStudyWithdraw, ACaptureStillRecordingRefusesTheWithdrawalAndNothingIsDeleted) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto session = store.open_study_session(new_session("pointing-1", "P01", 0)).session_id;
  ks::NewCapture info;
  info.source = "hapticd";
  info.rate_hz = 1000;
  auto recording = store.begin_capture(info);
  recording.append(ks::test::sample_at(0));
  recording.flush();
  store.commit_study_trial(trial(session, 1, recording.capture_id(), "P01"));
  const std::string before = checksum(store.connection());

  const std::string e = store_error([&] { store.withdraw_study_participant("pointing-1", "P01"); });

  EXPECT_THAT(e, HasSubstr("capture " + std::to_string(recording.capture_id()) + " is still recording"));
  EXPECT_THAT(e, HasSubstr("nothing was deleted"));
  EXPECT_EQ(checksum(store.connection()), before);
  recording.finish();
  EXPECT_EQ(store.withdraw_study_participant("pointing-1", "P01").captures, 1u);
}

TEST(StoreStudyWithdraw, TheWithdrawnRowsBytesDoNotLingerInTheStoreFileOrItsLog) {
  TempDir dir;
  const auto path = dir / "k.db";
  auto store = ks::Store::open(path);
  run_participant(store, "pointing-1", "P01", 0, false);
  run_participant(store, "pointing-1", "P02", 1, false);
  // A reader's open snapshot would hold the checkpoint off; none here.

  store.withdraw_study_participant("pointing-1", "P01");

  const std::string file = file_bytes(path);
  EXPECT_EQ(file.find("P01-said-pointing-1"), std::string::npos) << "a withdrawn note's text";
  EXPECT_EQ(file.find("P01-trace-pointing-1"), std::string::npos) << "a withdrawn trial's trace";
  EXPECT_NE(file.find("P02-said-pointing-1"), std::string::npos) << "the kept note is in the file itself";
  EXPECT_EQ(std::filesystem::file_size(dir / "k.db-wal"), 0u) << "the log is emptied";
}
