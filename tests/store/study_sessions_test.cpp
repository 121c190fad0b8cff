// The user studies' sessions, trials and notes (schema 8): a session opened
// once and resumed, refusals that store nothing, resume after gaps, cascades,
// the migration from version 7, and a participant's process SIGKILLed while
// committing trials.
#include <gmock/gmock.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "knoblab/interchange/digest.hpp"
#include "knoblab/store/schema.hpp"
#include "knoblab/store/store.hpp"
#include "test_util.hpp"

namespace ks = knoblab::store;
using ks::test::store_error;
using ks::test::TempDir;
using ::testing::HasSubstr;

namespace {

// A protocol file as run: the store keeps it byte for byte (indentation, a
// non-ASCII unit) and checks only that it is an object naming the study.
const std::string kProtocol = R"({
  "study": "pointing-1",
  "kind": "pointing",
  "title": "Rotary pointing, 2 × 2",
  "blocks": 2,
  "seed": 42
}
)";

ks::NewStudySession new_session(const std::string& participant = "P01", std::size_t index = 0) {
  ks::NewStudySession s;
  s.study = "pointing-1";
  s.participant = participant;
  s.participant_index = index;
  s.protocol_json = kProtocol;
  s.plan_trials = 8;
  return s;
}

// Trial i of a session: every field recomputable from i alone; a trace of
// `trace_rows` rows of the 100 ms telemetry.
ks::StudyTrial trial(std::int64_t session, std::size_t i, std::size_t trace_rows = 20) {
  ks::StudyTrial t;
  t.session_id = session;
  t.trial_index = i;
  t.block = 1 + (i - 1) / 4;
  t.stage = "all";
  t.practice = t.block == 1;
  t.repetition = t.practice ? 0 : 1;
  t.condition_json = R"({"knob":"level-)" + std::to_string(i % 7) + R"(","amplitude":"A30"})";
  t.started_unix = 1.7e9 + static_cast<double>(i) * 10.0 + 0.125;
  t.ended_unix = t.started_unix + 9.5 + static_cast<double>(i) * 1e-3;
  t.result_json = R"({"acquisitions":[{"mt_s":)" + std::to_string(0.5 + static_cast<double>(i) / 64) +
                  R"(,"errors":0}],"note":"θ in rad"})";
  t.ratings_json = R"({"appropriateness":)" + std::to_string(1 + i % 9) + "}";
  t.biometrics_json = R"({"emg_corrugator_V":1e-6,"markers":[)" + std::to_string(i) + "]}";
  std::string trace = "[";
  for (std::size_t r = 0; r < trace_rows; ++r)
    trace += (r ? "," : "") + std::string(R"({"t":)") + std::to_string(r) + R"(,"theta":)" +
             std::to_string(static_cast<double>(i) + static_cast<double>(r) * 1e-2) + "}";
  t.trace_json = trace + "]";
  return t;
}

void expect_same(const ks::StudyTrial& got, const ks::StudyTrial& want) {
  SCOPED_TRACE("trial " + std::to_string(want.trial_index));
  EXPECT_EQ(got.session_id, want.session_id);
  EXPECT_EQ(got.trial_index, want.trial_index);
  EXPECT_EQ(got.block, want.block);
  EXPECT_EQ(got.stage, want.stage);
  EXPECT_EQ(got.practice, want.practice);
  EXPECT_EQ(got.repetition, want.repetition);
  EXPECT_EQ(got.condition_json, want.condition_json);
  EXPECT_EQ(got.started_unix, want.started_unix);
  EXPECT_EQ(got.ended_unix, want.ended_unix);
  EXPECT_EQ(got.result_json, want.result_json);
  EXPECT_EQ(got.ratings_json, want.ratings_json);
  EXPECT_EQ(got.biometrics_json, want.biometrics_json);
  EXPECT_EQ(got.trace_json, want.trace_json);
  EXPECT_EQ(got.capture_id, want.capture_id);
}

