// .npy reader. Layout (numpy.lib.format):
//   "\x93NUMPY", major, minor; header length (u16 LE for 1.0, u32 LE for 2.0
//   and 3.0); the header, a Python dict literal such as
//   {'descr': '<f8', 'fortran_order': False, 'shape': (8192,), }
//   (ASCII in 1.0/2.0, UTF-8 in 3.0), padded with spaces and a '\n'; then
//   the array's bytes, C (row-major) or Fortran (column-major) order.
// The dict is parsed here as data, never evaluated.
#include <bit>
#include <climits>
#include <cstdint>
#include <optional>
#include <string>

#include "knoblab/interchange/npy.hpp"

namespace knoblab::interchange {

namespace {

constexpr std::string_view kMagic{"\x93NUMPY", 6};
// numpy itself refuses headers over 10000 bytes unless told otherwise.
constexpr std::size_t kMaxHeaderBytes = 64 * 1024;

struct Fail {
  const std::string& source;
  [[noreturn]] void operator()(std::size_t at, const std::string& reason) const {
    throw MatError(source, at, reason);
  }
};

// The header's three keys, as the dict gives them.
struct Header {
  std::optional<std::string> descr;
  std::optional<bool> fortran_order;
  std::optional<std::vector<std::size_t>> shape;
};

// A parser for exactly the literals a .npy header holds: a dict of string
// keys to strings, True/False and tuples of non-negative integers. A list
// (a structured dtype's descr) is recognised only to be refused.
class HeaderParser {
 public:
  HeaderParser(std::string_view text, std::size_t offset, Fail fail) : s_(text), base_(offset), fail_(fail) {}

  Header parse() {
    Header h;
    expect('{');
    for (;;) {
      if (peek() == '}') break;
      const std::size_t key_at = pos_;
      const std::string key = string_literal();
      expect(':');
      if (key == "descr") {
        if (peek() == '[')
          fail(pos_, "structured dtype (a list of fields in 'descr'): knoblab reads plain numeric arrays; "
                     "save one field at a time, e.g. np.save(f, a['torque'])");
        h.descr = string_literal();
      } else if (key == "fortran_order") {
        h.fortran_order = boolean();
      } else if (key == "shape") {
        h.shape = tuple();
      } else {
        fail(key_at, "unknown header key '" + key + "' (a .npy header holds descr, fortran_order and shape)");
      }
      if (peek() != ',') break;
      ++pos_;
    }
    expect('}');
    skip_space();
    if (pos_ != s_.size()) fail(pos_, "header: unexpected text after the closing '}'");
    return h;
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& reason) const { fail_(base_ + at, "header: " + reason); }

  void skip_space() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\t' || s_[pos_] == '\r')) ++pos_;
  }
  char peek() {
    skip_space();
    return pos_ < s_.size() ? s_[pos_] : '\0';
  }
  void expect(char c) {
    if (peek() != c) fail(pos_, std::string("expected '") + c + "'" + found());
    ++pos_;
  }
  std::string found() const {
    if (pos_ >= s_.size()) return ", found the end of the header";
    const auto c = static_cast<unsigned char>(s_[pos_]);
    if (c < 0x20 || c >= 0x7f) return ", found byte " + std::to_string(c);
    return std::string(", found '") + s_[pos_] + "'";
  }

  std::string string_literal() {
    const char q = peek();
    if (q != '\'' && q != '"') fail(pos_, "expected a quoted string" + found());
    const std::size_t start = ++pos_;
    while (pos_ < s_.size() && s_[pos_] != q) {
      if (s_[pos_] == '\\') fail(pos_, "escapes in strings are not part of a .npy header");
      ++pos_;
    }
    if (pos_ == s_.size()) fail(start - 1, "unterminated string");
    return std::string(s_.substr(start, pos_++ - start));
  }

  bool boolean() {
    skip_space();
    for (auto [word, value] : {std::pair{std::string_view("True"), true}, std::pair{std::string_view("False"), false}})
      if (s_.substr(pos_).starts_with(word)) {
        pos_ += word.size();
        return value;
      }
    fail(pos_, "'fortran_order': expected True or False" + found());
  }

