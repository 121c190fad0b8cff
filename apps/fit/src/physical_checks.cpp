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

std::string interval(const Value& x, const std::string& unit) {
  return g3(x.v * 1e3) + " " + unit + ", 95 % interval [" + g3(x.lo * 1e3) + ", " + g3(x.hi * 1e3) + "]";
}

// Friction in one direction, as a magnitude against speed: C + B·|ω| (Eq. 6,
// each coefficient a positive magnitude for a dissipative knob). Says where
// it turns negative, if anywhere the coefficients are resolved.
void friction_direction(const Value& C, const Value& B, const char* c_name, const char* b_name,
                        const std::string& direction, std::vector<std::string>& out) {
  const bool c_neg = C.known && C.hi < 0.0, b_neg = B.known && B.hi < 0.0;
  if (!c_neg && !b_neg) return;
  std::string what, where;
  if (c_neg && b_neg) {
    what = std::string(c_name) + " and " + b_name + " are both negative";
    where = "at every speed";
  } else if (c_neg) {
    what = std::string(c_name) + " is negative (" + interval(C, "mN·m") + ")";
    where = B.v > 0.0 ? "below " + g3(-C.v / B.v) + " rad/s" : "at every speed";
  } else {
    what = std::string(b_name) + " is negative (" + interval(B, "mN·m/(rad/s)") + ")";
    where = C.v > 0.0 ? "above " + g3(C.v / -B.v) + " rad/s" : "at every speed";
  }
  out.push_back(what + ": " + direction + " the fitted friction pushes the knob along " + where +
                ", an energy-producing knob. Check the torque sensor's sign and offset (calibration), "
                "or look for physics the model leaves out (knoblab discrepancy)");
}

}  // namespace

std::vector<std::string> physical_warnings(const FitResult& r) {
  std::vector<std::string> out;
  const Value M = get(r, "M_acc");
  if (M.known && M.hi < 0.0) {
    out.push_back("M_acc is negative (" + g3(M.v * 1e3) +
                  " mN·m/(rad/s²)): no knob has negative inertia. Check the accelerometer's gain and sign "
                  "(calibration) or fit with --alpha encoder");
  } else if (M.known && M.lo <= 0.0) {
    out.push_back("M_acc is not identified: its 95 % interval [" + g3(M.lo * 1e3) + ", " + g3(M.hi * 1e3) +
                  "] mN·m/(rad/s²) includes zero. The capture's accelerations are too small against the "
                  "noise: a faster or longer sweep helps");
  }
  if (r.model == ModelKind::Render4) {
    friction_direction(Value{0, 0, 0, true}, get(r, "B_vel"), "C_vel", "B_vel", "in both directions", out);
  } else {
    friction_direction(get(r, "C_vel_pos"), get(r, "B_vel_pos"), "C_vel_pos", "B_vel_pos", "turning forwards (θ̇ > 0)", out);
    friction_direction(get(r, "C_vel_neg"), get(r, "B_vel_neg"), "C_vel_neg", "B_vel_neg", "turning backwards (θ̇ < 0)", out);
  }
  return out;
}

}  // namespace knoblab::fit
