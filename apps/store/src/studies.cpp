// The user studies' sessions, trials and notes (schema 8, docs/store.md
// "Study sessions"). Every write is one short transaction; what can be
// checked without the database is checked before the write lock is taken.
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "internal.hpp"
#include "knoblab/interchange/digest.hpp"
#include "knoblab/store/store.hpp"
#include "knoblab/version.hpp"

namespace knoblab::store {

namespace {

double now_unix() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

std::string in_quotes(std::string_view s) { return "'" + std::string(s) + "'"; }

std::string session_name(std::int64_t id) { return "study session " + std::to_string(id); }

std::string trial_name(const StudyTrial& t) {
  return "trial " + std::to_string(t.trial_index) + " of " + session_name(t.session_id);
}

// sqlite keeps signed 64-bit integers.
std::int64_t to_int64(std::size_t n, const std::string& what) {
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int64_t>::max()))
    throw StoreError(what + " is too large (" + std::to_string(n) + ")");
  return static_cast<std::int64_t>(n);
}

// docs/studies.md: a study id is letters, digits, '-', '_', '.', at most 64.
bool valid_study_id(std::string_view s) {
  if (s.empty() || s.size() > 64) return false;
  for (const char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
          c == '_' || c == '.'))
      return false;
  return true;
}

// docs/studies.md: 1-16 letters, digits, '-' or '_', with at least one digit,
// so a name typed where the code belongs is refused (the schema checks the same).
bool valid_participant_code(std::string_view s) {
  if (s.empty() || s.size() > 16) return false;
  bool digit = false;
  for (const char c : s) {
    const bool d = c >= '0' && c <= '9';
    if (!(d || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '-' || c == '_')) return false;
    digit = digit || d;
  }
  return digit;
}

// The JSON type sqlite sees ("object", "array", "text", ...), none when the
// text is not valid JSON. No table is read: no lock is taken.
std::optional<std::string> json_kind(sqlite::Connection& db, std::string_view json) {
  auto st = db.prepare("SELECT CASE WHEN json_valid(?1) THEN json_type(?1) END");
  st.bind_text(1, json);
  std::optional<std::string> kind;
  if (st.step() && !st.is_null(0)) kind = st.column_text(0);
  st.reset();
  return kind;
}

void check_json(sqlite::Connection& db, std::string_view json, const std::string& what,
                const char* must_be = nullptr) {
  const auto kind = json_kind(db, json);
  if (!kind) throw StoreError(what + " is not valid JSON");
  if (must_be && *kind != must_be)
    throw StoreError(what + " must be a JSON " + must_be + ", got a JSON " + *kind);
}

const char* const kSessionSelect =
    "SELECT s.session_id, s.study, s.participant, s.participant_index, s.protocol_json,"
    " s.protocol_sha256, s.plan_trials, s.simulated, s.started_unix, s.finished_unix,"
    " s.knoblab_version,"
    " (SELECT count(*) FROM study_trials t WHERE t.session_id = s.session_id)"
    " FROM study_sessions s";

StudySession read_session_row(const sqlite::Statement& st) {
  StudySession s;
  s.session_id = st.column_int(0);
  s.study = st.column_text(1);
  s.participant = st.column_text(2);
  s.participant_index = static_cast<std::size_t>(st.column_int(3));
  s.protocol_json = st.column_text(4);
  s.protocol_sha256 = st.column_text(5);
  s.plan_trials = static_cast<std::size_t>(st.column_int(6));
  s.simulated = st.column_int(7) != 0;
  s.started_unix = st.column_double(8);
  if (!st.is_null(9)) s.finished_unix = st.column_double(9);
  s.knoblab_version = st.column_text(10);  // "" when NULL
  s.trials_committed = static_cast<std::size_t>(st.column_int(11));
  return s;
}

std::optional<StudySession> find_session(sqlite::Connection& db, std::string_view study,
                                         std::string_view participant) {
  auto st = db.prepare(std::string(kSessionSelect) + " WHERE s.study = ?1 AND s.participant = ?2");
  st.bind_text(1, study).bind_text(2, participant);
  std::optional<StudySession> s;
  if (st.step()) s = read_session_row(st);
  st.reset();
  return s;
}

