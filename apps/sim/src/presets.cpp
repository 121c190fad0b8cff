#include "knoblab/sim/presets.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace knoblab::sim::presets {

namespace {

constexpr double kMilli = 1e-3;
constexpr double kPi = std::numbers::pi;

// One Table 7 column, as printed (mN·m units; signs as printed).
struct Table7 {
  double M, C_neg, B_neg, C_pos, B_pos, D_neg, D_pos, dv, A, P, S;
};

KnobParams thesis_knob(const Table7& t) {
  KnobParams k;
  k.inertia.M = std::abs(t.M) * kMilli;
  k.friction = {std::abs(t.C_neg) * kMilli, std::abs(t.B_neg) * kMilli, std::abs(t.C_pos) * kMilli,
                std::abs(t.B_pos) * kMilli};
  k.stick = {t.dv, std::abs(t.D_neg) * kMilli, std::abs(t.D_pos) * kMilli};
  k.detents.A = t.A * kMilli;
  k.detents.P = t.P;
  k.detents.S = t.S;
  return k;
}

// One Table 19/20 row: b in mN·m/(rad/s), m in mN·m/(rad/s²), a1 in mN·m,
// a2 the detent period in rad (see presets.hpp).
KnobParams study_knob(double b, double m, double a1, double a2) {
  KnobParams k;
  k.inertia.M = m * kMilli + kHapticKnobInertia;
  k.friction = {0.0, b * kMilli, 0.0, b * kMilli};
  k.detents.A = a1 * kMilli;
  k.detents.P = a2 > 0.0 ? a2 / (2.0 * kPi) : 1.0;
  return k;
}

KnobParams non_sine() {
  // Set 1, with the caps and sign handling documented in presets.hpp.
  KnobParams k = thesis_knob({-0.0048, -35, -6.4, 35, 6.7, -90, 90, 0.015, 61, 1.0 / 12, -0.16 + kPi});
  k.detents.harmonics = 3;
  k.detents.a[2] = 0.10 * k.detents.A;  // skew: steeper on one side
  k.detents.a[3] = 0.20 * k.detents.A;  // flat tops: wide detents
  return k;
}

std::array<Preset, 19> build() {
  return {{
      {"high-friction", "Table 5/7: 1960s AM/FM radio volume knob; moderate friction, low inertia",
       thesis_knob({0.069, -50, -1.8, 50, 7.5, -150, 150, 0.040, 0, 1, 0})},
      {"high-inertia", "Table 5/7: 1960s AM/FM radio tuning knob; low friction, high inertia",
       thesis_knob({0.28, -3.8, -0.56, 3.8, 0.47, -17, 17, 0.015, 0, 1, 0})},
      {"subtle-detents", "Table 5/7: 2004 Mazda 626 volume knob; 30 very subtle detents/rev",
       thesis_knob({0.034, -2.2, -0.16, 2.2, 0.25, -10, 10, 0.010, 1.2, 1.0 / 30, 0.00046})},
      {"moderate-detents", "Table 5/7: 1970s amplifier source selector; 12 moderate detents/rev",
       thesis_knob({0.049, -1.1, -0.48, 1.1, 0.56, -20, 20, 0.010, -11, 1.0 / 12, -0.19})},
      {"non-sine-detents",
       "Table 5/7: 2004 Mazda 626 fan knob; 12 wide non-sinusoidal detents/rev (capped)", non_sine()},
      {"study2-not-rendered", "Table 19 #1: no force feedback (control)", study_knob(0, 0, 0, 0)},
      {"study2-low-friction", "Table 19 #2: b = 2.6 mN·m/(rad/s), portable radio volume",
       study_knob(2.6, 0, 0, 0)},
      {"study2-high-friction", "Table 19 #3: b = 5.3 mN·m/(rad/s), sink faucet",
       study_knob(5.3, 0, 0, 0)},
      {"study2-low-inertia", "Table 19 #4: m = 0.06 mN·m/(rad/s²), toy car wheel",
       study_knob(0, 0.06, 0, 0)},
      {"study2-high-inertia", "Table 19 #5: m = 0.38 mN·m/(rad/s²), free-spinning fishing reel",
       study_knob(0, 0.38, 0, 0)},
      {"study2-few-detents", "Table 19 #6: 14 mN·m detents, a2 = 2π (1/rev), 3-setting fan knob",
       study_knob(0, 0, 14, 2 * kPi)},
      {"study2-many-detents", "Table 19 #7: 14 mN·m detents, a2 = 2π/3 (3/rev), mouse scroll wheel",
       study_knob(0, 0, 14, 2 * kPi / 3)},
      {"study3-not-rendered", "Table 20 #1: no force feedback (control)", study_knob(0, 0, 0, 0)},
      {"study3-low-friction", "Table 20 #2: b = 2.6 mN·m/(rad/s), portable radio volume",
       study_knob(2.6, 0, 0, 0)},
      {"study3-high-friction", "Table 20 #3: b = 7.9 mN·m/(rad/s), sink faucet",
       study_knob(7.9, 0, 0, 0)},
      {"study3-low-inertia", "Table 20 #4: m = 0.06 mN·m/(rad/s²), toy car wheel",
       study_knob(0, 0.06, 0, 0)},
      {"study3-high-inertia", "Table 20 #5: m = 0.21 mN·m/(rad/s²), free-spinning fishing reel",
       study_knob(0, 0.21, 0, 0)},
      {"study3-few-detents", "Table 20 #6: 7 mN·m detents, a2 = 2π (1/rev), 3-setting fan knob",
       study_knob(0, 0, 7, 2 * kPi)},
      {"study3-many-detents", "Table 20 #7: 19 mN·m detents, a2 = 2π/5 (5/rev), mouse scroll wheel",
       study_knob(0, 0, 19, 2 * kPi / 5)},
  }};
}

}  // namespace

std::span<const Preset> all() {
  static const std::array<Preset, 19> table = build();
  return table;
}

std::vector<PresetInfo> list() {
  std::vector<PresetInfo> out;
  for (const Preset& p : all()) out.push_back({p.id, p.description});
  return out;
}

const Preset* find(std::string_view id) {
  for (const Preset& p : all())
    if (p.id == id) return &p;
  return nullptr;
}

std::optional<KnobParams> knob(std::string_view id) {
  if (const Preset* p = find(id)) return p->knob;
  return std::nullopt;
}

}  // namespace knoblab::sim::presets
