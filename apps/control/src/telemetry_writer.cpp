#include "knoblab/control/telemetry_writer.hpp"

#include <new>
#include <stdexcept>

#include "group_lookup.hpp"
#include "knoblab/control/telemetry_layout.hpp"
#include "shm_region.hpp"

namespace knoblab::control {

using namespace telemetry;

TelemetryWriter::TelemetryWriter(const TelemetryConfig& config) : decimation_(config.decimation) {
  if (config.capacity < 2 || (config.capacity & (config.capacity - 1)) != 0)
    throw std::runtime_error("telemetry capacity must be a power of two >= 2 (got " +
                             std::to_string(config.capacity) + ")");
  if (config.decimation == 0) throw std::runtime_error("telemetry decimation must be >= 1");
  const auto gid = detail::required_group(config.group, "telemetry shm " + config.shm_name);
  region_ = std::make_unique<detail::ShmRegion>(
      detail::ShmRegion::create(config.shm_name, region_size(config.capacity), 0640, gid));

  auto* base = static_cast<unsigned char*>(region_->data());
  // ftruncate zeroed everything: every slot's seq is 0, which matches no record.
  header_ = ::new (base) Header{};
  slots_ = reinterpret_cast<Slot*>(base + kSlotsOffset);
  mask_ = config.capacity - 1;
  header_->layout_version = kLayoutVersion;
  header_->record_size = sizeof(TelemetryRecord);
  header_->slot_size = sizeof(Slot);
  header_->decimation = config.decimation;
  header_->capacity = config.capacity;
  header_->loop_rate_hz = config.loop_rate_hz;
  header_->head.store(0, std::memory_order_relaxed);
  header_->writer_closed.store(0, std::memory_order_relaxed);
  // Last: a reader that sees the magic sees the fields above.
  header_->magic.store(kMagic, std::memory_order_release);
}

TelemetryWriter::~TelemetryWriter() {
  header_->writer_closed.store(1, std::memory_order_release);
}

void TelemetryWriter::push(const TelemetrySample& s) noexcept {
  if (count_ == 0) {
    torque_min_ = torque_max_ = s.torque;
    faults_ = 0;
  }
  if (s.torque < torque_min_) torque_min_ = s.torque;
  if (s.torque > torque_max_) torque_max_ = s.torque;
  faults_ |= s.fault_bits;
  if (++count_ < decimation_) return;
  count_ = 0;

  const TelemetryRecord r{s.t, s.theta, s.omega, s.torque, torque_min_, torque_max_, s.command, s.mode, faults_};
  const std::uint64_t n = next_++;
  Slot& slot = slots_[n & mask_];
  // Seqlock write: odd while the words change, then the record's even value.
  slot.seq.store(2 * n + 1, std::memory_order_relaxed);
  std::atomic_thread_fence(std::memory_order_release);
  store_record(slot, r);
  slot.seq.store(2 * n + 2, std::memory_order_release);
  header_->head.store(n + 1, std::memory_order_release);
}

}  // namespace knoblab::control
