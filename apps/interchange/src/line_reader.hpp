// Bounded line reader for the CSV parser: never holds more than one line of
// kMaxLineBytes, and stops at the first byte that cannot be in a text file,
// so a gigabyte of binary garbage is rejected after a few bytes.
#pragma once

#include <array>
#include <cstddef>
#include <istream>
#include <string>

namespace knoblab::interchange::detail {

class LineReader {
 public:
  LineReader(std::istream& in, const std::string& source) : in_(in), source_(source) {}

  // Next line without its "\n" or "\r\n"; false at end of input. Throws
  // CsvError for an over-long line, a control byte or a bare '\r'.
  bool next(std::string& line);

  std::size_t line_number() const { return line_; }  // of the last line returned

 private:
  bool refill();
  [[noreturn]] void fail_control(const std::string& line, const char* seg, std::size_t at,
                                 unsigned char byte) const;

  std::istream& in_;
  const std::string& source_;
  std::array<char, 64 * 1024> buf_{};
  std::size_t pos_ = 0, end_ = 0;
  std::size_t line_ = 0;
};

}  // namespace knoblab::interchange::detail