std::int64_t finished_capture(ks::Store& store) {
  ks::NewCapture info;
  info.knob = "fan";
  info.rate_hz = 1000;
  info.source = "hapticd";
  auto w = store.begin_capture(info);
  for (int i = 0; i < 5; ++i) w.append(ks::test::sample_at(i));
  w.finish();
  return w.capture_id();
}

std::int64_t count(ks::Store& store, const std::string& table) {
  return store.connection().query_int("SELECT count(*) FROM " + table);
}

double now_unix() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

// ---- sessions ---------------------------------------------------------------

TEST(StoreStudySessions, AParticipantsSessionIsCreatedOnceAndReopenedToResumeWhereItStopped) {
  TempDir dir;
  const auto path = dir / "k.db";
  std::int64_t id = 0;
  double started = 0;
  {
    auto store = ks::Store::open(path);
    const double before = now_unix();
    const auto s = store.open_study_session(new_session());
    id = s.session_id;
    started = s.started_unix;
    EXPECT_EQ(s.study, "pointing-1");
    EXPECT_EQ(s.participant, "P01");
    EXPECT_EQ(s.participant_index, 0u);
    EXPECT_EQ(s.protocol_json, kProtocol);
    EXPECT_EQ(s.protocol_sha256, knoblab::interchange::sha256_hex(kProtocol));
    EXPECT_EQ(s.plan_trials, 8u);
    EXPECT_FALSE(s.simulated);
    EXPECT_GE(s.started_unix, before - 1);
    EXPECT_LE(s.started_unix, now_unix() + 1);
    EXPECT_FALSE(s.finished_unix);
    EXPECT_FALSE(s.knoblab_version.empty());
    EXPECT_EQ(s.trials_committed, 0u);
    EXPECT_EQ(store.next_study_trial(id), 1u);
    store.commit_study_trial(trial(id, 1));
    store.commit_study_trial(trial(id, 2));
  }
  // The process ends; a new one opens the same participant's session.
  auto store = ks::Store::open(path);
  const auto again = store.open_study_session(new_session());
  EXPECT_EQ(again.session_id, id);
  EXPECT_EQ(again.started_unix, started);
  EXPECT_EQ(again.trials_committed, 2u);
  EXPECT_EQ(store.next_study_trial(id), 3u);
  const auto trials = store.study_trials(id);
  ASSERT_EQ(trials.size(), 2u);
  expect_same(trials[0], trial(id, 1));
  expect_same(trials[1], trial(id, 2));

  // Other participants get sessions of their own; the study lists them all.
  auto p2 = new_session("P02", 1);
  p2.simulated = true;
  const auto other = store.open_study_session(p2);
  EXPECT_NE(other.session_id, id);
  EXPECT_TRUE(other.simulated);
  const auto all = store.study_sessions("pointing-1");
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].session_id, id);
  EXPECT_EQ(all[0].trials_committed, 2u);
  EXPECT_EQ(all[1].participant, "P02");
  EXPECT_TRUE(store.study_sessions("another-study").empty());
  EXPECT_EQ(store.study_session(other.session_id)->participant_index, 1u);
  EXPECT_FALSE(store.study_session(other.session_id + 100));
}

TEST(StoreStudySessions, ResumingWithAChangedProtocolOrPlanIsRefusedAndTheSessionKept) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto s = store.open_study_session(new_session());
  store.commit_study_trial(trial(s.session_id, 1));
  const std::string before = ks::test::checksum(store.connection());

  auto edited = new_session();
  edited.protocol_json = kProtocol + " ";  // the file edited, even by a space: another protocol
  EXPECT_THAT(store_error([&] { store.open_study_session(edited); }), HasSubstr("different protocol"));
  auto longer = new_session();
  longer.plan_trials = 9;
  EXPECT_THAT(store_error([&] { store.open_study_session(longer); }), HasSubstr("plan of 8 trials, not 9"));
  auto row = new_session("P01", 3);
  EXPECT_THAT(store_error([&] { store.open_study_session(row); }), HasSubstr("participant index 0, not 3"));
  auto simulated = new_session();
  simulated.simulated = true;
  EXPECT_THAT(store_error([&] { store.open_study_session(simulated); }), HasSubstr("real participant"));

  EXPECT_EQ(ks::test::checksum(store.connection()), before);
  EXPECT_EQ(store.study_session(s.session_id)->protocol_json, kProtocol);
  EXPECT_EQ(store.open_study_session(new_session()).session_id, s.session_id);  // as it was: resumes
}

