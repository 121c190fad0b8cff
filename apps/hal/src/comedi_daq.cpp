#include "knoblab/hal/comedi_daq.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "knoblab/interchange/number_text.hpp"

namespace knoblab::hal {

namespace {

using interchange::shortest;

const char* type_name(int type) {
  switch (type) {
    case 0: return "unused";
    case comedi::kSubdeviceAnalogIn: return "analog-input";
    case comedi::kSubdeviceAnalogOut: return "analog-output";
    case 3: return "digital-input";
    case 4: return "digital-output";
    case 5: return "digital-I/O";
    case comedi::kSubdeviceCounter: return "counter";
    case 7: return "timer";
    default: return "other";
  }
}

constexpr unsigned aref_code(Aref a) {
  switch (a) {
    case Aref::Ground: return comedi::kArefGround;
    case Aref::Common: return comedi::kArefCommon;
    case Aref::Diff: return comedi::kArefDiff;
    case Aref::Other: return comedi::kArefOther;
  }
  return comedi::kArefGround;
}

// The names and SDF_* flags of the four references, indexed by aref code.
constexpr const char* kArefNames[] = {"ground", "common", "diff", "other"};
constexpr int kArefFlags[] = {comedi::kFlagGround, comedi::kFlagCommon, comedi::kFlagDiff, comedi::kFlagOther};

std::string range_text(const ComediRange& r) { return "[" + shortest(r.min) + ", " + shortest(r.max) + "] V"; }

bool near(double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b)); }

// Validation of one channel; every message starts "<role>: <device> …".
class ChannelCheck {
 public:
  ChannelCheck(ComediApi& api, ComediDevice* dev, const std::string& path, const char* role)
      : api_(api), dev_(dev), prefix_(std::string(role) + ": " + path) {}

  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(prefix_ + " " + what); }
  [[noreturn]] void fail_comedi(const std::string& what) const { fail(what + ": " + api_.last_error()); }

  unsigned subdevice(std::optional<unsigned> given, int type) {
    if (!given) {
      const int found = api_.find_subdevice_by_type(dev_, type, 0);
      if (found < 0) fail(std::string("has no ") + type_name(type) + " subdevice");
      subdev_ = static_cast<unsigned>(found);
      return subdev_;
    }
    const int n = api_.n_subdevices(dev_);
    if (n < 0) fail_comedi("cannot count subdevices");
    if (*given >= static_cast<unsigned>(n))
      fail("has " + std::to_string(n) + " subdevices; subdevice " + std::to_string(*given) + " does not exist");
    const int actual = api_.subdevice_type(dev_, *given);
    if (actual != type)
      fail("subdevice " + std::to_string(*given) + " is " + type_name(actual) + ", not " + type_name(type));
    subdev_ = *given;
    return subdev_;
  }

  void channel(unsigned channel) {
    channel_ = channel;
    const int n = api_.n_channels(dev_, subdev_);
    if (n < 0) fail_comedi("subdevice " + std::to_string(subdev_) + ": cannot count channels");
    if (channel >= static_cast<unsigned>(n))
      fail("subdevice " + std::to_string(subdev_) + " has " + std::to_string(n) + " channels; channel " +
           std::to_string(channel) + " does not exist");
  }

  // The range table entry the config asks for, which must be in volts.
  unsigned range(const AnalogChannelConfig& c, ComediRange& out) {
    const int n = api_.n_ranges(dev_, subdev_, channel_);
    if (n <= 0) fail_comedi(at() + ": cannot read the range table");
    std::vector<ComediRange> table(static_cast<std::size_t>(n));
    std::string available;
    for (unsigned i = 0; i < table.size(); ++i) {
      if (!api_.get_range(dev_, subdev_, channel_, i, table[i])) fail_comedi(at() + ": cannot read range " + std::to_string(i));
      available += (i ? ", " : "") + std::to_string(i) + " " + range_text(table[i]);
    }
    unsigned index = c.range.value_or(0);
    if (c.range && index >= table.size())
      fail(at() + " has no range " + std::to_string(index) + " (available: " + available + ")");
    if (c.range_V) {
      index = static_cast<unsigned>(table.size());
      for (unsigned i = 0; i < table.size(); ++i)
        if (near(table[i].min, c.range_V->min_V) && near(table[i].max, c.range_V->max_V)) index = i;
      if (index == table.size())
        fail(at() + " has no range [" + shortest(c.range_V->min_V) + ", " + shortest(c.range_V->max_V) +
             "] V (available: " + available + ")");
    }
    out = table[index];
    if (out.unit & comedi::kRangeExternal)
      fail(at() + " range " + std::to_string(index) + " is relative to an external reference; choose an internal one");
    if ((out.unit & 0xFF) != comedi::kUnitVolt)
      fail(at() + " range " + std::to_string(index) + " is not in volts (unit " + std::to_string(out.unit) + ")");
    if (!(out.min < out.max)) fail(at() + " range " + std::to_string(index) + " is empty: " + range_text(out));
    return index;
  }

  // Only checked when the driver advertises its references at all.
  void aref(unsigned aref) {
    const int flags = api_.subdevice_flags(dev_, subdev_);
    if (flags < 0) fail_comedi("subdevice " + std::to_string(subdev_) + ": cannot read flags");
    std::string supported;
    for (unsigned a = 0; a < 4; ++a)
      if (flags & kArefFlags[a]) supported += (supported.empty() ? "" : ", ") + std::string(kArefNames[a]);
    if (!supported.empty() && !(flags & kArefFlags[aref]))
      fail("subdevice " + std::to_string(subdev_) + " does not support aref " + kArefNames[aref] +
           " (supports: " + supported + ")");
  }

  std::uint32_t maxdata() {
    const std::uint32_t m = api_.maxdata(dev_, subdev_, channel_);
    if (m == 0) fail(at() + " reports maxdata 0");
    return m;
  }

  std::string at() const { return "subdevice " + std::to_string(subdev_) + " channel " + std::to_string(channel_); }
  std::string describe() const { return prefix_ + " " + at(); }

 private:
  ComediApi& api_;
  ComediDevice* dev_;
  std::string prefix_;
  unsigned subdev_ = 0, channel_ = 0;
};

