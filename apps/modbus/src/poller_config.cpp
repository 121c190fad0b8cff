// The rules a PollerConfig must meet before any thread starts.
//
// The timing rules follow from what one unanswered request costs: its thread
// waits out the whole response_timeout, and the good reads on either side of
// it are up to one polling period further apart still. So period +
// response_timeout must stay below the watchdog those reads keep quiet, or a
// single lost answer (a dropped frame, a device busy for a moment) raises it:
// for the amplifier that cuts torque, for the box it reports it lost.
// Devices on one RTU bus share a thread and the line, so each also waits
// out the other's requests; they share one response timeout (one libmodbus
// context), which the same rule then covers.
#include <string>
#include <utility>

#include "knoblab/modbus/poller.hpp"

namespace knoblab::modbus {
namespace {

std::string ms(Millis d) { return std::to_string(d.count()) + " ms"; }

// The first line setting on which two endpoints of one serial bus differ.
const char* line_difference(const ModbusEndpoint& a, const ModbusEndpoint& b) {
  if (a.baud != b.baud) return "baud";
  if (a.parity != b.parity) return "parity";
  if (a.data_bits != b.data_bits) return "data_bits";
  if (a.stop_bits != b.stop_bits) return "stop_bits";
  return nullptr;
}

}  // namespace

std::optional<PollerConfigProblem> validate(const PollerConfig& c) {
  using Problem = PollerConfigProblem;
  if (!c.poll_amplifier && !c.poll_biometrics) return Problem{"", "nothing to poll"};
  for (const auto& [name, e] : {std::pair{"amplifier", &c.amplifier}, std::pair{"biometrics", &c.biometrics}}) {
    if (auto problem = validate(*e)) return Problem{name, describe(*e) + ": " + *problem};
  }
  if (c.amplifier_period.count() <= 0) return Problem{"amplifier_period", "must be positive"};
  if (c.biometrics_period.count() <= 0 || c.biometrics_period > Millis{15})
    return Problem{"biometrics_period", "must be 1..15 ms (>= 64 Hz, twice the box's 32 Hz)"};
  if (c.comms_timeout <= c.amplifier_period) return Problem{"comms_timeout", "must exceed amplifier_period"};
  if (c.stale_periods < 1) return Problem{"stale_periods", "must be >= 1"};
  if (c.backoff_min.count() <= 0 || c.backoff_max < c.backoff_min)
    return Problem{"backoff_min", "bad reconnect backoff: backoff_min must be positive and at most backoff_max"};

  const ModbusEndpoint& amp = c.amplifier;
  const ModbusEndpoint& bio = c.biometrics;
  if (c.poll_amplifier && c.poll_biometrics && transport_key(amp) == transport_key(bio)) {
    if (amp.unit_id == bio.unit_id)
      return Problem{"biometrics.unit_id", "amplifier and biometrics share " + describe(bio) +
                                               ": two devices cannot answer to one unit id"};
    if (const char* setting = line_difference(amp, bio))
      return Problem{std::string("biometrics.") + setting,
                     describe(bio) + " shares the serial line of the amplifier (" + describe(amp) +
                         "): one line has one baud rate, parity and framing"};
    if (amp.response_timeout != bio.response_timeout)
      return Problem{"biometrics.response_timeout",
                     ms(bio.response_timeout) + ", but the amplifier on the same serial line has " +
                         ms(amp.response_timeout) + ": one line has one response timeout"};
  }
  if (c.poll_amplifier && amp.response_timeout + c.amplifier_period >= c.comms_timeout)
    return Problem{"amplifier.response_timeout",
                   ms(amp.response_timeout) + " plus the " + ms(c.amplifier_period) +
                       " amplifier period is not below the " + ms(c.comms_timeout) +
                       " comms timeout: one unanswered request would trip the watchdog and cut torque"};
  if (c.poll_biometrics && bio.response_timeout + c.biometrics_period >= c.biometrics_timeout)
    return Problem{"biometrics.response_timeout",
                   ms(bio.response_timeout) + " plus the " + ms(c.biometrics_period) +
                       " biometrics period is not below the " + ms(c.biometrics_timeout) +
                       " biometrics timeout: one unanswered request would report the box lost"};
  return std::nullopt;
}

}  // namespace knoblab::modbus
