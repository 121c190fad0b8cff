#include "knoblab/fit/physical_checks.hpp"

#include <cstdio>

namespace knoblab::fit {

namespace {

struct Value {
  double v = 0, lo = 0, hi = 0;
  bool known = false;  // fitted (a held parameter says nothing)
};

Value get(const FitResult& r, std::string_view name) {
  for (std::size_t k = 0; k < r.names.size(); ++k)
    if (r.names[k] == name) return {r.params[k], r.ci95[k][0], r.ci95[k][1], r.fitted[k]};
  return {};
}

// Three significant figures, as the fit's table prints them.
std::string g3(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

std::string interval(const Value& x, const Unit& unit) {
  return g3(unit(x.v)) + " " + std::string(unit.text) + ", 95 % interval [" + g3(unit(x.lo)) + ", " +
         g3(unit(x.hi)) + "]";
}

// Friction in one direction, as a magnitude against speed: C + B·|ω| (Eq. 6,
// each coefficient a positive magnitude for a dissipative knob). Says where
// it turns negative, if anywhere the coefficients are resolved.
void friction_direction(const AxisUnits& u, const Value& C, const Value& B, const char* c_name,
                        const char* b_name, const std::string& direction, std::vector<std::string>& out) {
  const bool c_neg = C.known && C.hi < 0.0, b_neg = B.known && B.hi < 0.0;
  if (!c_neg && !b_neg) return;
  std::string what, where;
  if (c_neg && b_neg) {
    what = std::string(c_name) + " and " + b_name + " are both negative";
    where = "at every speed";
  } else if (c_neg) {
    what = std::string(c_name) + " is negative (" + interval(C, u.torque) + ")";
    where = B.v > 0.0 ? "below " + u.speed.with(-C.v / B.v) : "at every speed";
  } else {
    what = std::string(b_name) + " is negative (" + interval(B, u.damping) + ")";
    where = C.v > 0.0 ? "above " + u.speed.with(C.v / -B.v) : "at every speed";
  }
  out.push_back(what + ": " + direction + " the fitted friction pushes the knob along " + where +
                ", an energy-producing knob. Check the torque sensor's sign and offset (calibration), "
                "or look for physics the model leaves out (knoblab discrepancy)");
}

}  // namespace

std::vector<std::string> physical_warnings(const FitResult& r) {
  std::vector<std::string> out;
  const AxisUnits& u = units(r.axis);
  const std::string mass(u.mass), per(u.inertia.text);
  const Value M = get(r, "M_acc");
  if (M.known && M.hi < 0.0) {
    out.push_back("M_acc is negative (" + u.inertia.with(M.v) + "): no knob has negative " + mass +
                  ". Check the accelerometer's gain and sign (calibration) or fit with --alpha encoder");
  } else if (M.known && M.lo <= 0.0) {
    out.push_back("M_acc is not identified: its 95 % interval [" + g3(u.inertia(M.lo)) + ", " + g3(u.inertia(M.hi)) +
                  "] " + per + " includes zero. The capture's accelerations are too small against the "
                  "noise: a faster or longer sweep helps");
  }
  const std::string moving(u.moving), rate(u.theta_dot);
  if (r.model == ModelKind::Render4) {
    friction_direction(u, Value{0, 0, 0, true}, get(r, "B_vel"), "C_vel", "B_vel", "in both directions", out);
  } else {
    friction_direction(u, get(r, "C_vel_pos"), get(r, "B_vel_pos"), "C_vel_pos", "B_vel_pos",
                       moving + " forwards (" + rate + " > 0)", out);
    friction_direction(u, get(r, "C_vel_neg"), get(r, "B_vel_neg"), "C_vel_neg", "B_vel_neg",
                       moving + " backwards (" + rate + " < 0)", out);
  }
  return out;
}

}  // namespace knoblab::fit
