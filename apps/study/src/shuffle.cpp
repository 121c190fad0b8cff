#include "knoblab/study/shuffle.hpp"

#include <stdexcept>

namespace knoblab::study {

std::uint64_t fnv1a64(std::string_view text) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // offset basis
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;  // FNV prime
  }
  return h;
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t participant_seed(std::uint64_t study_seed, std::string_view participant_code) {
  return splitmix64(study_seed ^ fnv1a64(participant_code));
}

std::uint64_t uniform_below(Engine& engine, std::uint64_t n) {
  if (n == 0) throw std::invalid_argument("uniform_below needs n >= 1");
  // 2^64 mod n, computed in 64 bits: (2^64 − n) mod n.
  const std::uint64_t threshold = (0 - n) % n;
  for (;;) {
    const std::uint64_t x = engine();
    if (x >= threshold) return x % n;
  }
}

}  // namespace knoblab::study
