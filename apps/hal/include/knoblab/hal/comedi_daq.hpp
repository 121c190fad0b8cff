// capture::Daq on a Comedi board (comedilib). Everything is opened and
// validated at construction — subdevice types, channel counts, ranges, units,
// references — so that read()/write() are only comedi_data_read /
// comedi_data_write (one synchronous ioctl each) plus precomputed linear
// scaling: no allocation, no lookup, no exceptions in the loop.
//
// A failed read keeps the channel's last good value and counts an error; a
// failed write counts an error; both report IoStatus::error, which hapticd's
// supervisor acts on.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "knoblab/capture/daq.hpp"
#include "knoblab/hal/comedi_api.hpp"
#include "knoblab/hal/comedi_config.hpp"
#include "knoblab/hal/scaling.hpp"

namespace knoblab::hal {

class ComediDaq final : public capture::Daq {
 public:
  // Throws std::runtime_error naming the device/subdevice/channel at fault.
  // `api` must outlive the ComediDaq.
  explicit ComediDaq(const ComediDaqConfig& config, ComediApi& api = system_comedi_api());
  // Writes 0 V to the motor command (a DAC holds its last value) and closes.
  ~ComediDaq() override;
  ComediDaq(const ComediDaq&) = delete;
  ComediDaq& operator=(const ComediDaq&) = delete;

  capture::IoStatus read(capture::DaqInputs& in) override;
  // Writes gain·motor_command_V clamped to the AO range; 0 V when the
  // amplifier is disabled or the command is not finite.
  capture::IoStatus write(const capture::DaqOutputs& out) override;

  struct Stats {
    std::uint64_t read_errors = 0;
    std::uint64_t write_errors = 0;
    std::uint64_t clamped_writes = 0;
  };
  Stats stats() const;

  // One line per channel: what was resolved (subdevice, range, bits), for logs.
  const std::string& description() const { return description_; }

 private:
  class Device {
   public:
    Device(ComediApi& api, const std::string& path);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;
    ComediDevice* get() const { return dev_; }
    const std::string& path() const { return path_; }

   private:
    ComediApi& api_;
    std::string path_;
    ComediDevice* dev_;
  };
  struct AnalogIn {
    ComediDevice* dev = nullptr;
    unsigned subdevice = 0, channel = 0, range = 0, aref = 0;
    AdcScale scale;
    double last_V = 0.0;
  };
  struct AnalogOut {
    ComediDevice* dev = nullptr;
    unsigned subdevice = 0, channel = 0, range = 0, aref = 0;
    DacScale scale;
    double gain = 1.0;
  };
  struct Counter {
    ComediDevice* dev = nullptr;
    unsigned subdevice = 0, channel = 0;
    CounterUnwrap unwrap;
    std::int64_t sign = 1;
  };

  bool read_analog(AnalogIn& ch);
  bool write_volts(double volts);

  ComediApi& api_;
  Device board_;
  std::unique_ptr<Device> encoder_board_;  // only when the encoder is on another device
  AnalogIn torque_, accel_;
  AnalogOut motor_;
  Counter encoder_;
  std::string description_;
  std::atomic<std::uint64_t> read_errors_{0}, write_errors_{0}, clamped_writes_{0};
};

}  // namespace knoblab::hal
