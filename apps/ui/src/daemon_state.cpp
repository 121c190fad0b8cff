#include "daemon_state.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::ui {

namespace {

// Shorter than this between readings and the cycle count says little (a
// 1 kHz loop turns 100 times in 0.1 s: 1 % resolution).
constexpr double kMinInterval_s = 0.1;
// Exponential smoothing time constant of the estimate.
constexpr double kSmoothing_s = 1.0;

}  // namespace

std::optional<double> LoopRateMeter::update(std::uint64_t cycles, double seconds) {
  if (!last_ || cycles < last_->cycles || seconds <= last_->seconds) {
    // First reading, or the daemon restarted (its counter went back).
    if (last_ && cycles < last_->cycles) rate_.reset();
    last_ = Reading{cycles, seconds};
    return rate_;
  }
  const double dt = seconds - last_->seconds;
  if (dt < kMinInterval_s) return rate_;
  const double now = static_cast<double>(cycles - last_->cycles) / dt;
  const double w = 1.0 - std::exp(-dt / kSmoothing_s);
  rate_ = rate_ ? *rate_ + w * (now - *rate_) : now;
  last_ = Reading{cycles, seconds};
  return rate_;
}

FaultReading read_faults(const std::vector<std::string>& faults) {
  FaultReading r;
  for (const std::string& f : faults) {
    if (f == "estop") r.estop = true;
    else if (f == "amplifier" || f == "amp_comms") r.amplifier = true;
    else r.others.push_back(f);
  }
  return r;
}

ModbusReading read_modbus(const std::string& status) {
  if (status.empty()) return {true, "–"};
  if (status == "ok") return {true, "off"};
  ModbusReading r{true, ""};
  std::size_t at = 0;
  while (at <= status.size()) {
    const auto bar = std::min(status.find('|', at), status.size());
    std::string flag = status.substr(at, bar - at);
    at = bar + 1;
    if (flag == "running" || flag == "amp-enabled" || flag.empty()) continue;
    for (char& c : flag)
      if (c == '-') c = ' ';
    r.ok = false;
    r.text += (r.text.empty() ? "" : ", ") + flag;
  }
  if (r.ok) r.text = "ok";
  return r;
}

}  // namespace knoblab::ui
