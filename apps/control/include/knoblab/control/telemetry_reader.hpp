// A reader of the telemetry ring (the UI; any number at once). Each reader
// has its own cursor and never writes to the shared memory. If the writer
// laps it, the reader skips ahead and says how many records it lost.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
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

class TelemetryReader {
 public:
  enum class Start { newest, oldest };  // only records from now on, or all still in the ring

  // Maps the ring read-only and checks its header. Throws std::runtime_error
  // (no such object, not initialised yet, other layout version).
  explicit TelemetryReader(const std::string& shm_name, Start start = Start::newest);
  ~TelemetryReader();
  TelemetryReader(TelemetryReader&&) noexcept;
  TelemetryReader& operator=(TelemetryReader&&) noexcept;

  struct Result {
    std::size_t count = 0;            // records written to the front of `out`
    std::uint64_t first_sequence = 0; // sequence of out[0]; the rest follow without gaps
    std::uint64_t lost = 0;           // records skipped (writer lapped us) during this call
  };
  // Copies the next available records, oldest first. Never blocks; count 0
  // means nothing new.
  Result read(std::span<TelemetryRecord> out) noexcept;

  std::uint64_t cursor() const noexcept { return cursor_; }  // sequence of the next record
  std::uint64_t lost_total() const noexcept { return lost_total_; }
  std::uint64_t capacity() const noexcept { return mask_ + 1; }
  std::uint32_t decimation() const noexcept;
  double record_rate_hz() const noexcept;  // loop rate / decimation
  // The daemon shut this ring down; a restarted daemon creates a new one
  // under the same name, so reopen by name to follow it.
  bool writer_closed() const noexcept;

 private:
  bool copy(std::uint64_t sequence, TelemetryRecord& out) const noexcept;
  void skip_ahead(std::uint64_t head) noexcept;

  std::unique_ptr<detail::ShmRegion> region_;
  const telemetry::Header* header_ = nullptr;
  const telemetry::Slot* slots_ = nullptr;
  std::uint64_t mask_ = 0;
  std::uint64_t cursor_ = 0;
  std::uint64_t lost_total_ = 0;
};

}  // namespace knoblab::control
