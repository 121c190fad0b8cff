#include "knoblab/sim/knob.hpp"

#include <cmath>

namespace knoblab::sim {

namespace {
bool finite_nonneg(double x) { return std::isfinite(x) && x >= 0.0; }
}  // namespace

std::string_view check(const KnobParams& k) {
  if (!finite_nonneg(k.inertia.M)) return "inertia M must be finite and >= 0";
  const auto& f = k.friction;
  if (!finite_nonneg(f.C_neg) || !finite_nonneg(f.C_pos) || !finite_nonneg(f.B_neg) ||
      !finite_nonneg(f.B_pos))
    return "friction C/B must be finite magnitudes >= 0 (dissipative)";
  if (!finite_nonneg(k.stick.dv) || !finite_nonneg(k.stick.D_neg) || !finite_nonneg(k.stick.D_pos))
    return "stick dv/D must be finite and >= 0";
  const auto& d = k.detents;
  if (!std::isfinite(d.A) || !std::isfinite(d.S) || !std::isfinite(d.P) || !(d.P > 0.0))
    return "detents need finite A, S and P > 0";
  if (d.harmonics < 1 || d.harmonics > d.kMaxHarmonic) return "detent harmonics must be 1..kMaxHarmonic";
  for (std::size_t i = 0; i < d.a.size(); ++i)
    if (!std::isfinite(d.a[i]) || !std::isfinite(d.b[i])) return "detent harmonics must be finite";
  if (!finite_nonneg(k.spring.K) || !finite_nonneg(k.spring.K3) || !std::isfinite(k.spring.theta0))
    return "spring K, K3 must be >= 0 (restoring)";
  if (!finite_nonneg(k.walls.K) || !finite_nonneg(k.walls.B) || !(k.walls.lo <= k.walls.hi) || !(k.walls.limit > 0.0))
    return "walls need K, B >= 0, lo <= hi and a limit > 0 (∞: none)";
  if (!finite_nonneg(k.backlash) || k.backlash > 0.5) return "backlash must be 0 … 0.5 rad";
  if (!finite_nonneg(k.presliding) || k.presliding > 0.1) return "presliding angle must be 0 … 0.1 rad";
  return {};
}

model::ThesisModel<double> thesis_model(const KnobParams& k) {
  model::ThesisModel<double> m;
  m.inertia = k.inertia;
  m.friction = k.friction;
  m.detents = k.detents;
  return m;
}

}  // namespace knoblab::sim
