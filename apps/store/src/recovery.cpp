// Crash recovery: captures whose writer died mid-recording.
//
// A 'recording' row may belong to a process that is recording right now
// (another knoblab, hapticd), so status alone proves nothing: only a writer
// that no longer exists - kill(pid, 0) says ESRCH, or the row comes from an
// earlier boot - is taken as crashed. Its committed batches are kept; the
// capture becomes 'incomplete' with sample_count = the rows actually there
// and an end_reason naming the writer.
// (The writer must also be reaped: a zombie still counts as alive.)
#include <vector>

#include "internal.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::store {

namespace {

std::vector<std::int64_t> dead_writers(sqlite::Connection& db) {
  const std::string boot = detail::boot_id();
  std::vector<std::int64_t> dead;
  auto st = db.prepare(
      "SELECT id, writer_pid, writer_boot FROM captures WHERE status = 'recording'");
  while (st.step()) {
    const bool other_boot = !st.is_null(2) && !boot.empty() && st.column_text(2) != boot;
    if (st.is_null(1) || other_boot || !detail::process_alive(st.column_int(1)))
      dead.push_back(st.column_int(0));
  }
  return dead;
}

}  // namespace

std::vector<std::int64_t> Store::recover_interrupted() {
  // Cheap read first: the common case needs no write lock at all.
  if (dead_writers(*db_).empty()) return {};
  sqlite::Transaction tx(*db_);
  const auto dead = dead_writers(*db_);  // again, now under the write lock
  auto mark = db_->prepare(
      "UPDATE captures SET status = 'incomplete',"
      " sample_count = (SELECT count(*) FROM samples WHERE capture_id = ?1),"
      " end_reason = 'interrupted: its writer (' || source || ', pid ' ||"
      "   coalesce(writer_pid, '?') || ') ended without finishing it',"
      " finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now')"
      " WHERE id = ?1 AND status = 'recording'");
  for (const auto id : dead) mark.bind_int(1, id).run();
  tx.commit();
  return dead;
}

}  // namespace knoblab::store
