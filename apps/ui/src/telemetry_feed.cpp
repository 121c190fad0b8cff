#include "telemetry_feed.hpp"

#include <exception>

#include "knoblab/control/telemetry_reader.hpp"

namespace knoblab::ui {

namespace {
constexpr int kPollMs = 33;
constexpr std::size_t kChunk = 4096;
}  // namespace

TelemetryFeed::TelemetryFeed(QObject* parent) : QObject(parent), buffer_(kChunk) {
  timer_.setInterval(kPollMs);
  connect(&timer_, &QTimer::timeout, this, &TelemetryFeed::poll);
}

TelemetryFeed::~TelemetryFeed() = default;

void TelemetryFeed::setRing(const QString& name) {
  if (name == ring_) return;
  ring_ = name;
  reader_.reset();
  if (ring_.isEmpty()) timer_.stop();
  else timer_.start();
  emit ringChanged();
  emit liveChanged();
  open();
}

void TelemetryFeed::setSeconds(double s) {
  if (!(s > 0) || s == seconds_) return;
  seconds_ = s;
  emit ringChanged();
}

void TelemetryFeed::clear() {
  records_.clear();
  emit updated();
}

void TelemetryFeed::open() {
  if (ring_.isEmpty() || reader_) return;
  try {
    reader_ = std::make_unique<control::TelemetryReader>(ring_.toStdString());
    emit liveChanged();
  } catch (const std::exception&) {
    // Not there (yet): hapticd creates it at start; tried again next poll.
  }
}

void TelemetryFeed::poll() {
  if (!reader_) {
    open();
    if (!reader_) return;
  }
  if (reader_->writer_closed()) {  // hapticd stopped; its successor makes a new ring
    reader_.reset();
    emit liveChanged();
    return;
  }
  bool any = false;
  for (;;) {
    const auto r = reader_->read(buffer_);
    if (r.count == 0) break;
    records_.insert(records_.end(), buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(r.count));
    any = true;
    if (r.count < buffer_.size()) break;
  }
  if (!any) return;
  const double newest = records_.back().t;
  while (!records_.empty() && records_.front().t < newest - seconds_) records_.pop_front();
  emit updated();
}

}  // namespace knoblab::ui
