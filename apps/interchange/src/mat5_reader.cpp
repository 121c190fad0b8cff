// MAT-file level 5 reader. Layout (MathWorks, "MAT-File Format"):
//   128-byte header: text, subsystem offset, version 0x0100, endian "IM"/"MI";
//   then data elements: tag (type u32, size u32) + data padded to 8 bytes, or
//   a "small" element (size in the tag's upper 16 bits, data in 4 bytes).
//   miMATRIX holds sub-elements: array flags, dims, name, then class data;
//   miCOMPRESSED holds a zlib stream of further elements (not padded).
#include "knoblab/interchange/mat5.hpp"

#include <zlib.h>

#include "file_bytes.hpp"
#include "knoblab/interchange/array_file.hpp"
#include "mat73_reader.hpp"

#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>
#include <system_error>

namespace knoblab::interchange {

namespace {

enum MiType : std::uint32_t {
  miINT8 = 1, miUINT8 = 2, miINT16 = 3, miUINT16 = 4, miINT32 = 5, miUINT32 = 6,
  miSINGLE = 7, miDOUBLE = 9, miINT64 = 12, miUINT64 = 13, miMATRIX = 14,
  miCOMPRESSED = 15, miUTF8 = 16, miUTF16 = 17, miUTF32 = 18,
};

constexpr std::size_t kHeaderBytes = 128;
constexpr std::uint32_t kFlagComplex = 0x0800, kFlagLogical = 0x0200;

// Bytes per element of a numeric data type; 0 for anything else.
std::size_t numeric_width(std::uint32_t type) {
  switch (type) {
    case miINT8: case miUINT8: return 1;
    case miINT16: case miUINT16: return 2;
    case miINT32: case miUINT32: case miSINGLE: return 4;
    case miDOUBLE: case miINT64: case miUINT64: return 8;
    default: return 0;
  }
}

// A byte range being parsed: the file itself, or one inflated compressed
// element (errors then point at that element and the byte inside it).
struct Buffer {
  std::string_view bytes;
  const std::string& source;
  bool big_endian;
  const MatLimits& limits;
  std::size_t& arrays;             // arrays read so far, across buffers
  bool inflated = false;
  std::size_t element_offset = 0;  // file offset of the compressed element

  [[noreturn]] void fail(std::size_t at, const std::string& reason) const {
    if (!inflated) throw MatError(source, at, reason);
    throw MatError(source, element_offset,
                   "in compressed element, inflated byte " + std::to_string(at) + ": " + reason);
  }

  // An unsigned integer of `width` bytes in the file's byte order; in bounds.
  std::uint64_t load(std::size_t at, std::size_t width) const {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < width; ++i) {
      const auto byte = static_cast<unsigned char>(bytes[at + (big_endian ? i : width - 1 - i)]);
      v = (v << 8) | byte;
    }
    return v;
  }
  std::uint32_t u32(std::size_t at) const { return static_cast<std::uint32_t>(load(at, 4)); }

