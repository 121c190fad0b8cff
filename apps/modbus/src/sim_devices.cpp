#include "sim_devices.hpp"

#include <algorithm>
#include <new>
#include <random>
#include <span>
#include <utility>

#include "knoblab/modbus/codec.hpp"

namespace knoblab::modbus {
namespace {

constexpr std::chrono::nanoseconds kSamplePeriod{1'000'000'000 / bio::kRateHz};  // 31.25 ms exactly
constexpr double kMaxAmpStep = 0.1;  // s: after a freeze, do not integrate the gap

modbus_mapping_t* new_mapping(int holding, int input) {
  modbus_mapping_t* m = modbus_mapping_new(0, 0, holding, input);
  if (m == nullptr) throw std::bad_alloc();
  return m;
}

std::span<std::uint16_t> inputs(modbus_mapping_t* m) {
  return {m->tab_input_registers, static_cast<std::size_t>(m->nb_input_registers)};
}

int sanitize_exception(std::uint16_t code) {
  if (code == 0) return 0;
  return code < MODBUS_EXCEPTION_MAX ? int{code} : int{MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE};
}

}  // namespace

SimDevices::SimDevices(const SimConfig& config, Clock::time_point start)
    : config_(config),
      start_(start),
      amp_(new_mapping(amp::kHoldingCount, amp::kInputCount)),
      bio_(new_mapping(0, bio::kInputCount)),
      control_(new_mapping(simctl::kHoldingCount, simctl::kInputCount)),
      bio_model_(config.seed * 2 + 1),
      amp_model_(config.seed * 2 + 2),
      box_clock_offset_ms_(static_cast<std::uint32_t>(std::mt19937_64(config.seed)() % 10'000'000)),
      amp_updated_(start) {
  amp_->tab_registers[amp::kCurrentLimitCommand] =
      static_cast<std::uint16_t>(amp::kContinuousCurrent / amp::kAmpsPerLsb);
  BiometricsSnapshot header;
  header.status = bio::status::kSampling;
  header.rate_hz = bio::kRateHz;
  encode_biometrics_header(header, inputs(bio_));
  control_->tab_input_registers[ident::kMapVersion] = kMapVersion;
  control_->tab_input_registers[ident::kDeviceType] = static_cast<std::uint16_t>(DeviceType::sim_control);
  update_amplifier(start);
}

SimDevices::~SimDevices() {
  modbus_mapping_free(amp_);
  modbus_mapping_free(bio_);
  modbus_mapping_free(control_);
}

SimDevices::Route SimDevices::route(int unit) const {
  const std::uint16_t* ctl = control_->tab_registers;
  using std::chrono::milliseconds;
  if (unit == config_.control_unit) return {control_, 0, false, milliseconds{0}};
  if (unit == config_.amplifier_unit)
    return {amp_, sanitize_exception(ctl[simctl::kAmpException]), (ctl[simctl::kMute] & simctl::kMuteAmplifier) != 0,
            milliseconds{ctl[simctl::kAmpReplyDelay]}};
  if (unit == config_.biometrics_unit)
    return {bio_, sanitize_exception(ctl[simctl::kBioException]), (ctl[simctl::kMute] & simctl::kMuteBiometrics) != 0,
            milliseconds{ctl[simctl::kBioReplyDelay]}};
  return {};
}

double SimDevices::seconds(Clock::time_point t) const {
  return std::chrono::duration<double>(t - start_).count();
}

void SimDevices::advance(Clock::time_point now) {
  update_amplifier(now);
  const auto due = static_cast<std::uint64_t>((now - start_) / kSamplePeriod);
  while (ticks_ < due) tick_biometrics(++ticks_);
  apply_map_versions();
}

// The encoders write the real map version; the control block may claim
// another firmware. Applied after every update, so every answer shows it.
void SimDevices::apply_map_versions() {
  const std::uint16_t* ctl = control_->tab_registers;
  auto version = [](std::uint16_t claimed) { return claimed != 0 ? claimed : kMapVersion; };
  amp_->tab_input_registers[ident::kMapVersion] = version(ctl[simctl::kAmpMapVersion]);
  bio_->tab_input_registers[ident::kMapVersion] = version(ctl[simctl::kBioMapVersion]);
}

void SimDevices::tick_biometrics(std::uint64_t n) {
  if ((control_->tab_registers[simctl::kFreeze] & simctl::kFreezeBiometrics) != 0) return;
  BiometricSample s;
  bio_model_.sample(static_cast<double>(n) / bio::kRateHz, s.emg_corrugator, s.emg_depressor,
                    s.skin_conductance);
  s.counter = ++counter_;
  // The box's own millisecond clock: its boot time is not ours.
  s.box_time_ms = box_clock_offset_ms_ + static_cast<std::uint32_t>(n * 1000 / bio::kRateHz);
  s.flags = bio::status::kSampling;
  encode_biometric_record(s, inputs(bio_));
  BiometricsSnapshot header;
  header.status = bio::status::kSampling;
  header.rate_hz = bio::kRateHz;
  header.latest_counter = counter_;
  encode_biometrics_header(header, inputs(bio_));
}

void SimDevices::apply_amplifier_writes() {
  std::uint16_t* hold = amp_->tab_registers;
  const std::uint16_t present = control_->tab_registers[simctl::kAmpFaultInject] & amp::fault::kAll;
  if (hold[amp::kFaultReset] != 0) {
    latched_faults_ = present;  // a reset clears only faults whose cause has gone
    hold[amp::kFaultReset] = 0;
  }
  latched_faults_ = static_cast<std::uint16_t>(latched_faults_ | present);
  const auto peak_ma = static_cast<std::uint16_t>(amp::kPeakCurrent / amp::kAmpsPerLsb);
  hold[amp::kCurrentLimitCommand] = std::min(hold[amp::kCurrentLimitCommand], peak_ma);
  if (latched_faults_ != 0) hold[amp::kEnableCommand] = 0;  // a fault drops the enable
}

void SimDevices::update_amplifier(Clock::time_point now) {
  if ((control_->tab_registers[simctl::kFreeze] & simctl::kFreezeAmplifier) != 0) return;
  const double dt = std::min(kMaxAmpStep, std::chrono::duration<double>(now - amp_updated_).count());
  amp_updated_ = now;
  apply_amplifier_writes();
  const std::uint16_t* hold = amp_->tab_registers;
  const bool requested = hold[amp::kEnableCommand] == 1;
  const double limit = hold[amp::kCurrentLimitCommand] * amp::kAmpsPerLsb;
  const sim::AmplifierState& st = amp_model_.step(seconds(now), dt, requested && latched_faults_ == 0, limit);

  AmplifierStatus s;
  s.status = static_cast<std::uint16_t>((st.enabled ? amp::status::kEnabled : 0) |
                                        (latched_faults_ != 0 ? amp::status::kFaulted : 0) |
                                        (st.limiting ? amp::status::kCurrentLimiting : 0) |
                                        (requested ? amp::status::kEnableRequested : 0));
  s.faults = latched_faults_;
  s.bus_voltage = st.bus_voltage;
  s.temperature = st.temperature;
  s.current = st.current;
  s.current_limit = limit;
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - start_).count();
  s.heartbeat = static_cast<std::uint16_t>(ms & 0xFFFF);
  encode_amplifier(s, inputs(amp_));
}

void SimDevices::apply_control_writes(Clock::time_point now) {
  std::uint16_t* ctl = control_->tab_registers;
  if (ctl[simctl::kDropConnections] != 0) {
    drop_request_ = std::chrono::milliseconds(ctl[simctl::kDropConnections]);
    ctl[simctl::kDropConnections] = 0;
  }
  if (ctl[simctl::kStimulus] != 0) {
    bio_model_.stimulus(seconds(now));
    ctl[simctl::kStimulus] = 0;
  }
}

void SimDevices::after_request(int unit, Clock::time_point now) {
  if (unit == config_.control_unit) apply_control_writes(now);
  // Writes to the amp (or injected faults) show in the very next read.
  if (unit == config_.control_unit || unit == config_.amplifier_unit) update_amplifier(now);
  apply_map_versions();
}

std::optional<std::chrono::milliseconds> SimDevices::take_drop_request() {
  return std::exchange(drop_request_, std::nullopt);
}

void SimDevices::publish_counters(const SimCounters& c) {
  std::uint16_t* in = control_->tab_input_registers;
  const auto requests = static_cast<std::uint32_t>(c.requests);
  in[simctl::kRequestsServed] = high_word(requests);
  in[simctl::kRequestsServed + 1] = low_word(requests);
  in[simctl::kBadFrames] = static_cast<std::uint16_t>(std::min<std::uint64_t>(c.bad_frames, 0xFFFF));
  in[simctl::kClients] = static_cast<std::uint16_t>(c.clients);
}

}  // namespace knoblab::modbus
