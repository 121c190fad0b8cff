// Field-level pieces both CSV readers share: the interchange reader
// (csv_reader.cpp) and the reader of other tools' CSV (mapped_csv_reader.cpp).
#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

namespace knoblab::interchange::detail {

inline std::string_view trim(std::string_view s) {
  const auto ws = [](char c) { return c == ' ' || c == '\t'; };
  while (!s.empty() && ws(s.front())) s.remove_prefix(1);
  while (!s.empty() && ws(s.back())) s.remove_suffix(1);
  return s;
}

// A field for an error message: quoted, shortened, non-printables escaped.
inline std::string quote(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string out = "\"";
  for (std::size_t i = 0; i < s.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
      out += static_cast<char>(c);
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (s.size() > kMax) out += "...";
  return out + "\"";
}

enum class NumError { kNone, kEmpty, kNotANumber, kNotFinite, kOutOfRange, kNotUnsigned };

inline NumError parse_number(std::string_view f, double& out) {
  if (f.empty()) return NumError::kEmpty;
  std::string_view digits = f;
  // from_chars rejects '+'; other writers emit it, so accept one.
  if (digits.front() == '+' && digits.size() > 1 && digits[1] != '-' && digits[1] != '+')
    digits.remove_prefix(1);
  const char* end = digits.data() + digits.size();
  const auto [ptr, ec] = std::from_chars(digits.data(), end, out);
  if (ec == std::errc::result_out_of_range) return NumError::kOutOfRange;
  if (ec != std::errc() || ptr != end) return NumError::kNotANumber;
  if (!std::isfinite(out)) return NumError::kNotFinite;
  return NumError::kNone;
}

}  // namespace knoblab::interchange::detail
