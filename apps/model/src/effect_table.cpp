// The effect table's rows (effect_table.hpp), their lookups, and the
// Markdown docs/discrepancy.md shows of them.
#include "knoblab/model/effect_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace knoblab::model {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
using R = Role;

// A torque amplitude or coefficient: any sign (the fitter's too).
constexpr EffectParam size(std::string_view name, std::string_view unit, std::string_view meaning) {
  return {.name = name, .unit = unit, .meaning = meaning, .role = R::Size};
}
// One that physics signs: outside its range a fitted value is not this
// effect (discovery drops the candidate), and simulate refuses it.
constexpr EffectParam signed_size(std::string_view name, std::string_view unit, std::string_view meaning,
                                  std::string_view why) {
  return {.name = name, .unit = unit, .meaning = meaning, .role = R::Size, .lo = 0.0, .why = why};
}
constexpr EffectParam reported(std::string_view name, std::string_view unit, std::string_view meaning,
                               std::string_view from = {}) {
  return {.name = name, .unit = unit, .meaning = meaning, .role = R::Reported, .fallback = kNone, .other = from};
}
constexpr EffectParam phase() {
  return {.name = "phase_rad", .unit = "rad", .meaning = "phase φ"};
}
constexpr EffectParam period() {
  return {.name = "period_rad", .unit = "rad", .meaning = "period over position (2π: once per revolution)", .lo = 0.0, .lo_open = true,
          .fallback = kTwoPi};
}
constexpr EffectParam cycles_per_rev() {
  return reported("cycles_per_rev", "1/rev", "2π / period_rad", "period_rad");
}

constexpr EffectParam kOffset[] = {size("offset_Nm", "N·m", "the bias τ₀")};

constexpr EffectParam kGravity[] = {size("amplitude_Nm", "N·m", "amplitude A"), phase()};

constexpr EffectParam kSpring[] = {
    signed_size("stiffness_Nm_per_rad", "N·m/rad", "linear stiffness K",
                "restoring: a negative stiffness pushes away from the centre (an over-centre mechanism, not a spring return)"),
    size("cubic_Nm_per_rad3", "N·m/rad³", "cubic stiffness K₃"),
    {.name = "centre_rad", .unit = "rad", .meaning = "centre θ₀"},
};

constexpr EffectParam kPeriodicTorque[] = {size("amplitude_Nm", "N·m", "amplitude A"), period(), cycles_per_rev(),
                                           phase()};

constexpr EffectParam kDetentShape[] = {
    reported("cycles_per_rev", "1/rev", "the knob's detents per revolution"),
    reported("h2_amplitude_Nm", "N·m", "√(a₂² + b₂²)"),
    reported("h2_cycles_per_rev", "1/rev", "2 × the detents'"),
    reported("h3_amplitude_Nm", "N·m", "√(a₃² + b₃²)"),
    reported("h3_cycles_per_rev", "1/rev", "3 × the detents'"),
    reported("h4_amplitude_Nm", "N·m", "√(a₄² + b₄²)"),
    reported("h4_cycles_per_rev", "1/rev", "4 × the detents'"),
    size("a2_Nm", "N·m", "sin 2φ"),
    size("b2_Nm", "N·m", "cos 2φ"),
    size("a3_Nm", "N·m", "sin 3φ"),
    size("b3_Nm", "N·m", "cos 3φ"),
    size("a4_Nm", "N·m", "sin 4φ"),
    size("b4_Nm", "N·m", "cos 4φ"),
};

constexpr EffectParam kStribeck[] = {
    signed_size("static_excess_Nm", "N·m", "ΔC, static above kinetic friction",
                "static friction above the kinetic: a dip near zero speed is not Stribeck friction"),
    {.name = "stribeck_velocity_rad_s", .unit = "rad/s", .meaning = "v_s, the speed it falls off over", .lo = 0.0,
     .lo_open = true, .fallback = 1.0},
};

constexpr EffectParam kNonlinearDamping[] = {
    signed_size("coefficient", "N·m·(s/rad)^p", "c", "dissipative: a negative coefficient feeds energy in"),
    {.name = "exponent", .unit = "", .meaning = "p (2: fluid drag; < 1: grease)", .lo = 0.0, .lo_open = true, .fallback = 2.0},
};

constexpr EffectParam kPositionFriction[] = {size("depth_Nm", "N·m", "modulation depth D"), period(),
                                             cycles_per_rev(), phase()};

constexpr EffectParam kDrift[] = {
    size("rate_Nm_per_s", "N·m/s", "how fast the Coulomb level changes"),
    {.name = "t0_s", .unit = "s", .meaning = "when it is at its level (discrepancy: the mid time)"},
};