// A session to resume must be the one asked for: the same protocol, the
// same plan. Anything else would mix two studies' trials in one session.
void check_resumable(const StudySession& s, const NewStudySession& asked, const std::string& sha) {
  const std::string who = "study " + in_quotes(s.study) + ", participant " + in_quotes(s.participant) +
                          ": the open session (" + session_name(s.session_id) + ")";
  if (s.protocol_sha256 != sha)
    throw StoreError(who + " ran a different protocol file (sha256 " + s.protocol_sha256 + ", now " + sha +
                     "); a session resumes only with the protocol it began with - run a changed "
                     "protocol as a new study id");
  if (s.plan_trials != asked.plan_trials)
    throw StoreError(who + " has a plan of " + std::to_string(s.plan_trials) + " trials, not " +
                     std::to_string(asked.plan_trials));
  if (s.participant_index != asked.participant_index)
    throw StoreError(who + " is of participant index " + std::to_string(s.participant_index) + ", not " +
                     std::to_string(asked.participant_index));
  if (s.simulated != asked.simulated)
    throw StoreError(who + " is of a " + (s.simulated ? "simulated" : "real") + " participant, not a " +
                     (asked.simulated ? "simulated" : "real") + " one");
}

struct SessionState {
  std::int64_t plan_trials = 0;
  bool finished = false;
};

// Inside the caller's transaction; throws for an unknown session.
SessionState session_state(sqlite::Connection& db, std::int64_t session_id) {
  auto st = db.prepare("SELECT plan_trials, finished_unix IS NOT NULL FROM study_sessions WHERE session_id = ?1");
  st.bind_int(1, session_id);
  if (!st.step()) throw StoreError("no study session with id " + std::to_string(session_id));
  SessionState s{st.column_int(0), st.column_int(1) != 0};
  st.reset();
  return s;
}

// The first plan index without a trial, from the ordered indices; past the
// plan (plan_trials + 1) when every trial is in.
std::int64_t first_missing(sqlite::Connection& db, std::int64_t session_id) {
  auto st = db.prepare("SELECT trial_index FROM study_trials WHERE session_id = ?1 ORDER BY trial_index");
  st.bind_int(1, session_id);
  std::int64_t expected = 1;
  while (st.step()) {
    if (st.column_int(0) != expected) break;  // indices are unique and ≥ 1: a gap
    ++expected;
  }
  st.reset();
  return expected;
}

}  // namespace

StudySession Store::open_study_session(const NewStudySession& s) {
  if (!valid_study_id(s.study))
    throw StoreError("study id " + in_quotes(s.study) +
                     " must be 1-64 letters, digits, '-', '_' or '.' (the protocol's \"study\")");
  if (!valid_participant_code(s.participant))
    throw StoreError("participant " + in_quotes(s.participant) +
                     " is not a pseudonymous code: 1-16 letters, digits, '-' or '_' with at least one "
                     "digit (docs/studies.md); the store keeps no names");
  if (s.plan_trials == 0) throw StoreError("a study session needs a plan of at least one trial (plan_trials 0)");
  const std::int64_t plan_trials = to_int64(s.plan_trials, "plan_trials");
  const std::int64_t participant_index = to_int64(s.participant_index, "participant_index");
  const std::string what = "protocol of study " + in_quotes(s.study);
  check_json(*db_, s.protocol_json, what, "object");
  {
    auto st = db_->prepare("SELECT json_extract(?1, '$.study') IS ?2");
    st.bind_text(1, s.protocol_json).bind_text(2, s.study);
    const bool same = st.step() && st.column_int(0) == 1;
    st.reset();
    if (!same) throw StoreError(what + ": its \"study\" is not " + in_quotes(s.study));
  }
  const std::string sha = interchange::sha256_hex(s.protocol_json);

  // Resuming, the common case after the first trial, reads only: no write lock.
  if (auto existing = find_session(*db_, s.study, s.participant)) {
    check_resumable(*existing, s, sha);
    return *existing;
  }
  sqlite::Transaction tx(*db_);
  // Under the write lock: another process may have opened it meanwhile.
  if (auto existing = find_session(*db_, s.study, s.participant)) {
    tx.commit();
    check_resumable(*existing, s, sha);
    return *existing;
  }
  auto st = db_->prepare(
      "INSERT INTO study_sessions (study, participant, participant_index, protocol_json,"
      " protocol_sha256, plan_trials, simulated, started_unix, knoblab_version)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)");
  st.bind_text(1, s.study)
      .bind_text(2, s.participant)
      .bind_int(3, participant_index)
      .bind_text(4, s.protocol_json)
      .bind_text(5, sha)
      .bind_int(6, plan_trials)
      .bind_int(7, s.simulated ? 1 : 0)
      .bind_double(8, now_unix())
      .bind_text(9, knoblab::kVersion);
  st.run();
  const std::int64_t id = db_->last_insert_rowid();
  auto created = find_session(*db_, s.study, s.participant);
  tx.commit();
  if (!created || created->session_id != id) throw StoreError(session_name(id) + " vanished");
  return *created;
}

