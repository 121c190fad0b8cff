// The DAQ seam (like ros2_control's hardware_interface): the loop calls
// read() → update → write() once per cycle. The sim backend and real boards
// sit behind the same interface, so the loop never knows which it drives.
#pragma once

#include <cstdint>

namespace knoblab::capture {

// Raw readings, in the units the board delivers.
struct DaqInputs {
  std::int64_t encoder_counts = 0;
  double torque_V = 0.0;  // torque-sensor channel at the ADC
  double accel_V = 0.0;   // accelerometer channel at the ADC
};

// What a read or write did, for the loop to act on (as ros2_control's
// return_type): a failed read leaves the last good values in place, so only
// this status tells the supervisor that the angle it sees is frozen.
enum class IoStatus : std::uint8_t { ok, error };

struct DaqOutputs {
  double motor_command_V = 0.0;  // amplifier command (DAC)
  bool amp_enable = false;
};

class Daq {
 public:
  virtual ~Daq() = default;
  // Both are called from the realtime loop: no allocation, no blocking.
  // `error` when any channel failed this call (its last good value stays).
  [[nodiscard]] virtual IoStatus read(DaqInputs& in) = 0;
  [[nodiscard]] virtual IoStatus write(const DaqOutputs& out) = 0;
};

}  // namespace knoblab::capture
