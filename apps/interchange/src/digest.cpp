#include "knoblab/interchange/digest.hpp"

#include <openssl/evp.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace knoblab::interchange {

namespace {

// OpenSSL's incremental SHA-256; every call checked, as none should fail.
class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new(), EVP_MD_CTX_free) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1)
      throw std::runtime_error("SHA-256: OpenSSL could not start a digest");
  }
  void update(const void* data, std::size_t size) {
    if (size != 0 && EVP_DigestUpdate(ctx_.get(), data, size) != 1)
      throw std::runtime_error("SHA-256: OpenSSL digest update failed");
  }
  std::string hex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> md{};
    unsigned int n = 0;
    if (EVP_DigestFinal_ex(ctx_.get(), md.data(), &n) != 1 || n != 32)
      throw std::runtime_error("SHA-256: OpenSSL digest failed");
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < n; ++i) {
      out += kHex[md[i] >> 4];
      out += kHex[md[i] & 15];
    }
    return out;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx_;
};

// Little-endian bytes of v appended to `out`.
template <typename T>
void put_le(std::vector<unsigned char>& out, T v) {
  unsigned char b[sizeof v];
  std::memcpy(b, &v, sizeof v);
  if constexpr (std::endian::native == std::endian::big)
    for (std::size_t i = 0; i < sizeof v / 2; ++i) std::swap(b[i], b[sizeof v - 1 - i]);
  out.insert(out.end(), b, b + sizeof v);
}

void put_value(std::vector<unsigned char>& out, double v) {
  put_le(out, std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v));
}

}  // namespace

std::string sha256_hex(std::string_view bytes) {
  Sha256 h;
  h.update(bytes.data(), bytes.size());
  return h.hex();
}

std::string file_sha256(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  Sha256 h;
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    h.update(buf.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw std::runtime_error(path.string() + ": read error");
  return h.hex();
}

std::string samples_sha256(const Capture& c) {
  Sha256 h;
  const std::string head = std::string("knoblab samples v1: t theta omega alpha torque") +
                           (c.has_command ? " command" : "") + " flags\n";
  h.update(head.data(), head.size());
  std::vector<unsigned char> rows;
  rows.reserve(64 * 1024);
  for (std::size_t i = 0; i < c.size(); ++i) {
    for (const double v : {c.t[i], c.theta[i], c.omega[i], c.alpha[i], c.torque[i]}) put_value(rows, v);
    if (c.has_command) put_value(rows, c.command[i]);
    put_le(rows, c.flags.empty() ? std::uint32_t{0} : c.flags[i]);
    if (rows.size() >= 60 * 1024) {
      h.update(rows.data(), rows.size());
      rows.clear();
    }
  }
  h.update(rows.data(), rows.size());
  return h.hex();
}

}  // namespace knoblab::interchange