TEST(StoreStudySessions, ParticipantsAreCodesNeverNamesAndTheProtocolMustNameTheStudy) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  for (const char* bad : {"Alice", "", "P 01", "P01-with-a-long-tail", "Zoë1"})
    EXPECT_THAT(store_error([&] { store.open_study_session(new_session(bad)); }),
                HasSubstr("not a pseudonymous code"))
        << bad;
  auto wrong_study = new_session();
  wrong_study.study = "pointing-2";
  EXPECT_THAT(store_error([&] { store.open_study_session(wrong_study); }),
              HasSubstr("its \"study\" is not 'pointing-2'"));
  auto not_json = new_session();
  not_json.protocol_json = "{\"study\": \"pointing-1\",";
  EXPECT_THAT(store_error([&] { store.open_study_session(not_json); }), HasSubstr("is not valid JSON"));
  auto empty_plan = new_session();
  empty_plan.plan_trials = 0;
  EXPECT_THAT(store_error([&] { store.open_study_session(empty_plan); }), HasSubstr("at least one trial"));
  EXPECT_EQ(count(store, "study_sessions"), 0);

  // The schema refuses a name as well, whoever writes.
  EXPECT_THROW(store.connection().exec(
                   "INSERT INTO study_sessions (study, participant, participant_index, protocol_json,"
                   " protocol_sha256, plan_trials, simulated, started_unix) VALUES ('s', 'Alice', 0,"
                   " '{\"study\":\"s\"}', '" + std::string(64, 'a') + "', 1, 0, 0)"),
               ks::StoreError);
}

// ---- trials -----------------------------------------------------------------

TEST(StoreStudySessions, ATrialIsCommittedOnceAndTheFirstIsKept) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto id = store.open_study_session(new_session()).session_id;
  store.commit_study_trial(trial(id, 1));
  auto second = trial(id, 1);
  second.result_json = R"({"acquisitions":[]})";
  second.ended_unix += 60;
  EXPECT_THAT(store_error([&] { store.commit_study_trial(second); }),
              HasSubstr("trial 1 of study session " + std::to_string(id) + " is already committed"));
  const auto trials = store.study_trials(id);
  ASSERT_EQ(trials.size(), 1u);
  expect_same(trials[0], trial(id, 1));
}

TEST(StoreStudySessions, EveryFieldOfATrialComesBackAsCommittedWithItsCapture) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto capture = finished_capture(store);
  const auto id = store.open_study_session(new_session()).session_id;
  auto t = trial(id, 5, 600);  // a minute of trace
  t.capture_id = capture;
  t.ratings_json = R"({"sam_valence": 7, "comment": "smooth \"like\" a dial"})";
  store.commit_study_trial(t);
  const auto trials = store.study_trials(id);
  ASSERT_EQ(trials.size(), 1u);
  expect_same(trials[0], t);
  auto unknown_capture = trial(id, 6);
  unknown_capture.capture_id = capture + 100;
  EXPECT_THAT(store_error([&] { store.commit_study_trial(unknown_capture); }),
              HasSubstr("no capture with id"));
  EXPECT_THAT(store_error([&] { store.commit_study_trial(trial(id + 100, 1)); }),
              HasSubstr("no study session with id"));
  EXPECT_EQ(count(store, "study_trials"), 1);
}

