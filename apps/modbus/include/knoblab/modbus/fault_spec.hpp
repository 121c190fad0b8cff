// Scheduled simulator faults, as given on the knoblab-modbus-sim command
// line (--fault SPEC, repeatable):
//
//   disconnect-after=S[:REFUSE_MS]   drop every client at S s, refuse new ones
//                                    for REFUSE_MS (default 1000)
//   exception=CODE[:UNIT][@S]        answer every request to UNIT (amp, bio or
//                                    a number; default both) with exception
//                                    CODE from S s on (default 0). CODE: a
//                                    number 1..11 or server-failure, busy,
//                                    gateway-path, gateway-target,
//                                    illegal-function, illegal-address,
//                                    illegal-value
//   stale-after=S[:bio|amp|all]      freeze values and counters at S s
//                                    (default bio)
//   amp-fault-after=S:BITS           raise amplifier fault bits at S s. BITS: a
//                                    number (0x.. allowed) or names joined by
//                                    '+': over-current, over-temperature,
//                                    under-voltage, over-voltage, motor-short,
//                                    feedback, internal
//   slow=MS[:UNIT][@S]               answer every request to UNIT (amp, bio or
//                                    a number; default both) MS ms late
//                                    (1..65535), from S s on (default 0)
//   hang-after=S[:bio|amp|all]       stop answering at S s, connections left
//                                    open: a hung device (default bio)
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace knoblab::modbus {

struct FaultAction {
  enum class Kind { disconnect, exception, stale, amp_fault, slow, hang };
  Kind kind = Kind::disconnect;
  double at_seconds = 0.0;                  // after SimServer::start()
  std::chrono::milliseconds refuse_for{1000};  // disconnect
  int exception_code = 0;                   // exception
  bool to_amplifier = true;                 // exception, stale, slow, hang: which devices
  bool to_biometrics = true;
  std::uint16_t fault_bits = 0;             // amp_fault
  std::chrono::milliseconds reply_delay{0}; // slow
};

// nullopt and a message in *error on a malformed spec.
std::optional<FaultAction> parse_fault(std::string_view spec, std::string* error);

}  // namespace knoblab::modbus