std::optional<StudySession> Store::study_session(std::int64_t session_id) {
  auto st = db_->prepare(std::string(kSessionSelect) + " WHERE s.session_id = ?1");
  st.bind_int(1, session_id);
  std::optional<StudySession> s;
  if (st.step()) s = read_session_row(st);
  st.reset();
  return s;
}

std::vector<StudySession> Store::study_sessions(std::string_view study) {
  std::vector<StudySession> out;
  auto st = db_->prepare(std::string(kSessionSelect) + " WHERE s.study = ?1 ORDER BY s.session_id");
  st.bind_text(1, study);
  while (st.step()) out.push_back(read_session_row(st));
  return out;
}

void Store::commit_study_trial(const StudyTrial& t) {
  const std::string what = trial_name(t);
  if (t.trial_index == 0) throw StoreError(what + ": trial indices count from 1");
  if (t.block == 0) throw StoreError(what + ": blocks count from 1");
  if (t.stage.empty()) throw StoreError(what + ": the stage is empty");
  if (!std::isfinite(t.started_unix) || !std::isfinite(t.ended_unix) || t.ended_unix < t.started_unix)
    throw StoreError(what + ": started_unix and ended_unix must be finite with ended >= started (got " +
                     std::to_string(t.started_unix) + ", " + std::to_string(t.ended_unix) + ")");
  const std::int64_t index = to_int64(t.trial_index, what + ": trial_index");
  const std::int64_t block = to_int64(t.block, what + ": block");
  const std::int64_t repetition = to_int64(t.repetition, what + ": repetition");
  check_json(*db_, t.condition_json, what + ": condition_json", "object");
  check_json(*db_, t.result_json, what + ": result_json");
  check_json(*db_, t.ratings_json, what + ": ratings_json");
  check_json(*db_, t.biometrics_json, what + ": biometrics_json");
  check_json(*db_, t.trace_json, what + ": trace_json");

  sqlite::Transaction tx(*db_);
  const SessionState session = session_state(*db_, t.session_id);
  if (session.finished) throw StoreError(what + ": the session is finished and takes no more trials");
  if (index > session.plan_trials)
    throw StoreError(what + ": outside the session's plan of " + std::to_string(session.plan_trials) +
                     " trials (1-" + std::to_string(session.plan_trials) + ")");
  {
    auto st = db_->prepare("SELECT 1 FROM study_trials WHERE session_id = ?1 AND trial_index = ?2");
    st.bind_int(1, t.session_id).bind_int(2, index);
    const bool exists = st.step();
    st.reset();
    if (exists) throw StoreError(what + " is already committed; a trial is committed once, the first kept");
  }
  if (t.capture_id && !detail::row_exists(*db_, "captures", *t.capture_id))
    throw StoreError(what + ": no capture with id " + std::to_string(*t.capture_id));
  auto st = db_->prepare(
      "INSERT INTO study_trials (session_id, trial_index, block, stage, practice, repetition,"
      " condition_json, started_unix, ended_unix, result_json, ratings_json, biometrics_json,"
      " trace_json, capture_id) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14)");
  st.bind_int(1, t.session_id)
      .bind_int(2, index)
      .bind_int(3, block)
      .bind_text(4, t.stage)
      .bind_int(5, t.practice ? 1 : 0)
      .bind_int(6, repetition)
      .bind_text(7, t.condition_json)
      .bind_double(8, t.started_unix)
      .bind_double(9, t.ended_unix)
      .bind_text(10, t.result_json)
      .bind_text(11, t.ratings_json)
      .bind_text(12, t.biometrics_json)
      .bind_text(13, t.trace_json);
  if (t.capture_id)
    st.bind_int(14, *t.capture_id);
  else
    st.bind_null(14);
  st.run();
  tx.commit();
}

std::vector<StudyTrial> Store::study_trials(std::int64_t session_id) {
  std::vector<StudyTrial> out;
  auto st = db_->prepare(
      "SELECT session_id, trial_index, block, stage, practice, repetition, condition_json,"
      " started_unix, ended_unix, result_json, ratings_json, biometrics_json, trace_json, capture_id"
      " FROM study_trials WHERE session_id = ?1 ORDER BY trial_index");
  st.bind_int(1, session_id);
  while (st.step()) {
    StudyTrial t;
    t.session_id = st.column_int(0);
    t.trial_index = static_cast<std::size_t>(st.column_int(1));
    t.block = static_cast<std::size_t>(st.column_int(2));
    t.stage = st.column_text(3);
    t.practice = st.column_int(4) != 0;
    t.repetition = static_cast<std::size_t>(st.column_int(5));
    t.condition_json = st.column_text(6);
    t.started_unix = st.column_double(7);
    t.ended_unix = st.column_double(8);
    t.result_json = st.column_text(9);
    t.ratings_json = st.column_text(10);
    t.biometrics_json = st.column_text(11);
    t.trace_json = st.column_text(12);
    if (!st.is_null(13)) t.capture_id = st.column_int(13);
    out.push_back(std::move(t));
  }
  return out;
}