TEST(StoreStudySessions, TheNextTrialIsTheFirstMissingPlanIndexAfterGaps) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto asked = new_session();
  asked.plan_trials = 6;
  const auto id = store.open_study_session(asked).session_id;
  EXPECT_EQ(store.next_study_trial(id), 1u);
  store.commit_study_trial(trial(id, 2));
  store.commit_study_trial(trial(id, 3));
  EXPECT_EQ(store.next_study_trial(id), 1u);  // trial 1 never committed: it comes first
  store.commit_study_trial(trial(id, 1));
  EXPECT_EQ(store.next_study_trial(id), 4u);
  store.commit_study_trial(trial(id, 6));
  EXPECT_EQ(store.next_study_trial(id), 4u);
  store.commit_study_trial(trial(id, 4));
  EXPECT_EQ(store.next_study_trial(id), 5u);
  store.commit_study_trial(trial(id, 5));
  EXPECT_EQ(store.next_study_trial(id), std::nullopt);
  const auto trials = store.study_trials(id);
  ASSERT_EQ(trials.size(), 6u);
  for (std::size_t i = 0; i < trials.size(); ++i) EXPECT_EQ(trials[i].trial_index, i + 1);
  EXPECT_THAT(store_error([&] { store.next_study_trial(id + 1); }), HasSubstr("no study session with id"));
}

TEST(StoreStudySessions, TrialsOutsideThePlanOrInAFinishedSessionAreRefused) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto asked = new_session();
  asked.plan_trials = 2;
  const auto id = store.open_study_session(asked).session_id;
  EXPECT_THAT(store_error([&] { store.commit_study_trial(trial(id, 0)); }), HasSubstr("count from 1"));
  EXPECT_THAT(store_error([&] { store.commit_study_trial(trial(id, 3)); }),
              HasSubstr("outside the session's plan of 2 trials"));
  auto backwards = trial(id, 1);
  backwards.ended_unix = backwards.started_unix - 1;
  EXPECT_THAT(store_error([&] { store.commit_study_trial(backwards); }), HasSubstr("ended >= started"));
  auto nan = trial(id, 1);
  nan.started_unix = std::nan("");
  EXPECT_THAT(store_error([&] { store.commit_study_trial(nan); }), HasSubstr("finite"));
  EXPECT_EQ(count(store, "study_trials"), 0);

  store.commit_study_trial(trial(id, 2));
  EXPECT_THAT(store_error([&] { store.finish_study_session(id); }),
              HasSubstr("trial 1 of its 2 is not committed"));
  EXPECT_FALSE(store.study_session(id)->finished_unix);
  store.commit_study_trial(trial(id, 1));
  const double before = now_unix();
  store.finish_study_session(id);
  const auto finished = store.study_session(id)->finished_unix;
  ASSERT_TRUE(finished);
  EXPECT_GE(*finished, before - 1);
  store.finish_study_session(id);  // again: nothing changes
  EXPECT_EQ(store.study_session(id)->finished_unix, finished);
  EXPECT_THAT(store_error([&] { store.commit_study_trial(trial(id, 1)); }), HasSubstr("is finished"));
  // A finished session still resumes (to nothing) with the same protocol.
  const auto resumed = store.open_study_session(asked);
  EXPECT_EQ(resumed.finished_unix, finished);
  EXPECT_EQ(store.next_study_trial(id), std::nullopt);
}

