// The randomness of a trial plan, spelled out so a plan is the same on every
// standard library and can be re-derived by hand or in another language:
// std::mt19937_64's output sequence is fixed by the C++ standard, but
// std::shuffle and std::uniform_int_distribution are not (each library may
// draw differently), so neither is used.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <string_view>
#include <utility>

namespace knoblab::study {

using Engine = std::mt19937_64;

// FNV-1a, 64-bit, over the bytes of `text`.
std::uint64_t fnv1a64(std::string_view text);

// Steele, Lea and Flood's SplitMix64 finaliser: spreads the bits of nearby
// inputs, so studies whose seeds differ by one get unrelated plans.
std::uint64_t splitmix64(std::uint64_t x);

// The seed of one participant's plan: splitmix64(study_seed XOR fnv1a64(code)).
std::uint64_t participant_seed(std::uint64_t study_seed, std::string_view participant_code);

// A uniform integer in [0, n), n ≥ 1, by rejection: draws below 2^64 mod n
// are refused so that every residue is equally likely, then x mod n.
std::uint64_t uniform_below(Engine& engine, std::uint64_t n);

// Fisher–Yates (Durstenfeld): for i = size−1 down to 1, swap items[i] with
// items[uniform_below(engine, i + 1)]. Draws size−1 numbers (more only on a
// rejection, which for small sizes has probability ~2^-60).
template <typename T>
void fisher_yates(std::span<T> items, Engine& engine) {
  for (std::size_t i = items.size(); i > 1; --i) {
    const auto j = static_cast<std::size_t>(uniform_below(engine, i));
    using std::swap;
    swap(items[i - 1], items[j]);
  }
}

}  // namespace knoblab::study
