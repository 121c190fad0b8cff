// Importing a whole capture atomically.
#include <cstdio>
#include <stdexcept>
#include <string>

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

std::int64_t Store::import_capture(const interchange::Capture& c, const NewCapture& info) {
  interchange::validate(c);  // std::invalid_argument before anything is written

  NewCapture row = info;
  if (row.source.empty()) row.source = "import";
  if (row.rate_hz <= 0)  // mean rate of the file
    row.rate_hz = static_cast<double>(c.size() - 1) / (c.t.back() - c.t.front());
  if (row.metadata.empty()) row.metadata = metadata_json(c);

  sqlite::Transaction tx(*db_);
  const auto id = detail::insert_capture_row(*db_, row, "complete", c.has_command);
  auto insert = db_->prepare(
      "INSERT INTO samples (capture_id, idx, t, theta, omega, alpha, torque, command)"
      " VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
  insert.bind_int(1, id);
  for (std::size_t i = 0; i < c.size(); ++i) {
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
    insert.run();
  }
  db_->prepare(
         "UPDATE captures SET sample_count = ?2,"
         " finished_at = strftime('%Y-%m-%dT%H:%M:%fZ', 'now') WHERE id = ?1")
      .bind_int(1, id)
      .bind_int(2, static_cast<std::int64_t>(c.size()))
      .run();
  tx.commit();
  return id;
}

}  // namespace knoblab::store