constexpr EffectParam kTimeDelay[] = {
    {.name = "delay_s", .unit = "s", .meaning = "δ, the torque behind the motion", .role = R::Size, .lo = 0.0,
     .hi = 0.1,
     .why = "positive: the torque behind the motion; the simulator does not model a torque ahead, which "
            "discrepancy may report"},
};

constexpr EffectParam kSaturation[] = {
    {.name = "limit_Nm", .unit = "N·m", .meaning = "the sensor clips at ±limit", .role = R::Size, .lo = 0.0,
     .lo_open = true},
};

constexpr EffectParam kBacklash[] = {
    {.name = "width_rad", .unit = "rad", .meaning = "total play (discrepancy: lost motion at the encoder)",
     .role = R::Size, .lo = 0.0, .hi = 0.5, .lo_open = true},
};

constexpr EffectParam kHysteresis[] = {
    {.name = "presliding_angle_rad", .unit = "rad", .meaning = "θ_p", .role = R::Size, .lo = 0.0, .hi = 0.1,
     .lo_open = true},
};

constexpr EffectParam kEndstop[] = {
    {.name = "position_rad", .unit = "rad", .meaning = "the stops sit at ±position", .role = R::Required, .lo = 0.0,
     .lo_open = true, .fallback = kNone},
    {.name = "stiffness_Nm_per_rad", .unit = "N·m/rad", .meaning = "K beyond a stop", .role = R::Size, .lo = 0.0,
     .lo_open = true},
    {.name = "damping_Nm_s_per_rad", .unit = "N·m·s/rad", .meaning = "B while in a stop", .lo = 0.0,
     .why = "dissipative", .reported = false},
    {.name = "max_torque_Nm", .unit = "N·m",
     .meaning = "T, where a stop's torque tops out (a rendered wall's plateau; not given: it climbs on, a mechanical stop)",
     .lo = 0.0, .lo_open = true, .fallback = kInf},
};

constexpr EffectParam kCompliance[] = {
    {.name = "stiffness_Nm_per_rad", .unit = "N·m/rad", .meaning = "k of the coupling", .role = R::Size, .lo = 0.0,
     .lo_open = true},
    {.name = "damping_Nm_s_per_rad", .unit = "N·m·s/rad",
     .meaning = "c of the coupling (default: the rig's damping ratio kept)", .lo = 0.0, .fallback = kNone,
     .why = "dissipative"},
    {.name = "frequency_hz", .unit = "Hz",
     .meaning = "the knob ringing against a held motor: k = J·(2πf)², J = knob + gripper inertia",
     .role = R::Alternative, .lo = 0.0, .lo_open = true, .fallback = kNone, .other = "stiffness_Nm_per_rad"},
    {.name = "zeta", .unit = "", .meaning = "damping ratio there: c = 2ζ·√(k·J)", .role = R::Alternative, .lo = 0.0,
     .fallback = kNone, .other = "damping_Nm_s_per_rad"},
};

constexpr EffectRow kTable[] = {
    {Effect::Offset, "offset", "a constant torque bias: sensor zero, preload", "τ₀", Acts::KnobTorque, kOffset},
    {Effect::Gravity, "gravity", "an unbalanced mass or tilted axis, once per revolution", "A·sin(θ + φ)",
     Acts::KnobTorque, kGravity},
    {Effect::Spring, "spring", "a restoring spring", "K·(θ − θ₀) + K₃·(θ − θ₀)³", Acts::KnobStructure, kSpring},
    {Effect::PeriodicTorque, "periodic_torque",
     "a second position-periodic torque: cogging, a second detent track, screw ripple", "A·sin(2πθ/period + φ)",
     Acts::KnobTorque, kPeriodicTorque},
    {Effect::DetentShape, "detent_shape", "non-sinusoidal detents: harmonics 2…4 of the detent period",
     "Σ a_k·sin kφ + b_k·cos kφ, φ = θ/P + S of the detents", Acts::KnobStructure, kDetentShape},
    {Effect::Stribeck, "stribeck", "friction above its Coulomb level near zero speed", "sgn(ω)·ΔC·exp(−(ω/v_s)²)",
     Acts::KnobTorque, kStribeck},
    {Effect::NonlinearDamping, "nonlinear_damping", "damping not proportional to speed", "sgn(ω)·c·|ω|^p",
     Acts::KnobTorque, kNonlinearDamping},
    {Effect::PositionFriction, "position_friction",
     "a friction level that varies with position: a bent shaft, an eccentric bearing",
     "sgn(ω)·D·sin(2πθ/period + φ)", Acts::KnobTorque, kPositionFriction},
    {Effect::Drift, "drift", "a friction level changing during the recording: warming, wear", "sgn(ω)·rate·(t − t₀)",
     Acts::KnobTorque, kDrift},
    {Effect::TimeDelay, "time_delay", "the torque channel behind the motion channels",
     "the torque at t is the model's at the motion of t − δ", Acts::TorqueSensor, kTimeDelay},
    {Effect::Saturation, "saturation", "the torque sensor clipping", "measured torque clipped at ±limit",
     Acts::TorqueSensor, kSaturation},
    {Effect::Backlash, "backlash", "play (lost motion) between the drive and the detent mechanism",
     "play operator of total width w; no mechanism torque out of contact", Acts::KnobStructure, kBacklash},
    {Effect::Hysteresis, "hysteresis", "presliding friction (Dahl): friction turns over instead of jumping",
     "C·z, dz/dθ = (1 − z·sgn θ̇)/θ_p", Acts::KnobStructure, kHysteresis},
    {Effect::Endstop, "endstop", "hard stops at the ends of the travel",
     "K·(θ ∓ position), at most ±T, + B·θ̇ beyond ±position", Acts::KnobStructure, kEndstop},
    {Effect::Compliance, "compliance", "a softer coupling between actuator and knob (gripper)",
     "the knob lags the motor by the twist e, k·e + c·ė = τ", Acts::Coupling, kCompliance},
};

