#include "knoblab/fit/axis_units.hpp"

#include <array>
#include <cstdio>
#include <numbers>

namespace knoblab::fit {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = 180.0 / kPi;

std::string number(double v, const char* format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

constexpr AxisUnits kRotary{
    .axis = Axis::Rotary,
    .name = "rotary",
    .effort = "torque",
    .travel = "angle",
    .mass = "inertia",
    .moves = "turns",
    .moving = "turning",
    .twist = "twist",
    .theta = "θ",
    .theta_dot = "θ̇",
    .omega = "ω",
    .alpha = "θ̈",
    .tau = "τ",
    .position = {.scale = kDeg, .text = "°", .label = "deg", .column = "deg", .glued = true},
    .fine_position = {.scale = 1e3, .text = "mrad"},
    .parameter_position = {.scale = 1.0, .text = "rad"},
    .speed = {.scale = 1.0, .text = "rad/s"},
    .plot_speed = {.scale = kDeg, .text = "deg/s", .column = "deg_per_s"},
    .torque = {.scale = 1e3, .text = "mN·m", .column = "mNm"},
    .stiffness = {.scale = 1e3, .text = "mN·m/rad"},
    .cubic_stiffness = {.scale = 1e3, .text = "mN·m/rad³"},
    .coupling_stiffness = {.scale = 1.0, .text = "N·m/rad"},
    .damping = {.scale = 1e3, .text = "mN·m/(rad/s)"},
    .inertia = {.scale = 1e3, .text = "mN·m/(rad/s²)"},
    // Cycles per revolution: 2π / period.
    .cycle = {.frequency = true, .scale = 2 * kPi, .text = "cycles/rev", .words = "cycles per revolution"},
};

constexpr AxisUnits kLinear{
    .axis = Axis::Linear,
    .name = "linear",
    .effort = "force",
    .travel = "position",
    .mass = "mass",
    .moves = "moves",
    .moving = "moving",
    .twist = "stretch",
    .theta = "x",
    .theta_dot = "v",
    .omega = "v",
    .alpha = "a",
    .tau = "F",
    .position = {.scale = 1e3, .text = "mm"},
    .fine_position = {.scale = 1e6, .text = "µm", .column = "um"},
    .parameter_position = {.scale = 1e3, .text = "mm"},
    .speed = {.scale = 1e3, .text = "mm/s", .column = "mm_per_s"},
    .plot_speed = {.scale = 1e3, .text = "mm/s", .column = "mm_per_s"},
    .torque = {.scale = 1.0, .text = "N"},
    .stiffness = {.scale = 1.0, .text = "N/m"},
    .cubic_stiffness = {.scale = 1.0, .text = "N/m³"},
    .coupling_stiffness = {.scale = 1.0, .text = "N/m"},
    .damping = {.scale = 1.0, .text = "N·s/m"},
    .inertia = {.scale = 1.0, .text = "kg"},
    .cycle = {.frequency = false, .scale = 1e3, .text = "mm per cycle", .words = "mm per cycle"},
};

// The effect table's units (rotary SI) and how each axis shows them.
struct EffectUnitRow {
  std::string_view si;
  Unit rotary, linear;
};
const std::array<EffectUnitRow, 9> kEffectUnits{{
    {"N·m", {.scale = 1e3, .text = "mN·m"}, {.scale = 1.0, .text = "N"}},
    {"N·m/rad", {.scale = 1e3, .text = "mN·m/rad"}, {.scale = 1.0, .text = "N/m"}},
    {"N·m/rad³", {.scale = 1e3, .text = "mN·m/rad³"}, {.scale = 1.0, .text = "N/m³"}},
    {"N·m·s/rad", {.scale = 1e3, .text = "mN·m·s/rad"}, {.scale = 1.0, .text = "N·s/m"}},
    {"N·m·(s/rad)^p", {.scale = 1e3, .text = "mN·m·(s/rad)^p"}, {.scale = 1.0, .text = "N·(s/m)^p"}},
    {"N·m/s", {.scale = 1e3, .text = "mN·m/s"}, {.scale = 1.0, .text = "N/s"}},
    {"rad", {.scale = 1.0, .text = "rad"}, {.scale = 1e3, .text = "mm"}},
    {"rad/s", {.scale = 1.0, .text = "rad/s"}, {.scale = 1e3, .text = "mm/s"}},
    {"1/rev", {.scale = 1.0, .text = "1/rev"}, {.scale = 1.0, .text = "1/(2π m)"}},
}};

}  // namespace

std::string_view axis_name(Axis a) { return units(a).name; }

std::optional<Axis> parse_axis(std::string_view name) {
  for (const Axis a : {Axis::Rotary, Axis::Linear})
    if (name == axis_name(a)) return a;
  return std::nullopt;
}

std::string Unit::with(double si, const char* format) const {
  return number(scale * si, format) + (glued ? "" : " ") + std::string(text);
}

std::string Periodicity::with(double period_si, const char* format) const {
  return number(of_period(period_si), format) + " " + std::string(text);
}

std::string Periodicity::words_with(double period_si, const char* format) const {
  return number(of_period(period_si), format) + " " + std::string(words);
}

const AxisUnits& units(Axis a) { return a == Axis::Linear ? kLinear : kRotary; }

Unit effect_param_unit(const AxisUnits& u, std::string_view param_name, std::string_view si_unit) {
  if (param_name.starts_with("phase")) return {.scale = 1.0, .text = "rad"};  // of the sine, not a position
  for (const EffectUnitRow& row : kEffectUnits)
    if (row.si == si_unit) return u.axis == Axis::Linear ? row.linear : row.rotary;
  return {.scale = 1.0, .text = si_unit.empty() ? std::string_view("–") : si_unit};
}

}  // namespace knoblab::fit
