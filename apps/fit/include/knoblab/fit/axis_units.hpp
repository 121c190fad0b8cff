// Rotary or linear, and how each quantity is presented at the edges (the
// commands' text, report axes, discovery's sentences). Inside, every
// quantity stays in its channel's SI unit whatever the axis: a linear
// actuator's "angle" channel is a position in m, its "torque" a force in N,
// its ω a speed in m/s, and the model and the fits work in those
// (docs/interchange.md, "axis").
//
//   const AxisUnits& u = units(data.axis);
//   u.torque.with(0.0012)      → "1.2 mN·m" | "0.0012 N"
//   u.position.axis_label()    → "deg" | "mm"
//   u.cycle.words_with(P)      → "17.3 cycles per revolution" | "2.5 mm per cycle"
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace knoblab::fit {

enum class Axis { Rotary, Linear };

std::string_view axis_name(Axis a);  // "rotary", "linear"
std::optional<Axis> parse_axis(std::string_view name);

// One quantity as presented: the factor from SI and the unit's text.
struct Unit {
  double scale = 1.0;      // SI → presented
  std::string_view text{};   // after a number: "mN·m", "°", "N/m"
  std::string_view label{};  // in an axis label, when not `text`: "deg"
  std::string_view column{}; // in a CSV column name: "mNm", "deg_per_s"
  bool glued = false;      // written without a space after the number (°)

  double operator()(double si) const { return scale * si; }
  std::string_view axis_label() const { return label.empty() ? text : label; }
  std::string_view column_suffix() const { return column.empty() ? axis_label() : column; }
  // "1.2 mN·m", "30°": the value presented, with its unit.
  std::string with(double si, const char* format = "%.3g") const;
};

// A periodic effect's repetition over position: as a frequency (cycles per
// revolution) on a rotary axis, as a period (mm per cycle) on a linear one.
struct Periodicity {
  bool frequency = true;   // presented as cycles per unit of travel, else as a period
  double scale = 1.0;      // frequency: scale / period; period: scale · period (period in SI)
  std::string_view text{};   // "cycles/rev", "mm per cycle"
  std::string_view words{};  // "cycles per revolution", "mm per cycle"

  double of_period(double period_si) const { return frequency ? scale / period_si : scale * period_si; }
  std::string with(double period_si, const char* format = "%.3g") const;        // "17.3 cycles/rev"
  std::string words_with(double period_si, const char* format = "%.3g") const;  // "17.3 cycles per revolution"
};

// An axis's presentation: words, symbols and units.
struct AxisUnits {
  Axis axis = Axis::Rotary;
  std::string_view name{};      // "rotary", "linear"
  std::string_view effort{};    // "torque", "force"
  std::string_view travel{};    // "angle", "position": what grows ("grows with angle")
  std::string_view mass{};      // "inertia", "mass"
  std::string_view moves{};     // "turns", "moves" ("the recording turns one way only")
  std::string_view moving{};    // "turning", "moving" ("turning forwards")
  std::string_view twist{};     // "twist", "stretch": a compliant coupling's deflection
  // Symbols: position, its rate in sentences, velocity in figures, acceleration, effort.
  std::string_view theta{}, theta_dot{}, omega{}, alpha{}, tau{};

  Unit position{};            // ° | mm: where an effect acts, report axes
  Unit fine_position{};       // mrad | µm: play, presliding travel, the forward view's error
  Unit parameter_position{};  // rad | mm: Eq. 6's P_pos in the fit's table
  Unit speed{};               // rad/s | mm/s: sentences, the stick band
  Unit plot_speed{};          // deg/s | mm/s: report axes
  Unit torque{};              // mN·m | N
  Unit stiffness{};           // mN·m/rad | N/m
  Unit cubic_stiffness{};     // mN·m/rad³ | N/m³
  Unit coupling_stiffness{};  // N·m/rad | N/m: a coupling is a thousand times stiffer than a spring
  Unit damping{};             // mN·m/(rad/s) | N·s/m
  Unit inertia{};             // mN·m/(rad/s²) | kg
  Periodicity cycle{};        // cycles/rev | mm per cycle
};

const AxisUnits& units(Axis a);

// How this axis presents a parameter the effect table gives in rotary SI
// units ("N·m", "rad/s", "N·m·s/rad", …; model/effect_table.hpp): a
// rotary axis shows torques in mN·m and the rest as given; a linear axis
// reads rad as m and N·m as N, so positions in mm, forces in N, stiffness
// in N/m. A phase ("phase…") stays in rad on either axis. A unit the table
// does not use comes back as given (its text a view of `si_unit`).
Unit effect_param_unit(const AxisUnits& u, std::string_view param_name, std::string_view si_unit);

}  // namespace knoblab::fit
