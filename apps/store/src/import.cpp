// Importing a whole capture in short transactions, all or nothing.
#include <chrono>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "internal.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::store {

namespace {

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      char esc[8];
      std::snprintf(esc, sizeof esc, "\\u%04x", c);
      out += esc;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

// The CSV's `# key: value` comments as a JSON object of strings, in order.
std::string metadata_json(const interchange::Capture& c) {
  std::string json = "{";
  for (const auto& [key, value] : c.metadata)
    json += (json.size() > 1 ? "," : "") + json_string(key) + ":" + json_string(value);
  return json + "}";
}

}  // namespace

std::int64_t Store::import_capture(const interchange::Capture& c, const NewCapture& info,
                                   const ImportOptions& options) {
  interchange::validate(c);  // std::invalid_argument before anything is written

  NewCapture row = info;
  if (row.source.empty()) row.source = "import";
  if (row.rate_hz <= 0)  // mean rate of the file
    row.rate_hz = static_cast<double>(c.size() - 1) / (c.t.back() - c.t.front());
  if (row.metadata.empty()) row.metadata = metadata_json(c);

  // The row first, on its own: 'recording' with our pid, so a crash from
  // here on is recovered like any dead writer's capture.
  bool created_knob = false;
  std::int64_t id = 0;
  {
    sqlite::Transaction tx(*db_);
    id = detail::insert_capture_row(*db_, row, "recording", c.has_command, &created_knob);
    tx.commit();
  }
  const std::optional<std::int64_t> knob = created_knob ? detail::knob_of_capture(*db_, id) : std::nullopt;

  try {
    auto insert = db_->prepare(
        "INSERT INTO samples (capture_id, idx, t, theta, omega, alpha, torque, command, flags)"
        " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)");
    auto count = db_->prepare("UPDATE captures SET sample_count = ?2 WHERE id = ?1");
    insert.bind_int(1, id);
    count.bind_int(1, id);
    using Clock = std::chrono::steady_clock;
    std::size_t i = 0;
    // At least one transaction, so the last one below also marks the
    // capture complete with its last batch.
    for (bool last = false; !last;) {
      sqlite::Transaction tx(*db_);
      const auto until = Clock::now() + options.max_transaction;
      do {
        insert.bind_int(2, static_cast<std::int64_t>(i))
            .bind_double(3, c.t[i])
            .bind_double(4, c.theta[i])
            .bind_double(5, c.omega[i])
            .bind_double(6, c.alpha[i])
            .bind_double(7, c.torque[i]);
        if (c.has_command)
          insert.bind_double(8, c.command[i]);
        else
          insert.bind_null(8);
        insert.bind_int(9, c.flags.empty() ? 0 : c.flags[i]);
        insert.run();
        ++i;
      } while (i < c.size() && Clock::now() < until);
      last = i == c.size();
      if (last) {
        // Last batch and 'complete' in one commit: no crash leaves every
        // sample there but the capture still 'recording'.
        db_->prepare(
               "UPDATE captures SET status = 'complete', sample_count = ?2,"
               " finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ?1")
            .bind_int(1, id)
            .bind_int(2, static_cast<std::int64_t>(i))
            .run();
      } else {
        count.bind_int(2, static_cast<std::int64_t>(i)).run();
      }
      tx.commit();
      if (options.on_commit) options.on_commit(static_cast<std::int64_t>(i));
      if (!last && options.pause.count() > 0) std::this_thread::sleep_for(options.pause);
    }
  } catch (...) {
    // Take the partial capture (and a knob made for it) out again, so a
    // failed import leaves the store as it was. If even that fails, the row
    // stays 'recording' under our pid and the next open after we exit marks
    // it 'incomplete'; the original error is the one to report.
    try {
      detail::remove_unfinished_capture(*db_, id, knob);
    } catch (const StoreError&) {
    }
    throw;
  }
  return id;
}

}  // namespace knoblab::store
