// A participant's withdrawal from a study: research ethics give them the
// right to have their data deleted (docs/studies.md "Withdrawal"). Their
// session, its trials and notes, and their trials' captures go in one
// transaction; the preview counts the same rows without deleting.
#include <string>
#include <vector>

#include "internal.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::store {

namespace {

// The withdrawn participant's sessions; every query below binds the study as
// ?1 and the participant as ?2. UNIQUE (study, participant) makes it one at
// most, but nothing here relies on that.
const std::string kWithdrawnSessions =
    "(SELECT session_id FROM study_sessions WHERE study = ?1 AND participant = ?2)";

// A count over the withdrawn rows.
std::int64_t count_withdrawn(sqlite::Connection& db, const std::string& sql, std::string_view study,
                             std::string_view participant) {
  auto st = db.prepare(sql);
  st.bind_text(1, study).bind_text(2, participant);
  const std::int64_t n = st.step() ? st.column_int(0) : 0;
  st.reset();
  return n;
}

struct TrialCaptures {
  std::vector<std::int64_t> owned;  // referred to by the withdrawn trials only
  std::size_t shared = 0;           // also by another participant's trial: kept
};

TrialCaptures trial_captures(sqlite::Connection& db, std::string_view study, std::string_view participant) {
  auto st = db.prepare(
      "SELECT DISTINCT t.capture_id, EXISTS (SELECT 1 FROM study_trials o WHERE o.capture_id = t.capture_id"
      " AND o.session_id NOT IN " + kWithdrawnSessions + ")"
      " FROM study_trials t WHERE t.capture_id IS NOT NULL AND t.session_id IN " + kWithdrawnSessions +
      " ORDER BY t.capture_id");
  st.bind_text(1, study).bind_text(2, participant);
  TrialCaptures captures;
  while (st.step()) {
    if (st.column_int(1) != 0)
      ++captures.shared;
    else
      captures.owned.push_back(st.column_int(0));
  }
  return captures;
}

std::int64_t samples_of(sqlite::Connection& db, const std::vector<std::int64_t>& captures) {
  auto st = db.prepare("SELECT count(*) FROM samples WHERE capture_id = ?1");
  std::int64_t n = 0;
  for (const std::int64_t id : captures) {
    st.bind_int(1, id);
    if (st.step()) n += st.column_int(0);
    st.reset();
  }
  return n;
}

// The codes with a session of the study, for the message that names none of
// them; the first few only, since a study may have hundreds.
std::string participants_of(sqlite::Connection& db, std::string_view study) {
  constexpr std::int64_t kListed = 20;
  auto st = db.prepare("SELECT participant, count(*) OVER () FROM study_sessions WHERE study = ?1 ORDER BY participant");
  st.bind_text(1, study);
  std::string codes;
  std::int64_t listed = 0, all = 0;
  while (st.step()) {
    all = st.column_int(1);
    if (listed == kListed) break;
    codes += (listed++ ? ", " : "") + st.column_text(0);
  }
  st.reset();
  if (all > listed) codes += ", … (" + std::to_string(all) + " in all)";
  return codes;
}

[[noreturn]] void throw_no_session(sqlite::Connection& db, std::string_view study, std::string_view participant) {
  const std::string codes = participants_of(db, study);
  const std::string what = "participant '" + std::string(participant) + "' has no session of study '" +
                           std::string(study) + "'";
  if (codes.empty()) throw StoreError(what + ": the store has no sessions of that study");
  throw StoreError(what + " (participants with one: " + codes + ")");
}

struct Withdrawn {
  StudyWithdrawal counts;
  std::vector<std::int64_t> captures;  // to delete
};

// Inside the caller's transaction; throws when the participant has no session.
Withdrawn find_withdrawn(sqlite::Connection& db, std::string_view study, std::string_view participant) {
  const auto count = [&](const std::string& sql) {
    return static_cast<std::size_t>(count_withdrawn(db, sql, study, participant));
  };
  Withdrawn w;
  w.counts.sessions = count("SELECT count(*) FROM study_sessions WHERE study = ?1 AND participant = ?2");
  if (w.counts.sessions == 0) throw_no_session(db, study, participant);
  w.counts.trials = count("SELECT count(*) FROM study_trials WHERE session_id IN " + kWithdrawnSessions);
  w.counts.notes = count("SELECT count(*) FROM study_notes WHERE session_id IN " + kWithdrawnSessions);
  TrialCaptures captures = trial_captures(db, study, participant);
  w.counts.captures = captures.owned.size();
  w.counts.shared_captures = captures.shared;
  w.counts.samples = samples_of(db, captures.owned);
  w.captures = std::move(captures.owned);
  return w;
}

// Deleted rows' bytes overwritten with zeros while it lives, not only
// unlinked: a withdrawn participant's data must not stay readable in the
// file's free pages. The connection's setting is restored after.
class ZeroDeletedContent {
 public:
  explicit ZeroDeletedContent(sqlite::Connection& db)
      : db_(db), before_(db.query_int("PRAGMA secure_delete")) {
    db_.exec("PRAGMA secure_delete = 1");
  }
  ~ZeroDeletedContent() {
    try {
      db_.exec("PRAGMA secure_delete = " + std::to_string(before_));  // our own integer
    } catch (const StoreError&) {
      // Only this connection's later deletes would zero pages too: harmless.
    }
  }
  ZeroDeletedContent(const ZeroDeletedContent&) = delete;
  ZeroDeletedContent& operator=(const ZeroDeletedContent&) = delete;

 private:
  sqlite::Connection& db_;
  std::int64_t before_;
};

// The zeroed pages into the store file now, and the write-ahead log, which
// still holds earlier copies of the deleted rows' pages, emptied. Best
// effort: while another process reads or writes, the log stays until a later
// checkpoint, and the withdrawal stands anyway.
void checkpoint_and_empty_log(sqlite::Connection& db) {
  try {
    db.query_int("PRAGMA wal_checkpoint(TRUNCATE)");
  } catch (const StoreError&) {
  }
}

}  // namespace

StudyWithdrawal Store::study_withdrawal(std::string_view study, std::string_view participant) {
  sqlite::Transaction tx(*db_, sqlite::Transaction::kRead);
  const Withdrawn w = find_withdrawn(*db_, study, participant);
  tx.commit();
  return w.counts;
}

StudyWithdrawal Store::withdraw_study_participant(std::string_view study, std::string_view participant) {
  Withdrawn w;
  {
    const ZeroDeletedContent zeroed(*db_);
    sqlite::Transaction tx(*db_);
    w = find_withdrawn(*db_, study, participant);
    // The sessions first: their trials and notes cascade, so no trial is left
    // to have its capture_id set NULL when the captures go.
    auto st = db_->prepare("DELETE FROM study_sessions WHERE study = ?1 AND participant = ?2");
    st.bind_text(1, study).bind_text(2, participant).run();
    for (const std::int64_t id : w.captures) {
      try {
        detail::delete_capture_row(*db_, id);
      } catch (const StoreError& e) {
        throw StoreError("withdrawing participant '" + std::string(participant) + "' from study '" +
                             std::string(study) + "': " + e.what() + "; nothing was deleted",
                         e.sqlite_code());
      }
    }
    tx.commit();
  }
  checkpoint_and_empty_log(*db_);
  return w.counts;
}

}  // namespace knoblab::store
