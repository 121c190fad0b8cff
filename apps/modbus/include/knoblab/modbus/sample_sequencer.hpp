// Turns successive reads of the biometrics ring into each 32 Hz sample
// exactly once, in counter order. Polling faster than 32 Hz sees the same
// sample several times (dropped here); a late poll finds several new ones in
// the ring (all delivered); a gap longer than the ring is counted as missed.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "knoblab/modbus/codec.hpp"

namespace knoblab::modbus {

class SampleSequencer {
 public:
  struct Batch {
    std::array<BiometricSample, bio::kRingSize> samples{};
    std::size_t count = 0;
  };

  // New samples of this snapshot, oldest first. The first snapshot yields
  // only its newest sample (older ones predate us); a counter that goes
  // backwards (the box restarted) starts over the same way.
  Batch accept(const BiometricsSnapshot& snapshot);

  bool has_last() const { return has_last_; }
  std::uint32_t last_counter() const { return last_; }
  std::uint64_t missed() const { return missed_; }    // samples gone before we read them
  std::uint64_t restarts() const { return restarts_; }// counter went backwards

 private:
  bool has_last_ = false;
  std::uint32_t last_ = 0;
  std::uint64_t missed_ = 0;
  std::uint64_t restarts_ = 0;
};

}  // namespace knoblab::modbus
