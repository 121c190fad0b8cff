// Raw DAQ codes ↔ volts and counter unwrapping, precomputed at setup so the
// loop only multiplies and adds.
//   V = min + raw · (max − min) / maxdata        (comedi_to_phys, linear range)
//   raw = round((V − min) · maxdata / (max − min)), V clamped to [min, max]
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace knoblab::hal {

// ADC code → volts, with an optional linear correction applied on top
// (reported = gain · V + offset_V), all folded into two coefficients.
struct AdcScale {
  double base_V = 0.0;
  double V_per_code = 0.0;

  static AdcScale from_range(double min_V, double max_V, std::uint32_t maxdata, double gain = 1.0,
                             double offset_V = 0.0) {
    return {gain * min_V + offset_V, gain * (max_V - min_V) / static_cast<double>(maxdata)};
  }
  double to_volts(std::uint32_t raw) const { return base_V + V_per_code * static_cast<double>(raw); }
};

// Volts → DAC code, clamped to the range (non-finite → the code nearest 0 V).
struct DacScale {
  double min_V = 0.0;
  double max_V = 0.0;
  double codes_per_V = 0.0;
  std::uint32_t maxdata = 0;

  static DacScale from_range(double min, double max, std::uint32_t maxdata) {
    return {min, max, static_cast<double>(maxdata) / (max - min), maxdata};
  }
  bool clamps(double volts) const { return !(volts >= min_V && volts <= max_V); }
  std::uint32_t to_code(double volts) const {
    const double v = std::isfinite(volts) ? std::clamp(volts, min_V, max_V) : std::clamp(0.0, min_V, max_V);
    const double code = std::floor((v - min_V) * codes_per_V + 0.5);
    return static_cast<std::uint32_t>(std::clamp(code, 0.0, static_cast<double>(maxdata)));
  }
};

// A hardware counter of maxdata+1 states (2^24, 2^32, …) → an int64 count
// that keeps going across wrap-around, provided it moves less than half a
// counter period between reads (at 10 kHz a 24-bit counter allows 8.4e10
// counts/s, i.e. 131 000 rev/s at 640 000 CPR).
class CounterUnwrap {
 public:
  explicit CounterUnwrap(std::uint32_t maxdata = 0xFFFFFFFFu)
      : modulus_(static_cast<std::uint64_t>(maxdata) + 1) {}

  // Starts from the raw value read as two's complement in the counter's width
  // (a counter just below zero reads −1, not 2^24 − 1).
  void reset(std::uint32_t raw) {
    last_ = raw % modulus_;
    count_ = last_ >= modulus_ / 2 ? static_cast<std::int64_t>(last_) - static_cast<std::int64_t>(modulus_)
                                   : static_cast<std::int64_t>(last_);
  }
  std::int64_t update(std::uint32_t raw) {
    const std::uint64_t now = raw % modulus_;
    std::uint64_t step = (now + modulus_ - last_) % modulus_;  // forward distance
    last_ = now;
    count_ += step >= modulus_ / 2 ? static_cast<std::int64_t>(step) - static_cast<std::int64_t>(modulus_)
                                   : static_cast<std::int64_t>(step);
    return count_;
  }
  std::int64_t count() const { return count_; }
  std::uint64_t modulus() const { return modulus_; }

 private:
  std::uint64_t modulus_;
  std::uint64_t last_ = 0;
  std::int64_t count_ = 0;
};

}  // namespace knoblab::hal
