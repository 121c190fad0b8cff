// The simulator's register images (one libmodbus mapping per unit) and the
// device behaviour behind them. Private to knoblab_modbus; used only on the
// SimServer thread (or under its mutex).
#pragma once

#include <modbus.h>

#include <chrono>
#include <cstdint>
#include <optional>

#include "knoblab/modbus/sim_server.hpp"
#include "knoblab/modbus/sim_signals.hpp"

namespace knoblab::modbus {

class SimDevices {
 public:
  using Clock = std::chrono::steady_clock;

  SimDevices(const SimConfig& config, Clock::time_point start);
  ~SimDevices();
  SimDevices(const SimDevices&) = delete;
  SimDevices& operator=(const SimDevices&) = delete;

  struct Route {
    modbus_mapping_t* mapping = nullptr;  // null: no such unit
    int exception = 0;                    // > 0: answer with this exception
    bool mute = false;                    // answer nothing
    std::chrono::milliseconds delay{0};   // hold each reply back this long (a slow device)
  };
  Route route(int unit) const;

  // Biometrics: every 32 Hz tick due by now; amplifier: one update.
  void advance(Clock::time_point now);
  // After a request to unit was answered: act on what it wrote.
  void after_request(int unit, Clock::time_point now);
  // A drop-connections request written to the control unit, once.
  std::optional<std::chrono::milliseconds> take_drop_request();

  void publish_counters(const SimCounters& c);
  std::uint32_t sample_counter() const { return counter_; }
  std::uint16_t& control(std::uint16_t reg) { return control_->tab_registers[reg]; }

 private:
  void update_amplifier(Clock::time_point now);
  void apply_amplifier_writes();
  void apply_control_writes(Clock::time_point now);
  void apply_map_versions();
  void tick_biometrics(std::uint64_t n);
  double seconds(Clock::time_point t) const;

  const SimConfig& config_;
  const Clock::time_point start_;
  modbus_mapping_t* amp_ = nullptr;
  modbus_mapping_t* bio_ = nullptr;
  modbus_mapping_t* control_ = nullptr;

  sim::BiometricsModel bio_model_;
  sim::AmplifierModel amp_model_;
  std::uint64_t ticks_ = 0;       // 32 Hz ticks elapsed
  std::uint32_t counter_ = 0;     // samples taken (frozen ticks do not count)
  std::uint32_t box_clock_offset_ms_;
  Clock::time_point amp_updated_;
  std::uint16_t latched_faults_ = 0;
  std::optional<std::chrono::milliseconds> drop_request_;
};

}  // namespace knoblab::modbus