TEST(StoreStudySessions, InvalidJsonIsRefusedNamingTheFieldAndStoresNothing) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto id = store.open_study_session(new_session()).session_id;
  const std::string bad = R"({"acquisitions": [1, 2,]})";
  const std::vector<std::pair<std::string, std::string ks::StudyTrial::*>> fields = {
      {"condition_json", &ks::StudyTrial::condition_json}, {"result_json", &ks::StudyTrial::result_json},
      {"ratings_json", &ks::StudyTrial::ratings_json},     {"biometrics_json", &ks::StudyTrial::biometrics_json},
      {"trace_json", &ks::StudyTrial::trace_json}};
  for (const auto& [name, field] : fields) {
    auto t = trial(id, 1);
    t.*field = bad;
    EXPECT_THAT(store_error([&] { store.commit_study_trial(t); }), HasSubstr(name + " is not valid JSON"));
    t.*field = "";
    EXPECT_THAT(store_error([&] { store.commit_study_trial(t); }), HasSubstr(name + " is not valid JSON"));
  }
  auto list = trial(id, 1);
  list.condition_json = R"(["A30"])";
  EXPECT_THAT(store_error([&] { store.commit_study_trial(list); }),
              HasSubstr("condition_json must be a JSON object"));
  EXPECT_EQ(count(store, "study_trials"), 0);
  EXPECT_EQ(store.next_study_trial(id), 1u);

  // The schema checks the same, whoever writes.
  auto& db = store.connection();
  EXPECT_THROW(db.exec("INSERT INTO study_trials (session_id, trial_index, block, stage, practice, repetition,"
                       " condition_json, started_unix, ended_unix, result_json, ratings_json, biometrics_json,"
                       " trace_json) VALUES (" +
                       std::to_string(id) + ", 1, 1, 'all', 0, 1, '{}', 0, 1, '{}', '{}', '{}', '[1,')"),
               ks::StoreError);
  EXPECT_EQ(count(store, "study_trials"), 0);
}

TEST(StoreStudySessions, TheSchemaKeepsTrialsInThePlanAndWhatRanFixed) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  auto asked = new_session();
  asked.plan_trials = 1;
  const auto id = store.open_study_session(asked).session_id;
  auto& db = store.connection();
  const auto insert = [&](int index) {
    db.exec("INSERT INTO study_trials (session_id, trial_index, block, stage, practice, repetition,"
            " condition_json, started_unix, ended_unix, result_json, ratings_json, biometrics_json,"
            " trace_json) VALUES (" +
            std::to_string(id) + ", " + std::to_string(index) + ", 1, 'all', 0, 1, '{}', 0, 1, '{}', '{}',"
            " '{}', '[]')");
  };
  const auto sql_error = [&](auto&& f) { return store_error(f); };
  const std::string finish = "UPDATE study_sessions SET finished_unix = started_unix + 1 WHERE session_id = " +
                             std::to_string(id);
  EXPECT_THAT(sql_error([&] { insert(2); }), HasSubstr("past the end of its session's plan"));
  EXPECT_THAT(sql_error([&] { db.exec(finish); }), HasSubstr("trials missing cannot be finished"));
  EXPECT_THAT(sql_error([&] {
                db.exec("UPDATE study_sessions SET protocol_json = '{\"study\":\"pointing-1\"}'");
              }),
              HasSubstr("fixed once it is open"));
  insert(1);
  db.exec(finish);
  db.exec("DELETE FROM study_trials");
  EXPECT_THAT(sql_error([&] { insert(1); }), HasSubstr("finished study session takes no more trials"));
}

// ---- notes ------------------------------------------------------------------

