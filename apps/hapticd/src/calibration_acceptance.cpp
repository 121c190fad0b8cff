#include "knoblab/hapticd/calibration_acceptance.hpp"

#include <cmath>
#include <numbers>
#include <nlohmann/json.hpp>

namespace knoblab::hapticd {

namespace {

AveragedValue average(std::string name, std::vector<double> runs) {
  AveragedValue v{std::move(name), 0.0, 0.0, std::move(runs)};
  const double n = static_cast<double>(v.runs.size());
  for (const double x : v.runs) v.mean += x / n;
  if (v.runs.size() > 1) {
    double ss = 0.0;
    for (const double x : v.runs) ss += (x - v.mean) * (x - v.mean);
    v.sd = std::sqrt(ss / (n - 1.0));
  }
  return v;
}

// A phase is averaged on the circle: runs at −π + ε and π − ε agree.
AveragedValue average_phase(std::string name, std::vector<double> runs) {
  double s = 0.0, c = 0.0;
  for (const double x : runs) {
    s += std::sin(x);
    c += std::cos(x);
  }
  const double mean = std::atan2(s, c);
  std::vector<double> unwrapped;
  for (const double x : runs) unwrapped.push_back(mean + std::remainder(x - mean, 2.0 * std::numbers::pi));
  AveragedValue v = average(std::move(name), std::move(unwrapped));
  v.mean = mean;
  v.runs = std::move(runs);
  return v;
}

}  // namespace

bool changes_constants(CalibrationKind kind) {
  return kind == CalibrationKind::AccelGain || kind == CalibrationKind::Gravity;
}

std::variant<AcceptedCalibration, std::string> average_runs(std::span<const CalibrationResult> history,
                                                            CalibrationKind kind, int repetitions,
                                                            const capture::SensorCalibration& in_use) {
  if (!changes_constants(kind))
    return std::string(to_string(kind)) + " verifies the sensors (Table 4) and changes no constant; "
                                          "accept accel_gain or gravity";
  std::vector<const CalibrationResult*> chosen;
  int of_kind = 0, stale = 0;
  for (auto it = history.rbegin(); it != history.rend() && static_cast<int>(chosen.size()) < repetitions; ++it) {
    if (it->kind != kind) continue;
    ++of_kind;
    if (!it->ok()) continue;
    if (!(it->in_use == in_use)) {
      ++stale;
      continue;
    }
    chosen.push_back(&*it);
  }
  if (static_cast<int>(chosen.size()) < repetitions) {
    std::string why = "accepting " + std::string(to_string(kind)) + " averages " + std::to_string(repetitions) +
                      (repetitions == 1 ? " good run" : " good runs") + ", and " + std::to_string(chosen.size()) +
                      " of the " + std::to_string(of_kind) +
                      " ended " + to_string(kind) + " runs qualify";
    if (stale > 0) why += " (" + std::to_string(stale) + " used constants that have changed since)";
    return why + "; run calibrate kind=" + to_string(kind) + " again";
  }

  AcceptedCalibration a;
  a.kind = kind;
  a.before = in_use;
  a.after = in_use;
  std::vector<double> C_cal, A, C, D;
  for (const CalibrationResult* r : chosen) {
    C_cal.push_back(r->updated.C_cal);
    A.push_back(r->updated.grav_A);
    C.push_back(r->updated.grav_C);
    D.push_back(r->updated.grav_D);
  }
  if (kind == CalibrationKind::AccelGain) {
    a.values.push_back(average("C_cal", C_cal));
    a.after.C_cal = a.values[0].mean;
  } else {
    a.values.push_back(average("grav_A", A));
    a.values.push_back(average_phase("grav_C", C));
    a.values.push_back(average("grav_D", D));
    a.after.grav_A = a.values[0].mean;
    a.after.grav_B = 1.0;
    a.after.grav_C = a.values[1].mean;
    a.after.grav_D = a.values[2].mean;
  }
  return a;
}

nlohmann::json to_json(const AcceptedCalibration& a) {
  nlohmann::json values = nlohmann::json::object();
  for (const AveragedValue& v : a.values) values[v.name] = {{"mean", v.mean}, {"sd", v.sd}, {"runs", v.runs}};
  return {{"kind", to_string(a.kind)}, {"repetitions", a.values.empty() ? 0 : a.values[0].runs.size()},
          {"values", values}, {"unix_time", a.unix_time}};
}

}  // namespace knoblab::hapticd