  // One element of a numeric data type, as double.
  double number(std::uint32_t type, std::size_t at) const {
    const std::uint64_t u = load(at, numeric_width(type));
    switch (type) {
      case miINT8: return static_cast<std::int8_t>(u);
      case miUINT8: return static_cast<double>(u);
      case miINT16: return static_cast<std::int16_t>(u);
      case miUINT16: return static_cast<double>(u);
      case miINT32: return static_cast<std::int32_t>(u);
      case miUINT32: return static_cast<double>(u);
      case miSINGLE: return std::bit_cast<float>(static_cast<std::uint32_t>(u));
      case miDOUBLE: return std::bit_cast<double>(u);
      case miINT64: return static_cast<double>(static_cast<std::int64_t>(u));
      default: return static_cast<double>(u);  // miUINT64
    }
  }
};

struct Element {
  std::uint32_t type;
  std::size_t at;    // where the tag starts
  std::size_t data;  // where the data starts
  std::size_t size;  // data bytes, without padding
  std::size_t next;  // where the following element starts
};

// The element tag at `at`, checked to fit before `end`.
Element read_tag(const Buffer& b, std::size_t at, std::size_t end) {
  if (end - at < 8)
    b.fail(at, "truncated: a data element tag needs 8 bytes, " + std::to_string(end - at) + " left");
  const std::uint32_t first = b.u32(at);
  if (first >> 16 != 0) {  // small data element: the data sits in the tag's second half
    const std::size_t size = first >> 16;
    if (size > 4) b.fail(at, "small data element claims " + std::to_string(size) + " bytes (at most 4)");
    return {first & 0xffff, at, at + 4, size, at + 8};
  }
  const std::size_t size = b.u32(at + 4);
  const std::size_t left = end - at - 8;
  if (size > left)
    b.fail(at, "element of " + std::to_string(size) + " bytes runs past the end of its container (" +
                   std::to_string(left) + " bytes left)");
  // Compressed elements are not padded; padding past the container's end is forgiven.
  const std::size_t padded = first == miCOMPRESSED ? size : std::min((size + 7) / 8 * 8, left);
  return {first, at, at + 8, size, at + 8 + padded};
}

const char* class_name(MatClass c) {
  switch (c) {
    case MatClass::kCell: return "cell";
    case MatClass::kStruct: return "struct";
    case MatClass::kObject: return "object";
    case MatClass::kChar: return "char";
    case MatClass::kSparse: return "sparse";
    case MatClass::kDouble: return "double";
    case MatClass::kSingle: return "single";
    case MatClass::kInt8: return "int8";
    case MatClass::kUInt8: return "uint8";
    case MatClass::kInt16: return "int16";
    case MatClass::kUInt16: return "uint16";
    case MatClass::kInt32: return "int32";
    case MatClass::kUInt32: return "uint32";
    case MatClass::kInt64: return "int64";
    case MatClass::kUInt64: return "uint64";
    case MatClass::kFunction: return "function_handle";
    case MatClass::kOpaque: return "opaque";
  }
  return "?";
}

bool numeric_class(MatClass c) { return c >= MatClass::kDouble && c <= MatClass::kUInt64; }

// Product of the dims, or a MatError when it does not fit in size_t.
std::size_t element_count(const Buffer& b, std::size_t at, const std::vector<std::size_t>& dims) {
  std::size_t n = 1;
  for (std::size_t d : dims) {
    if (d != 0 && n > SIZE_MAX / d) b.fail(at, "dimensions overflow: their product does not fit in 64 bits");
    n *= d;
  }
  return n;
}

// The contents of one miMATRIX element, data in [at, end).
MatArray parse_matrix(const Buffer& b, std::size_t at, std::size_t end, std::size_t depth) {
  if (depth > b.limits.max_depth)
    b.fail(at, "arrays nested deeper than " + std::to_string(b.limits.max_depth) + " levels");
  if (++b.arrays > b.limits.max_arrays)
    b.fail(at, "more than " + std::to_string(b.limits.max_arrays) + " arrays (the limit)");
  MatArray a;
  if (at == end) {  // an empty element stands for an empty array
    a.dims = {0, 0};
    return a;
  }
  const Element flags = read_tag(b, at, end);
  if (flags.type != miUINT32 || flags.size != 8)
    b.fail(at, "array flags: expected 8 bytes of miUINT32, found type " + std::to_string(flags.type) +
                   " with " + std::to_string(flags.size) + " bytes");
  const std::uint32_t f = b.u32(flags.data);
  const std::uint32_t cls = f & 0xff;
  if (cls < 1 || cls > 17) b.fail(flags.data, "unknown array class " + std::to_string(cls));
  a.cls = static_cast<MatClass>(cls);
  a.complex = (f & kFlagComplex) != 0;
  a.logical = (f & kFlagLogical) != 0;

  const Element dims = read_tag(b, flags.next, end);
  if (dims.type != miINT32 || dims.size == 0 || dims.size % 4 != 0)
    b.fail(dims.at, "dimensions: expected miINT32 values, found type " + std::to_string(dims.type) +
                        " with " + std::to_string(dims.size) + " bytes");
  for (std::size_t p = dims.data; p < dims.data + dims.size; p += 4) {
    const auto d = static_cast<std::int32_t>(b.u32(p));
    if (d < 0) b.fail(p, "negative dimension " + std::to_string(d));
    a.dims.push_back(static_cast<std::size_t>(d));
  }

  const Element name = read_tag(b, dims.next, end);
  if (name.type != miINT8 && name.type != miUINT8 && name.type != miUTF8)
    b.fail(name.at, "array name: expected miINT8 text, found type " + std::to_string(name.type));
  for (char c : b.bytes.substr(name.data, name.size))
    a.name += (c >= 0x20 && c < 0x7f) ? c : '?';  // names are [A-Za-z0-9_]; keep messages printable

  const std::size_t n = element_count(b, dims.at, a.dims);
  std::size_t pos = name.next;
  if (a.is_cell()) {
    // Every cell is an element of at least 8 bytes: refuse counts the bytes cannot hold.
    if (n > (end - pos) / 8)
      b.fail(dims.at, "cell array of " + std::to_string(n) + " cells, but only " +
                          std::to_string(end - pos) + " bytes hold them");
    for (std::size_t i = 0; i < n; ++i) {
      const Element e = read_tag(b, pos, end);
      if (e.type != miMATRIX)
        b.fail(e.at, "cell " + std::to_string(i) + ": expected miMATRIX, found type " + std::to_string(e.type));
      a.cells.push_back(parse_matrix(b, e.data, e.data + e.size, depth + 1));
      pos = e.next;
    }
    return a;
  }
  if (!numeric_class(a.cls) || a.complex) return a;  // listed, contents not read

  const Element real = read_tag(b, pos, end);
  const std::size_t width = numeric_width(real.type);
  if (width == 0)
    b.fail(real.at, "numeric data: element type " + std::to_string(real.type) + " is not a number type");
  if (real.size % width != 0 || real.size / width != n)
    b.fail(real.at, "dimensions say " + std::to_string(n) + " elements, the data holds " +
                        std::to_string(real.size) + " bytes of " + std::to_string(width) + "-byte values");
  a.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) a.values[i] = b.number(real.type, real.data + i * width);
  return a;
}