TEST(StoreStudySessions, NotesAboutTheSessionOrATrialComeBackInOrder) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto id = store.open_study_session(new_session()).session_id;
  ks::StudyNote about_session;
  about_session.session_id = id;
  about_session.text = "P01 left-handed; glasses off for the EMG electrodes";
  const double before = now_unix();
  const auto first = store.add_study_note(about_session);
  ks::StudyNote about_trial;
  about_trial.session_id = id;
  about_trial.trial_index = 3;  // not committed yet: said during the trial
  about_trial.noted_unix = 1.7e9 + 0.25;
  about_trial.text = "\"it sticks just before the target\"";
  about_trial.tags_json = R"(["think-aloud", "overshoot"])";
  const auto second = store.add_study_note(about_trial);
  ks::StudyNote tags_only;
  tags_only.session_id = id;
  tags_only.tags_json = R"(["interrupted"])";
  store.add_study_note(tags_only);
  EXPECT_GT(second, first);

  const auto notes = store.study_notes(id);
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_EQ(notes[0].note_id, first);
  EXPECT_FALSE(notes[0].trial_index);
  EXPECT_GE(notes[0].noted_unix, before - 1);  // 0: now
  EXPECT_EQ(notes[0].tags_json, "[]");
  EXPECT_EQ(notes[1].trial_index, 3u);
  EXPECT_EQ(notes[1].noted_unix, 1.7e9 + 0.25);
  EXPECT_EQ(notes[1].text, about_trial.text);
  EXPECT_EQ(notes[1].tags_json, about_trial.tags_json);
  EXPECT_EQ(notes[2].text, "");

  auto bad = about_trial;
  bad.tags_json = R"(["ok", 3])";
  EXPECT_THAT(store_error([&] { store.add_study_note(bad); }), HasSubstr("array of strings"));
  bad.tags_json = R"({"tag": "x"})";
  EXPECT_THAT(store_error([&] { store.add_study_note(bad); }), HasSubstr("must be a JSON array"));
  bad = about_trial;
  bad.trial_index = 9;
  EXPECT_THAT(store_error([&] { store.add_study_note(bad); }), HasSubstr("outside the session's plan"));
  bad = tags_only;
  bad.tags_json = "[]";
  EXPECT_THAT(store_error([&] { store.add_study_note(bad); }), HasSubstr("neither text nor tags"));
  bad = about_session;
  bad.session_id = id + 1;
  EXPECT_THAT(store_error([&] { store.add_study_note(bad); }), HasSubstr("no study session with id"));
  EXPECT_EQ(count(store, "study_notes"), 3);
}

// ---- deletion -----------------------------------------------------------------

TEST(StoreStudySessions, DeletingASessionDeletesItsTrialsAndNotesOnly) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto gone = store.open_study_session(new_session("P01")).session_id;
  const auto kept = store.open_study_session(new_session("P02", 1)).session_id;
  for (const auto id : {gone, kept}) {
    store.commit_study_trial(trial(id, 1));
    store.commit_study_trial(trial(id, 2));
    ks::StudyNote n;
    n.session_id = id;
    n.trial_index = 1;
    n.text = "note";
    store.add_study_note(n);
  }
  store.connection().prepare("DELETE FROM study_sessions WHERE session_id = ?1").bind_int(1, gone).run();
  EXPECT_FALSE(store.study_session(gone));
  EXPECT_TRUE(store.study_trials(gone).empty());
  EXPECT_TRUE(store.study_notes(gone).empty());
  EXPECT_EQ(count(store, "study_trials"), 2);
  EXPECT_EQ(count(store, "study_notes"), 1);
  EXPECT_EQ(store.study_trials(kept).size(), 2u);
  EXPECT_FALSE(store.connection().prepare("PRAGMA foreign_key_check").step());
}

TEST(StoreStudySessions, DeletingATrialsCaptureKeepsTheTrialWithoutIt) {
  TempDir dir;
  auto store = ks::Store::open(dir / "k.db");
  const auto recorded = finished_capture(store);
  const auto other = finished_capture(store);
  const auto id = store.open_study_session(new_session()).session_id;
  auto t1 = trial(id, 1);
  t1.capture_id = recorded;
  auto t2 = trial(id, 2);
  t2.capture_id = other;
  store.commit_study_trial(t1);
  store.commit_study_trial(t2);
  store.delete_capture(recorded);
  const auto trials = store.study_trials(id);
  ASSERT_EQ(trials.size(), 2u);
  t1.capture_id.reset();
  expect_same(trials[0], t1);  // everything else as committed
  EXPECT_EQ(trials[1].capture_id, other);
  EXPECT_EQ(store.next_study_trial(id), 3u);
}

// ---- migration ------------------------------------------------------------------