  std::vector<std::size_t> tuple() {
    std::vector<std::size_t> dims;
    expect('(');
    while (peek() != ')') {
      const std::size_t at = pos_;
      std::size_t d = 0;
      bool any = false;
      while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9') {
        const auto digit = static_cast<std::size_t>(s_[pos_++] - '0');
        if (d > (SIZE_MAX - digit) / 10) fail(at, "'shape': a dimension does not fit in 64 bits");
        d = d * 10 + digit;
        any = true;
      }
      if (!any) fail(at, "'shape': expected a non-negative integer" + found());
      if (pos_ < s_.size() && s_[pos_] == 'L') ++pos_;  // Python 2's long suffix
      dims.push_back(d);
      if (peek() != ',') break;
      ++pos_;
    }
    expect(')');
    return dims;
  }

  std::string_view s_;
  std::size_t base_;
  Fail fail_;
  std::size_t pos_ = 0;
};

struct Dtype {
  char kind = 'f';    // 'f' float, 'i' signed, 'u' unsigned, 'b' bool
  std::size_t width = 8;
  bool big_endian = false;
  MatClass cls = MatClass::kDouble;
};

// '<f8', '>i4', '|u1', '|b1', ...: byte order, kind, width.
Dtype parse_descr(const std::string& d, std::size_t at, const Fail& fail) {
  const std::string quoted = "dtype '" + d + "'";
  if (d.size() < 2) fail(at, "unknown " + quoted);
  const char order = d[0];
  if (order != '<' && order != '>' && order != '|' && order != '=')
    fail(at, quoted + ": expected a byte order '<', '>' or '|' first");
  Dtype t;
  t.big_endian = order == '>' || (order == '=' && std::endian::native == std::endian::big);
  t.kind = d[1];
  switch (t.kind) {
    case 'O':
      fail(at, "object array (" + quoted + "): its data is a Python pickle, which knoblab never loads; "
               "save a numeric array, e.g. np.save(f, np.asarray(x, dtype=float))");
    case 'c':
      fail(at, "complex array (" + quoted + "): save the real part, e.g. np.save(f, x.real)");
    case 'S': case 'U': case 'a': case 'V': case 'M': case 'm':
      fail(at, quoted + " holds text, raw bytes or dates, not numbers");
    default:
      break;
  }
  static constexpr std::pair<std::string_view, MatClass> kTypes[] = {
      {"f8", MatClass::kDouble}, {"f4", MatClass::kSingle}, {"i1", MatClass::kInt8},   {"u1", MatClass::kUInt8},
      {"i2", MatClass::kInt16},  {"u2", MatClass::kUInt16}, {"i4", MatClass::kInt32},  {"u4", MatClass::kUInt32},
      {"i8", MatClass::kInt64},  {"u8", MatClass::kUInt64}, {"b1", MatClass::kUInt8}};
  for (auto [code, cls] : kTypes)
    if (d.substr(1) == code) {
      t.cls = cls;
      t.width = static_cast<std::size_t>(code[1] - '0');
      return t;
    }
  fail(at, "unsupported " + quoted + " (knoblab reads float64, float32, int8 to int64, uint8 to uint64 and bool)");
}

double load(std::string_view bytes, std::size_t at, const Dtype& t) {
  std::uint64_t u = 0;
  for (std::size_t i = 0; i < t.width; ++i) {
    const auto byte = static_cast<unsigned char>(bytes[at + (t.big_endian ? i : t.width - 1 - i)]);
    u = (u << 8) | byte;
  }
  switch (t.kind) {
    case 'f': return t.width == 8 ? std::bit_cast<double>(u) : std::bit_cast<float>(static_cast<std::uint32_t>(u));
    case 'i': {
      const unsigned shift = static_cast<unsigned>(64 - 8 * t.width);  // sign-extend from the top bit
      return static_cast<double>(static_cast<std::int64_t>(u << shift) >> shift);
    }
    case 'b': return u != 0 ? 1.0 : 0.0;
    default: return static_cast<double>(u);
  }
}

std::string shape_text(const std::vector<std::size_t>& dims) {
  std::string s = "(";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + (dims.size() == 1 ? ",)" : ")");
}

}  // namespace

