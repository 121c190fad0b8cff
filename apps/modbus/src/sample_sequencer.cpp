#include "knoblab/modbus/sample_sequencer.hpp"

namespace knoblab::modbus {

SampleSequencer::Batch SampleSequencer::accept(const BiometricsSnapshot& snapshot) {
  Batch batch;
  const std::uint32_t latest = snapshot.latest_counter;
  if (latest == 0) return batch;  // the box has not sampled yet
  const BiometricSample& newest = snapshot.ring[latest % bio::kRingSize];

  // Wrap-safe distance (the counter wraps after 4 years at 32 Hz).
  const auto ahead = static_cast<std::int32_t>(latest - last_);
  if (!has_last_ || ahead < 0) {
    if (has_last_) ++restarts_;
    has_last_ = true;
    last_ = latest;
    if (newest.counter == latest) batch.samples[batch.count++] = newest;
    return batch;
  }
  std::uint32_t first = last_ + 1;
  if (static_cast<std::uint32_t>(ahead) > bio::kRingSize) {  // overwritten before we read them
    missed_ += static_cast<std::uint32_t>(ahead) - bio::kRingSize;
    first = latest - bio::kRingSize + 1;
  }
  for (std::uint32_t c = first; c != latest + 1; ++c) {
    const BiometricSample& r = snapshot.ring[c % bio::kRingSize];
    if (r.counter != c) {  // not (yet) a consistent record: count it gone

      ++missed_;
      continue;
    }
    batch.samples[batch.count++] = r;
  }
  last_ = latest;
  return batch;
}

}  // namespace knoblab::modbus