// Inflates one miCOMPRESSED element, growing the output in steps so a small
// stream claiming a huge size never costs more than the limit.
std::string inflate_element(const Buffer& b, const Element& e) {
  const std::size_t cap = b.limits.max_inflated_bytes;
  z_stream zs{};
  if (inflateInit(&zs) != Z_OK) b.fail(e.at, "zlib inflateInit failed");
  struct End {
    z_stream* z;
    ~End() { inflateEnd(z); }
  } end_guard{&zs};

  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(b.bytes.data() + e.data));
  zs.avail_in = static_cast<uInt>(e.size);  // an element size is 32 bits
  std::string out(std::min(cap + 1, std::max<std::size_t>(e.size * 4, 64 * 1024)), '\0');
  std::size_t have = 0;
  for (;;) {
    if (have == out.size()) out.resize(std::min(cap + 1, out.size() * 2));
    const std::size_t room = std::min<std::size_t>(out.size() - have, UINT_MAX);
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + have);
    zs.avail_out = static_cast<uInt>(room);
    const int rc = inflate(&zs, Z_NO_FLUSH);
    have += room - zs.avail_out;
    if (have > cap)
      b.fail(e.at, "compressed element inflates to more than " + std::to_string(cap) +
                       " bytes (the limit); refusing it");
    if (rc == Z_STREAM_END) break;
    if (rc == Z_OK || (rc == Z_BUF_ERROR && zs.avail_out == 0)) continue;
    if (rc == Z_BUF_ERROR) b.fail(e.at, "compressed element is truncated: its zlib stream does not end");
    b.fail(e.at, std::string("compressed element is corrupt: zlib says ") + (zs.msg ? zs.msg : "error"));
  }
  out.resize(have);
  return out;
}

// Top-level elements in [at, size): variables, possibly inside compressed elements.
void parse_elements(const Buffer& b, std::size_t at, std::vector<MatArray>& out) {
  while (at < b.bytes.size()) {
    const Element e = read_tag(b, at, b.bytes.size());
    if (e.type == miCOMPRESSED) {
      if (b.inflated) b.fail(e.at, "compressed element inside a compressed element");
      const std::string inflated = inflate_element(b, e);
      const Buffer inner{inflated, b.source, b.big_endian, b.limits, b.arrays, true, e.at};
      parse_elements(inner, 0, out);
    } else if (e.type == miMATRIX) {
      MatArray m = parse_matrix(b, e.data, e.data + e.size, 0);
      if (!m.name.empty()) out.push_back(std::move(m));  // unnamed: MATLAB's subsystem data
    } else {
      b.fail(e.at, "top-level element of type " + std::to_string(e.type) +
                       " (expected miMATRIX 14 or miCOMPRESSED 15)");
    }
    at = e.next;
  }
}

}  // namespace