MatArray parse_npy(std::string_view bytes, std::string_view source_name, const MatLimits& limits) {
  const std::string source(source_name);
  const Fail fail{source};
  if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x80 && bytes[1] >= 2 && bytes[1] <= 5)
    throw MatError(source, 0, "a Python pickle, not a NumPy array file: knoblab never loads pickles; "
                              "save the data with np.save(f, numeric_array)", true);
  if (!bytes.starts_with(kMagic))
    throw MatError(source, 0, "not a .npy file: it does not start with \"\\x93NUMPY\"", true);
  if (bytes.size() < 10) fail(bytes.size(), "truncated: the .npy preamble needs 10 bytes, the file has " +
                                                std::to_string(bytes.size()));
  const auto major = static_cast<unsigned char>(bytes[6]), minor = static_cast<unsigned char>(bytes[7]);
  if (major < 1 || major > 3 || minor != 0)
    fail(6, "unsupported .npy format version " + std::to_string(major) + "." + std::to_string(minor) +
                " (knoblab reads 1.0, 2.0 and 3.0)");
  const std::size_t len_bytes = major == 1 ? 2 : 4;
  const std::size_t header_at = 8 + len_bytes;
  if (bytes.size() < header_at) fail(8, "truncated: no room for the header length");
  std::size_t header_len = 0;
  for (std::size_t i = 0; i < len_bytes; ++i)
    header_len |= static_cast<std::size_t>(static_cast<unsigned char>(bytes[8 + i])) << (8 * i);
  if (header_len > kMaxHeaderBytes)
    fail(8, "header of " + std::to_string(header_len) + " bytes is over the " + std::to_string(kMaxHeaderBytes) +
                "-byte limit");
  if (bytes.size() - header_at < header_len)
    fail(8, "truncated: the header claims " + std::to_string(header_len) + " bytes, " +
                std::to_string(bytes.size() - header_at) + " follow");
  const std::string_view text = bytes.substr(header_at, header_len);
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && c != '\n' && c != '\t' && c != '\r') || (c >= 0x80 && major < 3))
      fail(header_at + i, "header: byte " + std::to_string(c) + " cannot be in a version " +
                              std::to_string(major) + ".0 header");
  }
  const Header h = HeaderParser(text, header_at, fail).parse();
  if (!h.descr || !h.fortran_order || !h.shape)
    fail(header_at, std::string("header: missing key '") + (!h.descr ? "descr" : !h.fortran_order ? "fortran_order" : "shape") + "'");
  const Dtype type = parse_descr(*h.descr, header_at, fail);
  const std::vector<std::size_t>& shape = *h.shape;
  if (shape.size() > 2)
    fail(header_at, "array of shape " + shape_text(shape) + ": knoblab reads 1-D and 2-D arrays");

  MatArray a;
  a.cls = type.cls;
  a.logical = type.kind == 'b';
  a.dims = shape.size() == 2 ? shape : std::vector<std::size_t>{1, shape.empty() ? 1 : shape[0]};
  std::size_t n = 1;
  for (std::size_t d : shape) {
    if (d != 0 && n > SIZE_MAX / d) fail(header_at, "shape " + shape_text(shape) + " overflows 64 bits");
    n *= d;
  }
  const std::size_t data_at = header_at + header_len;
  const std::size_t present = bytes.size() - data_at;
  if (n > present / type.width)
    fail(data_at, "truncated: shape " + shape_text(shape) + " of " + std::to_string(type.width) +
                      "-byte values needs " + (n > SIZE_MAX / type.width ? std::string("more than 2^64") : std::to_string(n * type.width)) +
                      " bytes, the file holds " + std::to_string(present) + " after its header");
  if (present != n * type.width)
    fail(data_at + n * type.width, std::to_string(present - n * type.width) +
                                       " bytes follow the array's data (several arrays saved into one file?)");
  if (n * sizeof(double) > limits.max_inflated_bytes)
    fail(header_at, "array of " + std::to_string(n) + " values is over the " +
                        std::to_string(limits.max_inflated_bytes) + "-byte limit");

  // MatArray is column-major: element (r, c) of an R x C array at c*R + r.
  a.values.resize(n);
  const std::size_t rows = a.dims[0], cols = a.dims[1];
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t dst = *h.fortran_order || rows == 1 || cols == 1 ? i : (i % cols) * rows + i / cols;
    a.values[dst] = load(bytes, data_at + i * type.width, type);
  }
  return a;
}

}  // namespace knoblab::interchange
