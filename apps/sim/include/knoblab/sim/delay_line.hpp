// A signal read back a fixed time late: the torque channel's pipeline delay
// (TorqueSensorParams::delay). What is pushed at arbitrary, non-decreasing
// times is resampled on a fixed grid (linear interpolation) so the storage
// depends only on delay / grid step, whatever substep the plant takes; reads
// interpolate between grid points. The constructor allocates; push, read and
// reset do not.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace knoblab::sim {

class DelayLine {
 public:
  DelayLine() = default;
  // delay ≥ 0 and grid step > 0, s. Allocates ⌈delay/step⌉ + 3 slots.
  DelayLine(double delay, double step)
      : delay_(delay), step_(step), buf_(static_cast<std::size_t>(std::ceil(delay / step)) + 3) {}

  bool active() const { return delay_ > 0.0; }

  // The whole history holds `value` up to time t.
  void reset(double t, double value) {
    std::fill(buf_.begin(), buf_.end(), value);
    head_ = 0;
    t_head_ = t_last_ = t;
    v_last_ = value;
  }

  void push(double t, double value) {
    if (buf_.empty()) return;
    const double span = t - t_last_;
    while (t_head_ + step_ <= t) {
      t_head_ += step_;
      const double f = span > 0.0 ? (t_head_ - t_last_) / span : 1.0;
      head_ = head_ + 1 == buf_.size() ? 0 : head_ + 1;
      buf_[head_] = v_last_ + f * (value - v_last_);
    }
    t_last_ = t;
    v_last_ = value;
  }

  // The value pushed at t − delay (the oldest held before the history).
  double read(double t) const {
    if (buf_.empty()) return v_last_;
    const double s = t - delay_;
    if (s >= t_last_) return v_last_;
    if (s >= t_head_) {  // between the newest grid point and the last push
      const double span = t_last_ - t_head_;
      return span > 0.0 ? at(0) + (s - t_head_) / span * (v_last_ - at(0)) : v_last_;
    }
    const double back = (t_head_ - s) / step_;
    const double top = static_cast<double>(buf_.size() - 2);
    if (back >= top) return at(buf_.size() - 1);
    const auto i = static_cast<std::size_t>(back);
    const double f = back - static_cast<double>(i);
    return at(i) + f * (at(i + 1) - at(i));
  }

 private:
  // The grid point `back` steps before the newest.
  double at(std::size_t back) const { return buf_[(head_ + buf_.size() - back) % buf_.size()]; }

  double delay_ = 0.0, step_ = 1.0;
  std::vector<double> buf_;
  std::size_t head_ = 0;
  double t_head_ = 0.0;         // time of the newest grid point
  double t_last_ = 0.0, v_last_ = 0.0;  // the last push
};

}  // namespace knoblab::sim
