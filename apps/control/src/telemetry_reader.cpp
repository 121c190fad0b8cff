#include "knoblab/control/telemetry_reader.hpp"

#include <stdexcept>

#include "knoblab/control/telemetry_layout.hpp"
#include "shm_region.hpp"

namespace knoblab::control {

using namespace telemetry;

TelemetryReader::TelemetryReader(const std::string& shm_name, Start start)
    : region_(std::make_unique<detail::ShmRegion>(detail::ShmRegion::open_read_only(shm_name))) {
  const auto fail = [&](const std::string& why) {
    throw std::runtime_error("telemetry shm " + shm_name + ": " + why);
  };
  if (region_->size() < kSlotsOffset) fail("too small for a header");
  const auto* base = static_cast<const unsigned char*>(region_->data());
  header_ = reinterpret_cast<const Header*>(base);
  if (header_->magic.load(std::memory_order_acquire) != kMagic) fail("not a knoblab telemetry ring (or not initialised yet)");
  if (header_->layout_version != kLayoutVersion)
    fail("layout version " + std::to_string(header_->layout_version) + ", this reader knows " +
         std::to_string(kLayoutVersion));
  if (header_->record_size != sizeof(TelemetryRecord) || header_->slot_size != sizeof(Slot))
    fail("record/slot size differs from this build");
  const std::uint64_t cap = header_->capacity;
  if (cap < 2 || (cap & (cap - 1)) != 0) fail("capacity is not a power of two");
  if (region_->size() < region_size(cap)) fail("smaller than its capacity says");
  slots_ = reinterpret_cast<const Slot*>(base + kSlotsOffset);
  mask_ = cap - 1;
  const std::uint64_t head = header_->head.load(std::memory_order_acquire);
  cursor_ = start == Start::newest ? head : (head > cap ? head - cap : 0);
}

TelemetryReader::~TelemetryReader() = default;
TelemetryReader::TelemetryReader(TelemetryReader&&) noexcept = default;
TelemetryReader& TelemetryReader::operator=(TelemetryReader&&) noexcept = default;

std::uint32_t TelemetryReader::decimation() const noexcept { return header_->decimation; }

double TelemetryReader::record_rate_hz() const noexcept { return header_->loop_rate_hz / header_->decimation; }

bool TelemetryReader::writer_closed() const noexcept {
  return header_->writer_closed.load(std::memory_order_acquire) != 0;
}

bool TelemetryReader::copy(std::uint64_t n, TelemetryRecord& out) const noexcept {
  const Slot& slot = slots_[n & mask_];
  const std::uint64_t expected = 2 * n + 2;
  if (slot.seq.load(std::memory_order_acquire) != expected) return false;  // already overwritten
  out = load_record(slot);
  std::atomic_thread_fence(std::memory_order_acquire);
  return slot.seq.load(std::memory_order_relaxed) == expected;  // else torn: overwritten meanwhile
}

// Lapped: jump to half a ring behind the writer, so it cannot lap us again
// right away, and count what we jumped over.
void TelemetryReader::skip_ahead(std::uint64_t head) noexcept {
  const std::uint64_t target = head - (mask_ + 1) / 2;
  if (target > cursor_) {
    lost_total_ += target - cursor_;
    cursor_ = target;
  }
}

TelemetryReader::Result TelemetryReader::read(std::span<TelemetryRecord> out) noexcept {
  Result result;
  const std::uint64_t before = lost_total_;
  std::uint64_t head = header_->head.load(std::memory_order_acquire);
  if (head < cursor_) cursor_ = head;  // cannot happen with one writer; stay sane anyway
  if (head - cursor_ > mask_ + 1) skip_ahead(head);
  result.first_sequence = cursor_;
  while (result.count < out.size() && cursor_ < head) {
    if (!copy(cursor_, out[result.count])) {
      // Lapped while reading. Return the contiguous run we have; if none,
      // skip ahead and start a new run.
      if (result.count > 0) break;
      head = header_->head.load(std::memory_order_acquire);
      skip_ahead(head > cursor_ + mask_ + 1 ? head : cursor_ + mask_ + 1);
      result.first_sequence = cursor_;
      continue;
    }
    ++result.count;
    ++cursor_;
  }
  result.lost = lost_total_ - before;
  return result;
}

}  // namespace knoblab::control