TEST(StoreStudySessions, Version7DatabaseIsUpgradedKeepingItsData) {
  TempDir dir;
  const auto path = dir / "k.db";
  const std::string sha(64, 'c');
  std::string old_tables;
  const auto dump_old_tables = [](ks::sqlite::Connection& db) {
    std::string out;
    for (const char* table : {"knobs", "captures", "samples", "biometrics", "fits", "fit_files", "discrepancies",
                              "discrepancy_files"}) {
      auto st = db.prepare(std::string("SELECT * FROM ") + table + " ORDER BY 1, 2");
      out += std::string(table) + ":";
      while (st.step())
        for (int c = 0; c < st.column_count(); ++c) out += (st.is_null(c) ? "NULL" : st.column_text(c)) + "|";
      out += "\n";
    }
    return out;
  };
  {
    // A database as knoblab wrote it at schema version 7.
    auto db = ks::sqlite::Connection::open(path);
    db.exec("PRAGMA foreign_keys = ON");
    ks::migrate(db, 7);
    ASSERT_EQ(ks::schema_version(db), 7);
    db.exec(R"sql(
INSERT INTO knobs (id, name) VALUES (1, 'fan');
INSERT INTO captures (id, knob_id, mode, rate_hz, source, status, sample_count)
  VALUES (1, 1, 'lab', 1000, 'import', 'complete', 1);
INSERT INTO samples VALUES (1, 0, 0.0, 0.1, 0.2, 0.3, 0.4, NULL, 0);
INSERT INTO biometrics VALUES (1, 0, 0.0, 1e-6, 2e-6, 3e-6);
INSERT INTO fits (id, capture_id, model, params, result, created_at, tool_version, input_sha256, options)
  VALUES (7, 1, 'thesis6', '{"M_acc":1e-5}', '{"rmse_Nm":0.002}', '2024-05-01T10:00:00.000Z', '0.1.0', ')sql" +
            sha + R"sql(', '{"alpha":"accel"}');
INSERT INTO fit_files (fit_id, name, bytes) VALUES (7, 'fit.json', x'7b7d0a');
INSERT INTO discrepancies (id, capture_id, result, created_at) VALUES (3, 1, '{"findings":[]}', '2024-05-02T10:00:00.000Z');
INSERT INTO discrepancy_files (discrepancy_id, name, bytes) VALUES (3, 'summary.md', x'23');
)sql");
    old_tables = dump_old_tables(db);
    EXPECT_EQ(db.query_int("SELECT count(*) FROM sqlite_schema WHERE name = 'study_sessions'"), 0);
  }

  auto store = ks::Store::open(path);
  EXPECT_EQ(store.schema_version(), 8);
  EXPECT_EQ(ks::latest_schema_version(), 8);
  EXPECT_EQ(store.integrity_check(), "ok");
  EXPECT_FALSE(store.connection().prepare("PRAGMA foreign_key_check").step());
  EXPECT_EQ(dump_old_tables(store.connection()), old_tables);
  EXPECT_EQ(store.fit_info(7)->provenance->input_sha256, sha);
  EXPECT_EQ(store.load_samples(1).size(), 1u);
  for (const char* table : {"study_sessions", "study_trials", "study_notes"}) EXPECT_EQ(count(store, table), 0);

  // The old capture takes a trial's recording; deleting it keeps the trial.
  const auto id = store.open_study_session(new_session()).session_id;
  auto t = trial(id, 1);
  t.capture_id = 1;
  store.commit_study_trial(t);
  store.delete_capture(1);
  EXPECT_FALSE(store.study_trials(id).at(0).capture_id);
}

TEST(StoreStudySessions, FailedMigrationToVersion8LeavesVersion7) {
  TempDir dir;
  const auto path = dir / "k.db";
  {
    auto db = ks::sqlite::Connection::open(path);
    ks::migrate(db, 7);
    db.exec("CREATE TABLE study_notes (x)");  // in the way of step 8, after its first tables
  }
  EXPECT_THAT(store_error([&] { ks::Store::open(path); }), HasSubstr("migration to version 8 failed"));
  auto db = ks::sqlite::Connection::open(path);
  EXPECT_EQ(ks::schema_version(db), 7);
  EXPECT_EQ(db.query_int("SELECT count(*) FROM sqlite_schema WHERE name IN ('study_sessions', 'study_trials')"), 0);
}

// ---- crash safety -----------------------------------------------------------------

namespace {

constexpr std::size_t kCrashPlan = 100000;
constexpr std::size_t kCrashTrace = 3000;  // 5 min of 100 ms rows: a commit takes a while

ks::NewStudySession crash_session() {
  auto s = new_session("P07", 6);
  s.plan_trials = kCrashPlan;
  s.simulated = true;
  return s;
}

// In the child: a participant's process resuming its session and committing
// trials "forever", reporting each trial index once its commit has returned.
[[noreturn]] void run_trials_until_killed(const std::filesystem::path& path, int fd) {
  try {
    auto store = ks::Store::open(path);
    const auto session = store.open_study_session(crash_session());
    for (auto next = store.next_study_trial(session.session_id); next; ++*next) {
      store.commit_study_trial(trial(session.session_id, *next, kCrashTrace));
      const auto reported = static_cast<std::int64_t>(*next);
      if (::write(fd, &reported, sizeof reported) != sizeof reported) ::_exit(3);
    }
    ::_exit(4);  // the plan is too long to finish before the kill
  } catch (...) {
    ::_exit(2);
  }
}

}  // namespace

TEST(StoreStudySessions, SigkillWhileCommittingLosesNoReportedTrialAndResumesAtTheFirstMissing) {
  TempDir dir;
  const auto path = dir / "k.db";
  { ks::Store::open(path); }  // schema first; no connection open across fork()

  // Several rounds, each child resuming where the last was killed; every
  // trial committed before must survive the later kills untouched.
  const int kill_after[] = {4, 11, 7, 9};
  std::int64_t reported = 0;  // the last trial index any child reported committed
  for (int round = 0; round < 4; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    int fds[2];
    ASSERT_EQ(::pipe(fds), 0);
    ks::test::Child child;
    child.pid = ::fork();
    ASSERT_GE(child.pid, 0);
    if (child.pid == 0) {
      ::close(fds[0]);
      run_trials_until_killed(path, fds[1]);
    }
    ::close(fds[1]);
    const std::int64_t before = reported;
    for (int n = 0; n < kill_after[round]; ++n) {
      ASSERT_TRUE(ks::test::read_int64(fds[0], reported)) << "child died early";
      // The child resumed at the first missing trial and goes on in order.
      ASSERT_EQ(reported, before + n + 1);
    }
    ::usleep(static_cast<useconds_t>(200 + round * 1100));  // land at different points of a commit
    ASSERT_EQ(::kill(child.pid, SIGKILL), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child.pid, &status, 0), child.pid);
    child.pid = -1;
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
    // Reports that made it into the pipe before the kill were committed too.
    for (std::int64_t n; ks::test::read_int64(fds[0], n);) reported = n;
    ::close(fds[0]);

    auto store = ks::Store::open(path);
    EXPECT_EQ(store.integrity_check(), "ok");
    const auto sessions = store.study_sessions("pointing-1");
    ASSERT_EQ(sessions.size(), 1u);
    const auto id = sessions[0].session_id;
    const auto trials = store.study_trials(id);
    const auto n = static_cast<std::int64_t>(trials.size());
    // Everything reported is there; at most the one trial in flight more.
    EXPECT_GE(n, reported);
    EXPECT_LE(n, reported + 1);
    EXPECT_EQ(sessions[0].trials_committed, trials.size());
    for (std::size_t i = 0; i < trials.size(); ++i) {
      ASSERT_EQ(trials[i].trial_index, i + 1) << "a gap in the committed trials";
      const auto want = trial(id, i + 1, kCrashTrace);
      ASSERT_TRUE(trials[i].trace_json == want.trace_json && trials[i].result_json == want.result_json &&
                  trials[i].condition_json == want.condition_json && trials[i].ended_unix == want.ended_unix)
          << "trial " << i + 1 << " not intact";
    }
    EXPECT_EQ(store.next_study_trial(id), trials.size() + 1);
    reported = n;  // the next child resumes after the trial in flight, if it got in
  }
}
