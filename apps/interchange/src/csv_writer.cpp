// CSV writing: shortest round-trip numbers, and an atomic replace on disk.
#include <algorithm>
#include <charconv>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "knoblab/interchange/atomic_file.hpp"
#include "knoblab/interchange/csv.hpp"

namespace knoblab::interchange {

namespace {

bool has_control(std::string_view s) {
  for (char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  return false;
}

// Refuse metadata that would read back differently (or break the format).
void check_metadata(const std::vector<std::pair<std::string, std::string>>& metadata) {
  for (const auto& [key, value] : metadata) {
    const auto bad = [&](const char* why) {
      throw std::invalid_argument("metadata '" + key + "' cannot be written: " + why);
    };
    if (has_control(key) || has_control(value)) bad("contains a line break or control character");
    if (key.find(':') != std::string::npos) bad("key contains ':'");
    if (key.empty() && value.find(':') != std::string::npos)
      bad("a free comment (empty key) must not contain ':'");
    if (key == kKindKey) bad("the kind line is the writer's to write");
  }
}

}  // namespace

void write_csv(const Capture& c, std::ostream& out) {
  validate(c);
  check_metadata(c.metadata);
  for (const auto& [key, value] : c.metadata)
    out << "# " << (key.empty() ? value : key + ": " + value) << '\n';

  // Derived ω/α are left out, as they came in: read back, they are derived
  // again (the same values) and still known as derived, so the fit takes
  // α from the encoder rather than from a column that only looks measured.
  const std::vector<double>* all[] = {&c.t, &c.theta, &c.omega, &c.alpha, &c.torque, &c.command};
  const bool keep[] = {true, true, !c.omega_derived, !c.alpha_derived, true, c.has_command};
  const std::vector<double>* cols[6];
  std::size_t ncols = 0;
  for (std::size_t j = 0; j < 6; ++j) {
    if (!keep[j]) continue;
    out << (ncols ? "," : "") << kChannelNames[j];
    cols[ncols++] = all[j];
  }
  // Flags only when there is something to say: a capture without any is
  // the same capture without the column, and files stay as they were.
  const bool flags = std::any_of(c.flags.begin(), c.flags.end(), [](std::uint32_t f) { return f != 0; });
  if (flags) out << (ncols ? "," : "") << kFlagsColumn;
  out << '\n';

  // 6 fields × at most 24 chars each for a shortest-form double, and flags.
  char row[7 * 32];
  for (std::size_t i = 0; i < c.size(); ++i) {
    char* p = row;
    for (std::size_t j = 0; j < ncols; ++j) {
      if (j) *p++ = ',';
      p = std::to_chars(p, row + sizeof row, (*cols[j])[i]).ptr;
    }
    if (flags) {
      *p++ = ',';
      p = std::to_chars(p, row + sizeof row, c.flags[i]).ptr;
    }
    *p++ = '\n';
    out.write(row, p - row);
  }
  out.flush();
  if (!out) throw std::system_error(std::make_error_code(std::errc::io_error), "write_csv");
}

void write_csv(const Capture& c, const std::filesystem::path& path) {
  // Validate first so a bad capture never even creates the temp file.
  validate(c);
  check_metadata(c.metadata);

  write_file_atomically(path, [&](std::ostream& out) { write_csv(c, out); });
}

void write_static_map(const StaticMap& m, std::ostream& out) {
  validate(m);
  check_metadata(m.metadata);
  out << "# " << kKindKey << ": " << kStaticMapKind << '\n';
  for (const auto& [key, value] : m.metadata) out << "# " << (key.empty() ? value : key + ": " + value) << '\n';
  out << "theta,torque\n";
  char row[2 * 32];
  for (std::size_t i = 0; i < m.size(); ++i) {
    char* p = std::to_chars(row, row + sizeof row, m.theta[i]).ptr;
    *p++ = ',';
    p = std::to_chars(p, row + sizeof row, m.torque[i]).ptr;
    *p++ = '\n';
    out.write(row, p - row);
  }
  out.flush();
  if (!out) throw std::system_error(std::make_error_code(std::errc::io_error), "write_static_map");
}

void write_static_map(const StaticMap& m, const std::filesystem::path& path) {
  validate(m);
  check_metadata(m.metadata);
  write_file_atomically(path, [&](std::ostream& out) { write_static_map(m, out); });
}

}  // namespace knoblab::interchange