std::string bits_text(std::uint32_t maxdata) {
  return std::to_string(std::bit_width(maxdata)) + "-bit (maxdata " + std::to_string(maxdata) + ")";
}

}  // namespace

ComediDaq::Device::Device(ComediApi& api, const std::string& path) : api_(api), path_(path), dev_(api.open(path.c_str())) {
  if (dev_ == nullptr) throw std::runtime_error("cannot open Comedi device " + path + ": " + api.last_error());
}

ComediDaq::Device::~Device() { api_.close(dev_); }

ComediDaq::ComediDaq(const ComediDaqConfig& config, ComediApi& api) : api_(api), board_(api, config.device) {
  // The motor first: a DAC keeps its last value, perhaps from a crashed run.
  {
    ChannelCheck check(api_, board_.get(), board_.path(), "motor");
    motor_.dev = board_.get();
    motor_.subdevice = check.subdevice(config.motor.subdevice, comedi::kSubdeviceAnalogOut);
    motor_.channel = config.motor.channel;
    check.channel(motor_.channel);
    ComediRange r;
    motor_.range = check.range(config.motor, r);
    motor_.aref = aref_code(config.motor.aref);
    check.aref(motor_.aref);
    const std::uint32_t maxdata = check.maxdata();
    motor_.scale = DacScale::from_range(r.min, r.max, maxdata);
    motor_.gain = config.motor.gain;
    if (!write_volts(0.0)) check.fail_comedi(check.at() + ": writing 0 V failed");
    description_ += check.describe() + ", range " + std::to_string(motor_.range) + " " + range_text(r) + ", aref " +
                    kArefNames[motor_.aref] + ", " + bits_text(maxdata) + ", gain " + shortest(motor_.gain) + "\n";
  }

  const auto setup_input = [&](AnalogIn& in, const AnalogChannelConfig& c, const char* role) {
    ChannelCheck check(api_, board_.get(), board_.path(), role);
    in.dev = board_.get();
    in.subdevice = check.subdevice(c.subdevice, comedi::kSubdeviceAnalogIn);
    in.channel = c.channel;
    check.channel(in.channel);
    ComediRange r;
    in.range = check.range(c, r);
    in.aref = aref_code(c.aref);
    check.aref(in.aref);
    const std::uint32_t maxdata = check.maxdata();
    in.scale = AdcScale::from_range(r.min, r.max, maxdata, c.gain, c.offset_V);
    std::uint32_t raw = 0;
    if (!api_.data_read(in.dev, in.subdevice, in.channel, in.range, in.aref, raw))
      check.fail_comedi(check.at() + ": reading failed");
    in.last_V = in.scale.to_volts(raw);
    description_ += check.describe() + ", range " + std::to_string(in.range) + " " + range_text(r) + ", aref " +
                    kArefNames[in.aref] + ", " + bits_text(maxdata) + "\n";
  };
  setup_input(torque_, config.torque, "torque");
  setup_input(accel_, config.accel, "accel");

  if (!config.encoder.device.empty() && config.encoder.device != config.device)
    encoder_board_ = std::make_unique<Device>(api_, config.encoder.device);
  const Device& enc = encoder_board_ ? *encoder_board_ : board_;
  ChannelCheck check(api_, enc.get(), enc.path(), "encoder");
  encoder_.dev = enc.get();
  encoder_.subdevice = check.subdevice(config.encoder.subdevice, comedi::kSubdeviceCounter);
  encoder_.channel = config.encoder.channel;
  check.channel(encoder_.channel);
  const std::uint32_t maxdata = check.maxdata();
  encoder_.unwrap = CounterUnwrap(maxdata);
  encoder_.sign = config.encoder.sign < 0 ? -1 : 1;
  if (config.encoder.reset_on_open && !api_.reset_counter(encoder_.dev, encoder_.subdevice, encoder_.channel))
    check.fail_comedi(check.at() + ": reset (INSN_CONFIG_RESET) failed");
  std::uint32_t raw = 0;
  if (!api_.data_read(encoder_.dev, encoder_.subdevice, encoder_.channel, 0, 0, raw))
    check.fail_comedi(check.at() + ": reading failed");
  encoder_.unwrap.reset(raw);
  description_ += check.describe() + ", " + bits_text(maxdata) + ", sign " + std::to_string(encoder_.sign) + "\n";
}