MatError::MatError(std::string source, std::size_t offset, std::string reason, bool whole_file)
    : std::runtime_error(source + (whole_file ? "" : ": offset " + std::to_string(offset)) + ": " + reason),
      offset_(offset),
      reason_(std::move(reason)) {}

bool MatArray::is_numeric() const { return numeric_class(cls) && !complex; }

std::size_t MatArray::numel() const {
  std::size_t n = dims.empty() ? 0 : 1;
  for (std::size_t d : dims) n *= d;  // checked when read
  return n;
}

std::size_t MatArray::cols() const {
  std::size_t n = 1;
  for (std::size_t i = 1; i < dims.size(); ++i) n *= dims[i];
  return dims.empty() ? 0 : n;
}

double MatArray::at(std::size_t row, std::size_t col) const {
  if (row >= rows() || col >= cols() || values.size() != numel())
    throw std::out_of_range("MatArray::at(" + std::to_string(row) + ", " + std::to_string(col) +
                            ") outside " + describe());
  return values[col * rows() + row];
}

const MatArray& MatArray::cell(std::size_t row, std::size_t col) const {
  if (row >= rows() || col >= cols() || cells.size() != numel())
    throw std::out_of_range("MatArray::cell(" + std::to_string(row) + ", " + std::to_string(col) +
                            ") outside " + describe());
  return cells[col * rows() + row];
}

std::string MatArray::describe() const {
  std::string s;
  for (std::size_t d : dims) s += (s.empty() ? "" : "x") + std::to_string(d);
  const char* type = logical ? "logical" : class_name(cls);
  return s + (complex ? " complex " : " ") + type;
}

std::vector<MatArray> parse_mat(std::string_view bytes, std::string_view source_name,
                                const MatLimits& limits) {
  const std::string source(source_name);
  const auto whole = [&](const std::string& reason) { return MatError(source, 0, reason, true); };
  static constexpr std::string_view kHdf5Signature{"\x89HDF\r\n\x1a\n", 8};
  if (bytes.starts_with("MATLAB 7.3") || (bytes.size() >= 520 && bytes.substr(512, 8) == kHdf5Signature))
    return detail::parse_mat73(bytes, source, limits);
  if (!bytes.starts_with("MATLAB"))
    throw whole("not a MAT v5 file: it does not start with the 'MATLAB 5.0 MAT-file' header text "
                "(MAT v4 files are not supported either)");
  if (bytes.size() < kHeaderBytes)
    throw MatError(source, bytes.size(), "truncated: the header needs 128 bytes, the file has " +
                                             std::to_string(bytes.size()));

  const std::string_view endian = bytes.substr(126, 2);
  if (endian != "IM" && endian != "MI")
    throw MatError(source, 126, "bad endian indicator (expected 'IM' or 'MI')");
  std::size_t arrays = 0;
  const Buffer b{bytes, source, endian == "MI", limits, arrays};
  const auto version = b.load(124, 2);
  if (version == 0x0200) throw whole("the header says MAT v7.3, but no HDF5 data follows it at byte 512");
  if (version != 0x0100) b.fail(124, "unsupported MAT-file version " + std::to_string(version));

  std::vector<MatArray> vars;
  parse_elements(b, kHeaderBytes, vars);
  return vars;
}

std::vector<MatArray> read_mat(const std::filesystem::path& path, const MatLimits& limits) {
  return parse_mat(detail::read_file_bytes(path, limits), path.string(), limits);
}

MatArray read_mat_variable(const std::filesystem::path& path, std::string_view name,
                           const MatLimits& limits) {
  std::vector<MatArray> vars = read_mat(path, limits);
  return take_array(vars, name, path.string());
}

}  // namespace knoblab::interchange