std::optional<std::size_t> Store::next_study_trial(std::int64_t session_id) {
  sqlite::Transaction tx(*db_, sqlite::Transaction::kRead);  // the plan and its trials from one snapshot
  const SessionState session = session_state(*db_, session_id);
  const std::int64_t next = first_missing(*db_, session_id);
  tx.commit();
  if (next > session.plan_trials) return std::nullopt;
  return static_cast<std::size_t>(next);
}

void Store::finish_study_session(std::int64_t session_id) {
  sqlite::Transaction tx(*db_);
  const SessionState session = session_state(*db_, session_id);
  if (session.finished) return;  // finished before (a retry): its first finish time stays
  const std::int64_t next = first_missing(*db_, session_id);
  if (next <= session.plan_trials)
    throw StoreError(session_name(session_id) + " cannot be finished: trial " + std::to_string(next) + " of its " +
                     std::to_string(session.plan_trials) + " is not committed");
  // Never before it started, even if the clock was set back meanwhile.
  db_->prepare("UPDATE study_sessions SET finished_unix = max(?2, started_unix) WHERE session_id = ?1")
      .bind_int(1, session_id)
      .bind_double(2, now_unix())
      .run();
  tx.commit();
}

std::int64_t Store::add_study_note(const StudyNote& n) {
  const std::string what = "note on " + session_name(n.session_id);
  if (n.trial_index && *n.trial_index == 0) throw StoreError(what + ": trial indices count from 1");
  if (!std::isfinite(n.noted_unix)) throw StoreError(what + ": noted_unix is not finite");
  check_json(*db_, n.tags_json, what + ": tags_json", "array");
  {
    auto st = db_->prepare("SELECT coalesce(sum(type <> 'text'), 0), count(*) FROM json_each(?1)");
    st.bind_text(1, n.tags_json);
    st.step();
    const bool strings = st.column_int(0) == 0;
    const bool tagged = st.column_int(1) > 0;
    st.reset();
    if (!strings) throw StoreError(what + ": tags_json must be an array of strings, got " + n.tags_json);
    if (n.text.empty() && !tagged) throw StoreError(what + ": neither text nor tags");
  }
  const std::optional<std::int64_t> index =
      n.trial_index ? std::optional(to_int64(*n.trial_index, what + ": trial_index")) : std::nullopt;

  sqlite::Transaction tx(*db_);
  const SessionState session = session_state(*db_, n.session_id);
  if (index && *index > session.plan_trials)
    throw StoreError(what + ": trial " + std::to_string(*index) + " is outside the session's plan of " +
                     std::to_string(session.plan_trials) + " trials");
  auto st = db_->prepare(
      "INSERT INTO study_notes (session_id, trial_index, noted_unix, text, tags_json)"
      " VALUES (?1, ?2, ?3, ?4, ?5)");
  st.bind_int(1, n.session_id);
  if (index)
    st.bind_int(2, *index);
  else
    st.bind_null(2);
  st.bind_double(3, n.noted_unix == 0 ? now_unix() : n.noted_unix).bind_text(4, n.text).bind_text(5, n.tags_json);
  st.run();
  const std::int64_t id = db_->last_insert_rowid();
  tx.commit();
  return id;
}

std::vector<StudyNote> Store::study_notes(std::int64_t session_id) {
  std::vector<StudyNote> out;
  auto st = db_->prepare(
      "SELECT note_id, session_id, trial_index, noted_unix, text, tags_json FROM study_notes"
      " WHERE session_id = ?1 ORDER BY note_id");
  st.bind_int(1, session_id);
  while (st.step()) {
    StudyNote n;
    n.note_id = st.column_int(0);
    n.session_id = st.column_int(1);
    if (!st.is_null(2)) n.trial_index = static_cast<std::size_t>(st.column_int(2));
    n.noted_unix = st.column_double(3);
    n.text = st.column_text(4);
    n.tags_json = st.column_text(5);
    out.push_back(std::move(n));
  }
  return out;
}

}  // namespace knoblab::store