// A default as docs show it (2π as 6.283).
std::string with_unit(double v, std::string_view unit) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf + (unit.empty() ? "" : " " + std::string(unit));
}

}  // namespace

std::string shortest_number(double v) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  return std::string(buf, end);
}

std::string_view acts_name(Acts a) {
  switch (a) {
    case Acts::KnobTorque: return "knob torque";
    case Acts::KnobStructure: return "knob";
    case Acts::Coupling: return "coupling";
    case Acts::TorqueSensor: return "torque sensor";
  }
  return "?";
}

bool EffectParam::in_range(double v) const {
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string EffectParam::range_text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  const std::string u = unit.empty() ? "" : " " + std::string(unit);
  if (has_lo && has_hi)
    return "in " + std::string(lo_open ? "(" : "[") + shortest_number(lo) + ", " + shortest_number(hi) + (hi_open ? ")" : "]") + u;
  if (has_lo) return std::string(lo_open ? "> " : ">= ") + shortest_number(lo) + u;
  if (has_hi) return std::string(hi_open ? "< " : "<= ") + shortest_number(hi) + u;
  return "";
}

const EffectParam* EffectRow::param(std::string_view name) const {
  for (const EffectParam& p : params)
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<std::string_view> EffectRow::settable_names() const {
  std::vector<std::string_view> out;
  for (const EffectParam& p : params)
    if (p.settable()) out.push_back(p.name);
  return out;
}

std::span<const EffectRow> effect_table() { return kTable; }

const EffectRow& effect_row(Effect e) { return kTable[static_cast<std::size_t>(e)]; }

const EffectRow* find_effect(std::string_view id) {
  for (const EffectRow& r : kTable)
    if (r.id == id) return &r;
  return nullptr;
}

std::string known_effect_ids() {
  std::vector<std::string_view> ids;
  for (const EffectRow& r : kTable) ids.push_back(r.id);
  std::sort(ids.begin(), ids.end());
  std::string out;
  for (const std::string_view id : ids) out += (out.empty() ? "" : ", ") + std::string(id);
  return out;
}

std::string effect_table_markdown() {
  std::string md =
      "| id | acts on | what | model | parameters |\n"
      "|---|---|---|---|---|\n";
  for (const EffectRow& r : kTable) {
    std::string params;
    for (const EffectParam& p : r.params) {
      std::string cell = "`" + std::string(p.name) + "`";
      if (p.role == Role::Size) cell = "**" + cell + "**";
      if (p.role == Role::Reported) cell = "*" + cell + "*";
      cell += " " + std::string(p.unit.empty() ? "–" : p.unit) + ", " + std::string(p.meaning);
      if (const std::string range = p.range_text(); !range.empty()) cell += "; " + range;
      if (p.role == Role::Required) cell += "; required";
      if (p.role == Role::Alternative) cell += "; instead of `" + std::string(p.other) + "`";
      if (p.settable() && p.role != Role::Alternative && std::isfinite(p.fallback) &&
          (p.role != Role::Size || p.fallback != 0.0))
        cell += "; default " + with_unit(p.fallback, p.unit);
      if (!p.reported) cell += "; simulator only";
      params += (params.empty() ? "" : "<br>") + cell;
    }
    std::string law(r.law);
    std::string escaped;
    for (const char c : law) escaped += c == '|' ? std::string("\\|") : std::string(1, c);
    md += "| `" + std::string(r.id) + "` | " + std::string(acts_name(r.acts)) + " | " + std::string(r.description) +
          " | " + escaped + " | " + params + " |\n";
  }
  return md;
}

}  // namespace knoblab::model
