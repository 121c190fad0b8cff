// The realtime side of the telemetry ring. Construct it before the loop
// starts (it creates the shared memory); push() from the loop every cycle.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "knoblab/control/telemetry_sample.hpp"

namespace knoblab::control {

namespace telemetry {
struct Header;
struct Slot;
}  // namespace telemetry
namespace detail {
class ShmRegion;
}

struct TelemetryConfig {
  std::string shm_name = "/knoblab-telemetry";
  std::uint32_t capacity = 4096;  // records, a power of two (4 s at 1 kHz)
  std::uint32_t decimation = 10;  // loop cycles per record: 10 kHz → 1 kHz
  double loop_rate_hz = 10000.0;  // recorded in the header for readers
  std::string group;              // group of the shm object (mode 0640); empty keeps
};

class TelemetryWriter {
 public:
  // Creates the shm object (replacing a leftover one). Throws std::runtime_error.
  explicit TelemetryWriter(const TelemetryConfig& config);
  // Marks the ring closed for readers and unlinks the object.
  ~TelemetryWriter();
  TelemetryWriter(const TelemetryWriter&) = delete;
  TelemetryWriter& operator=(const TelemetryWriter&) = delete;

  // One loop cycle. Every `decimation` calls publish one record. No
  // allocation, no locks, no syscalls: a few stores into mapped memory.
  void push(const TelemetrySample& sample) noexcept;

  std::uint64_t records_published() const noexcept { return next_; }

 private:
  std::unique_ptr<detail::ShmRegion> region_;
  telemetry::Header* header_;
  telemetry::Slot* slots_;
  std::uint64_t mask_;
  std::uint32_t decimation_;
  std::uint64_t next_ = 0;  // sequence of the next record

  // the current decimation window
  std::uint32_t count_ = 0;
  double torque_min_ = 0.0, torque_max_ = 0.0;
  std::uint32_t faults_ = 0;
};

}  // namespace knoblab::control
