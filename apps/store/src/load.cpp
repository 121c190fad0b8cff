// Reading captures back: rows, and samples as an interchange::Capture.
#include <charconv>
#include <cmath>
#include <string>

#include "internal.hpp"
#include "knoblab/store/store.hpp"

namespace knoblab::store {

const char* const detail::kCaptureColumns =
    "c.id, c.knob_id, coalesce(k.name, ''), c.mode, c.rate_hz, c.stimulus, c.orientation,"
    " c.calibration, c.source, c.status, c.writer_pid, c.has_command, c.started_at,"
    " c.finished_at, c.sample_count, c.metadata, c.end_reason"
    " FROM captures c LEFT JOIN knobs k ON k.id = c.knob_id";

CaptureInfo detail::read_capture_row(const sqlite::Statement& st) {
  CaptureInfo c;
  c.id = st.column_int(0);
  if (!st.is_null(1)) c.knob_id = st.column_int(1);
  c.knob = st.column_text(2);
  c.mode = st.column_text(3);
  c.rate_hz = st.column_double(4);
  c.stimulus = st.column_text(5);
  c.orientation = st.column_text(6);
  c.calibration = st.column_text(7);
  c.source = st.column_text(8);
  c.status = st.column_text(9);
  if (!st.is_null(10)) c.writer_pid = st.column_int(10);
  c.has_command = st.column_int(11) != 0;
  c.started_at = st.column_text(12);
  if (!st.is_null(13)) c.finished_at = st.column_text(13);
  c.sample_count = st.column_int(14);
  c.metadata = st.column_text(15);
  if (!st.is_null(16)) c.end_reason = st.column_text(16);
  return c;
}

std::vector<CaptureInfo> Store::list_captures() {
  std::vector<CaptureInfo> out;
  auto st = db_->prepare(std::string("SELECT ") + detail::kCaptureColumns + " ORDER BY c.id");
  while (st.step()) out.push_back(detail::read_capture_row(st));
  return out;
}

std::optional<CaptureInfo> Store::capture_info(std::int64_t id) {
  auto st = db_->prepare(std::string("SELECT ") + detail::kCaptureColumns + " WHERE c.id = ?1");
  st.bind_int(1, id);
  if (!st.step()) return std::nullopt;
  auto info = detail::read_capture_row(st);
  st.reset();
  return info;
}

namespace {

// A value for one `# key: value` line. Valid JSON has control characters
// only as whitespace between tokens (inside strings they are escaped), so
// turning them into spaces keeps its meaning.
std::string one_line(std::string text) {
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return text;
}

std::string number(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

}  // namespace

interchange::Capture Store::load_samples(std::int64_t id) {
  // One snapshot for the row and its samples, even while a writer appends.
  sqlite::Transaction tx(*db_, sqlite::Transaction::kRead);
  const auto info = capture_info(id);
  if (!info) throw StoreError("no capture with id " + std::to_string(id));

  interchange::Capture c;
  c.has_command = info->has_command;
  const auto n = static_cast<std::size_t>(info->sample_count);
  for (auto* v : {&c.t, &c.theta, &c.omega, &c.alpha, &c.torque}) v->reserve(n);
  if (c.has_command) c.command.reserve(n);
  c.flags.reserve(n);

  auto st = db_->prepare(
      "SELECT idx, t, theta, omega, alpha, torque, command, flags FROM samples"
      " WHERE capture_id = ?1 ORDER BY idx");
  st.bind_int(1, id);
  std::int64_t expected = 0;
  while (st.step()) {
    if (st.column_int(0) != expected)
      throw StoreError("capture " + std::to_string(id) + ": sample " + std::to_string(expected) +
                       " is missing");
    c.t.push_back(st.column_double(1));
    c.theta.push_back(st.column_double(2));
    c.omega.push_back(st.column_double(3));
    c.alpha.push_back(st.column_double(4));
    c.torque.push_back(st.column_double(5));
    if (c.has_command) {
      if (st.is_null(6))
        throw StoreError("capture " + std::to_string(id) + ": sample " +
                         std::to_string(expected) + " has no command value");
      c.command.push_back(st.column_double(6));
    }
    c.flags.push_back(static_cast<std::uint32_t>(st.column_int(7)));
    ++expected;
  }
  tx.commit();

  auto& m = c.metadata;
  m.emplace_back("capture_id", std::to_string(info->id));
  if (!info->knob.empty()) m.emplace_back("knob", one_line(info->knob));
  m.emplace_back("mode", info->mode);
  m.emplace_back("rate_hz", number(info->rate_hz));
  m.emplace_back("source", one_line(info->source));
  m.emplace_back("status", info->status);
  if (info->end_reason) m.emplace_back("end_reason", one_line(*info->end_reason));
  m.emplace_back("started_at", info->started_at);
  if (info->finished_at) m.emplace_back("finished_at", *info->finished_at);
  m.emplace_back("sample_count", std::to_string(c.size()));
  m.emplace_back("stimulus", one_line(info->stimulus));
  m.emplace_back("orientation", one_line(info->orientation));
  m.emplace_back("calibration", one_line(info->calibration));
  m.emplace_back("metadata", one_line(info->metadata));
  return c;
}

}  // namespace knoblab::store
