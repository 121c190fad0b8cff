#include "knoblab/modbus/fault_spec.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <utility>

#include "knoblab/modbus/register_map.hpp"

namespace knoblab::modbus {
namespace {

std::optional<double> parse_seconds(std::string_view s) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(v) || v < 0.0) return std::nullopt;
  return v;
}

std::optional<unsigned long> parse_number(std::string_view s) {
  int base = 10;
  if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    s.remove_prefix(2);
    base = 16;
  }
  unsigned long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v, base);
  if (s.empty() || ec != std::errc{} || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<int> parse_exception_code(std::string_view s) {
  static constexpr std::array<std::pair<std::string_view, int>, 7> names{{
      {"illegal-function", 1},
      {"illegal-address", 2},
      {"illegal-value", 3},
      {"server-failure", 4},
      {"busy", 6},
      {"gateway-path", 10},
      {"gateway-target", 11},
  }};
  for (const auto& [name, code] : names) {
    if (s == name) return code;
  }
  if (auto n = parse_number(s); n && *n >= 1 && *n <= 11) return static_cast<int>(*n);
  return std::nullopt;
}

std::optional<std::uint16_t> parse_fault_bits(std::string_view s) {
  if (auto n = parse_number(s)) {
    if (*n == 0 || *n > amp::fault::kAll) return std::nullopt;
    return static_cast<std::uint16_t>(*n);
  }
  static constexpr std::array<std::pair<std::string_view, std::uint16_t>, 7> names{{
      {"over-current", amp::fault::kOverCurrent},
      {"over-temperature", amp::fault::kOverTemperature},
      {"under-voltage", amp::fault::kUnderVoltage},
      {"over-voltage", amp::fault::kOverVoltage},
      {"motor-short", amp::fault::kMotorShort},
      {"feedback", amp::fault::kFeedback},
      {"internal", amp::fault::kInternal},
  }};
  std::uint16_t bits = 0;
  while (!s.empty()) {
    const auto plus = s.find('+');
    const std::string_view name = s.substr(0, plus);
    bool found = false;
    for (const auto& [n, bit] : names) {
      if (n == name) {
        bits = static_cast<std::uint16_t>(bits | bit);
        found = true;
      }
    }
    if (!found) return std::nullopt;
    s = plus == std::string_view::npos ? std::string_view{} : s.substr(plus + 1);
  }
  if (bits == 0) return std::nullopt;
  return bits;
}

// "amp" / "bio" / "all" or a unit id (amp 1, bio 2 by convention).
bool parse_target(std::string_view s, FaultAction& a) {
  if (s == "amp" || s == "1") {
    a.to_amplifier = true;
    a.to_biometrics = false;
  } else if (s == "bio" || s == "2") {
    a.to_amplifier = false;
    a.to_biometrics = true;
  } else if (s == "all") {
    a.to_amplifier = a.to_biometrics = true;
  } else {
    return false;
  }
  return true;
}

// Splits "HEAD:TAIL" at the first ':'; tail is empty when there is none.
std::pair<std::string_view, std::string_view> split(std::string_view s, char at) {
  const auto i = s.find(at);
  if (i == std::string_view::npos) return {s, {}};
  return {s.substr(0, i), s.substr(i + 1)};
}

// The optional ":unit" and "@seconds" of exception= and slow=; the problem,
// or nullptr when both (or neither) are good.
const char* parse_unit_and_time(std::string_view unit, std::string_view when, FaultAction& a) {
  if (!unit.empty() && !parse_target(unit, a)) return "unit must be amp, bio, all, 1 or 2";
  if (when.empty()) return nullptr;
  const auto at = parse_seconds(when);
  if (!at) return "expected seconds after '@'";
  a.at_seconds = *at;
  return nullptr;
}

}  // namespace

std::optional<FaultAction> parse_fault(std::string_view spec, std::string* error) {
  auto fail = [&](std::string why) -> std::optional<FaultAction> {
    if (error) *error = "bad --fault '" + std::string(spec) + "': " + std::move(why);
    return std::nullopt;
  };
  const auto [key, value] = split(spec, '=');
  if (value.empty()) return fail("expected KIND=VALUE");
  FaultAction a;

  if (key == "disconnect-after") {
    a.kind = FaultAction::Kind::disconnect;
    const auto [when, refuse] = split(value, ':');
    const auto at = parse_seconds(when);
    if (!at) return fail("expected seconds");
    a.at_seconds = *at;
    if (!refuse.empty()) {
      const auto ms = parse_number(refuse);
      if (!ms || *ms > 65535) return fail("refuse time must be 0..65535 ms");
      a.refuse_for = std::chrono::milliseconds(*ms);
    }
    return a;
  }
  if (key == "exception") {
    a.kind = FaultAction::Kind::exception;
    const auto [what, when] = split(value, '@');
    const auto [code, unit] = split(what, ':');
    const auto c = parse_exception_code(code);
    if (!c) return fail("unknown exception code '" + std::string(code) + "'");
    a.exception_code = *c;
    if (const char* why = parse_unit_and_time(unit, when, a)) return fail(why);
    return a;
  }
  if (key == "slow") {
    a.kind = FaultAction::Kind::slow;
    const auto [what, when] = split(value, '@');
    const auto [delay, unit] = split(what, ':');
    const auto ms = parse_number(delay);
    if (!ms || *ms < 1 || *ms > 65535) return fail("reply delay must be 1..65535 ms");
    a.reply_delay = std::chrono::milliseconds(*ms);
    if (const char* why = parse_unit_and_time(unit, when, a)) return fail(why);
    return a;
  }
  if (key == "hang-after") {
    a.kind = FaultAction::Kind::hang;
    const auto [when, target] = split(value, ':');
    const auto at = parse_seconds(when);
    if (!at) return fail("expected seconds");
    a.at_seconds = *at;
    a.to_amplifier = false;
    if (!target.empty() && !parse_target(target, a)) return fail("target must be bio, amp or all");
    return a;
  }
  if (key == "stale-after") {
    a.kind = FaultAction::Kind::stale;
    const auto [when, target] = split(value, ':');
    const auto at = parse_seconds(when);
    if (!at) return fail("expected seconds");
    a.at_seconds = *at;
    a.to_amplifier = false;
    if (!target.empty() && !parse_target(target, a)) return fail("target must be bio, amp or all");
    return a;
  }
  if (key == "amp-fault-after") {
    a.kind = FaultAction::Kind::amp_fault;
    const auto [when, bits] = split(value, ':');
    const auto at = parse_seconds(when);
    if (!at) return fail("expected seconds");
    a.at_seconds = *at;
    const auto b = parse_fault_bits(bits);
    if (!b) return fail("expected fault bits (number or names joined by '+')");
    a.fault_bits = *b;
    return a;
  }
  return fail("unknown fault kind '" + std::string(key) + "'");
}

}  // namespace knoblab::modbus
