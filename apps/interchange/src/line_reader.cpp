#include "line_reader.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "knoblab/interchange/csv.hpp"

namespace knoblab::interchange::detail {

namespace {
// Tab is allowed (whitespace; a tab delimiter gets its own message later);
// '\r' is checked once the line is complete.
bool is_control(unsigned char c) { return (c < 0x20 && c != '\t' && c != '\r') || c == 0x7f; }
}  // namespace

bool LineReader::refill() {
  if (!in_.good()) return false;
  in_.read(buf_.data(), static_cast<std::streamsize>(buf_.size()));
  pos_ = 0;
  end_ = static_cast<std::size_t>(in_.gcount());
  if (in_.bad()) throw CsvError(source_, line_ + 1, 0, "read error");
  return end_ > 0;
}

bool LineReader::next(std::string& line) {
  line.clear();
  bool any = false;
  for (;;) {
    if (pos_ == end_ && !refill()) {
      if (!any) return false;
      break;  // last line without '\n'
    }
    if (!any) ++line_;
    any = true;
    const char* seg = buf_.data() + pos_;
    const std::size_t avail = end_ - pos_;
    const void* nl = std::memchr(seg, '\n', avail);
    const std::size_t len =
        nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - seg) : avail;
    for (std::size_t i = 0; i < len; ++i)
      if (is_control(static_cast<unsigned char>(seg[i])))
        fail_control(line, seg, i, static_cast<unsigned char>(seg[i]));
    // +1: room for the '\r' of a CRLF line end.
    if (line.size() + len > kMaxLineBytes + 1)
      throw CsvError(source_, line_, 0,
                     "line longer than " + std::to_string(kMaxLineBytes) +
                         " bytes (binary or corrupt file, not a knoblab CSV?)");
    line.append(seg, len);
    pos_ += len;
    if (nl) {
      ++pos_;
      break;
    }
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.size() > kMaxLineBytes)
    throw CsvError(source_, line_, 0,
                   "line longer than " + std::to_string(kMaxLineBytes) + " bytes");
  if (line.find('\r') != std::string::npos)
    throw CsvError(source_, line_, 0, "carriage return inside a line (old Mac line endings?)");
  return true;
}

void LineReader::fail_control(const std::string& line, const char* seg, std::size_t at,
                              unsigned char byte) const {
  // Report the field the byte sits in, like every other error.
  const std::size_t commas = static_cast<std::size_t>(std::count(line.begin(), line.end(), ',') +
                                                      std::count(seg, seg + at, ','));
  char hex[8];
  std::snprintf(hex, sizeof hex, "0x%02x", byte);
  throw CsvError(source_, line_, commas + 1,
                 std::string("control byte ") + hex + " (binary data, not a CSV file?)");
}

}  // namespace knoblab::interchange::detail