ComediDaq::~ComediDaq() { write_volts(0.0); }

bool ComediDaq::read_analog(AnalogIn& ch) {
  std::uint32_t raw = 0;
  if (api_.data_read(ch.dev, ch.subdevice, ch.channel, ch.range, ch.aref, raw)) {
    ch.last_V = ch.scale.to_volts(raw);
    return true;
  }
  read_errors_.fetch_add(1, std::memory_order_relaxed);  // keep the last good value
  return false;
}

capture::IoStatus ComediDaq::read(capture::DaqInputs& in) {
  bool ok = read_analog(torque_);
  ok = read_analog(accel_) && ok;
  in.torque_V = torque_.last_V;
  in.accel_V = accel_.last_V;
  std::uint32_t raw = 0;
  if (api_.data_read(encoder_.dev, encoder_.subdevice, encoder_.channel, 0, 0, raw)) {
    encoder_.unwrap.update(raw);
  } else {
    read_errors_.fetch_add(1, std::memory_order_relaxed);
    ok = false;
  }
  in.encoder_counts = encoder_.sign * encoder_.unwrap.count();
  return ok ? capture::IoStatus::ok : capture::IoStatus::error;
}

capture::IoStatus ComediDaq::write(const capture::DaqOutputs& out) {
  const bool drive = out.amp_enable && std::isfinite(out.motor_command_V);
  const double volts = drive ? motor_.gain * out.motor_command_V : 0.0;
  if (motor_.scale.clamps(volts)) clamped_writes_.fetch_add(1, std::memory_order_relaxed);
  if (write_volts(volts)) return capture::IoStatus::ok;
  write_errors_.fetch_add(1, std::memory_order_relaxed);
  return capture::IoStatus::error;
}

bool ComediDaq::write_volts(double volts) {
  return api_.data_write(motor_.dev, motor_.subdevice, motor_.channel, motor_.range, motor_.aref,
                         motor_.scale.to_code(volts));
}

ComediDaq::Stats ComediDaq::stats() const {
  return {read_errors_.load(std::memory_order_relaxed), write_errors_.load(std::memory_order_relaxed),
          clamped_writes_.load(std::memory_order_relaxed)};
}

}  // namespace knoblab::hal
