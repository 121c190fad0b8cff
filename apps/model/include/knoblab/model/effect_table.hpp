// The effect library's one table: each effect's id, what it is, where it
// acts, and its parameters — names (SI, the unit in the suffix), units,
// physical ranges, defaults and which of them give the effect its size.
// `knoblab simulate --effects` parses with it, discrepancy reports its
// findings' parameters under its names, so a finding's params can be given
// back to simulate, and docs/discrepancy.md's effect table is generated from
// it (effect_table_markdown). The torque laws are in effects.hpp.
//
//   const EffectSpec s = parse_effect_spec("stribeck:static_excess_Nm=0.004");
//   s.value("stribeck_velocity_rad_s")   → 1 (the default)
//   effect_from_params("stribeck", finding.params)   (effect_json.hpp: JSON)
#pragma once

#include <array>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace knoblab::model {

// In the table's order.
enum class Effect {
  Offset,
  Gravity,
  Spring,
  PeriodicTorque,
  DetentShape,
  Stribeck,
  NonlinearDamping,
  PositionFriction,
  Drift,
  TimeDelay,
  Saturation,
  Backlash,
  Hysteresis,
  Endstop,
  Compliance,
};

inline constexpr std::array kAllEffects = {
    Effect::Offset,           Effect::Gravity,          Effect::Spring,
    Effect::PeriodicTorque,   Effect::DetentShape,      Effect::Stribeck,
    Effect::NonlinearDamping, Effect::PositionFriction, Effect::Drift,
    Effect::TimeDelay,        Effect::Saturation,       Effect::Backlash,
    Effect::Hysteresis,       Effect::Endstop,          Effect::Compliance,
};

// Where an effect acts, which decides where the simulator puts it.
enum class Acts {
  KnobTorque,     // a torque on the knob (a KnobEffect)
  KnobStructure,  // folded into the knob's own terms (KnobParams)
  Coupling,       // the plant's coupling between actuator and knob
  TorqueSensor,   // the torque channel (delay, clipping)
};
std::string_view acts_name(Acts a);  // "knob torque", …

enum class Role {
  Size,         // gives the effect its size: at least one Size parameter (or
                // its alternative) must be given, or the effect is zero
  Required,     // must be given
  Optional,     // its default applies when not given
  Alternative,  // may be given instead of `other` (not both)
  Reported,     // derived from `other`, reported beside it; not set
};

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

struct EffectParam {
  std::string_view name;
  std::string_view unit;     // SI; "" when dimensionless
  std::string_view meaning;  // a few words
  Role role = Role::Optional;
  // Physical range; a value outside is refused.
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  double fallback = 0.0;     // when not given; kNone: none (see meaning)
  std::string_view other{};  // Alternative: the parameter it replaces; Reported: the one it derives from
  std::string_view why{};    // said with a range error
  bool reported = true;      // discrepancy reports it (false: the simulator's only)

  bool settable() const { return role != Role::Reported; }
  bool in_range(double v) const;
  std::string range_text() const;  // "> 0 rad/s", "in (0, 0.1] rad", "" when any
};

struct EffectRow {
  Effect effect;
  std::string_view id;
  std::string_view description;  // one line
  std::string_view law;          // the model, as docs/discrepancy.md shows it
  Acts acts;
  std::span<const EffectParam> params;

  const EffectParam* param(std::string_view name) const;
  std::vector<std::string_view> settable_names() const;
};

std::span<const EffectRow> effect_table();
const EffectRow& effect_row(Effect e);
const EffectRow* find_effect(std::string_view id);
std::string known_effect_ids();  // "backlash, compliance, …" (sorted)

using NamedValues = std::vector<std::pair<std::string, double>>;

// An effect with the parameters given for it (checked against the table).
struct EffectSpec {
  Effect effect{};
  NamedValues params;  // as given, in the table's order

  const EffectRow& row() const { return effect_row(effect); }
  std::string_view id() const { return row().id; }
  bool has(std::string_view name) const;
  // The value given, else the table's default (kNone when it has none).
  // Throws std::logic_error for a name that is not one of the effect's.
  double value(std::string_view name) const;
  std::string text() const;  // "id:k=v,…", read back the same by parse_effect_spec
};

// "id:k=v,k=v". Throws std::invalid_argument on an unknown id or parameter, a
// reported-only one, one given twice or with its alternative, a value that is
// not a finite number or is out of its range, and an effect without the
// parameters it needs (the message names the effect, the parameter and why).
EffectSpec parse_effect_spec(std::string_view text);
// Several, separated by ';' (empty ones skipped).
std::vector<EffectSpec> parse_effect_specs(std::string_view text);

// The parameters as discrepancy reports them (a finding's params): values
// derived and reported beside a parameter (cycles_per_rev, h2_amplitude_Nm,
// …) are skipped, and an alternative given with the parameter it replaces
// (compliance's frequency_hz and zeta beside stiffness and damping) yields to
// it. Otherwise as parse_effect_spec, and throws as it does.
EffectSpec effect_from_params(std::string_view id, const NamedValues& params);

// Values under the names of the parameters discrepancy reports for `e`, in
// the table's order: one value per reported parameter, or std::logic_error.
NamedValues reported_values(Effect e, const std::vector<double>& values);

// The shortest text that reads back as v ("0.002", "6.283185307179586").
std::string shortest_number(double v);

// docs/discrepancy.md's effect table (Markdown).
std::string effect_table_markdown();

}  // namespace knoblab::model
