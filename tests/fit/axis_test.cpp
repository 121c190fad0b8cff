// A capture's axis (rotary or linear): where it comes from (the metadata, a
// stored capture's metadata object, the caller), and how each axis presents
// its quantities (axis_units.hpp) in the fit's JSON and warnings.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "knoblab/fit/axis_units.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/physical_checks.hpp"
#include "knoblab/fit/result_json.hpp"
#include "knoblab/fit/validation_data.hpp"

namespace knoblab::fit {
namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Half a second of a 2 Hz sweep at 1 kHz: enough to prepare.
interchange::Capture sweep(std::vector<std::pair<std::string, std::string>> metadata) {
  interchange::Capture c;
  c.metadata = std::move(metadata);
  for (int i = 0; i < 500; ++i) {
    const double t = i * 1e-3;
    c.t.push_back(t);
    c.theta.push_back(0.01 * std::sin(4 * std::numbers::pi * t));
    c.omega.push_back(0.0);
    c.alpha.push_back(0.0);
    c.torque.push_back(0.1 * std::cos(4 * std::numbers::pi * t));
  }
  c.alpha_derived = true;
  return c;
}

TEST(AxisUnits, ARotaryAxisShowsTorqueInMilliNewtonMetresAnglesInDegreesAndCyclesPerRevolution) {
  const AxisUnits& u = units(Axis::Rotary);
  EXPECT_EQ(u.torque.with(0.0012), "1.2 mN·m");
  EXPECT_EQ(u.position.with(std::numbers::pi / 6), "30°");
  EXPECT_EQ(u.position.axis_label(), "deg");
  EXPECT_EQ(u.plot_speed.column_suffix(), "deg_per_s");
  EXPECT_EQ(u.torque.column_suffix(), "mNm");
  EXPECT_EQ(u.cycle.with(2 * std::numbers::pi / 12), "12 cycles/rev");
  EXPECT_EQ(u.inertia.with(5e-5), "0.05 mN·m/(rad/s²)");
}

TEST(AxisUnits, ALinearAxisShowsForceInNewtonsPositionsInMillimetresAndPeriodsInMillimetresPerCycle) {
  const AxisUnits& u = units(Axis::Linear);
  EXPECT_EQ(u.torque.with(1.5), "1.5 N");
  EXPECT_EQ(u.position.with(0.0125), "12.5 mm");
  EXPECT_EQ(u.speed.with(0.02), "20 mm/s");
  EXPECT_EQ(u.stiffness.with(400.0), "400 N/m");
  EXPECT_EQ(u.damping.with(3.0), "3 N·s/m");
  EXPECT_EQ(u.inertia.with(0.8), "0.8 kg");
  EXPECT_EQ(u.cycle.with(0.0025), "2.5 mm per cycle");
  EXPECT_EQ(u.position.column_suffix(), "mm");
  EXPECT_EQ(u.plot_speed.column_suffix(), "mm_per_s");
}

TEST(AxisUnits, AnEffectParameterInRotaryUnitsReadsAsItsLinearCounterpart) {
  const AxisUnits& lin = units(Axis::Linear);
  EXPECT_EQ(effect_param_unit(lin, "stiffness_Nm_per_rad", "N·m/rad").text, "N/m");
  EXPECT_EQ(effect_param_unit(lin, "width_rad", "rad").text, "mm");
  EXPECT_EQ(effect_param_unit(lin, "width_rad", "rad").scale, 1e3);
  EXPECT_EQ(effect_param_unit(lin, "amplitude_Nm", "N·m").text, "N");
  // A phase is the sine's angle on either axis.
  EXPECT_EQ(effect_param_unit(lin, "phase_rad", "rad").text, "rad");
  const AxisUnits& rot = units(Axis::Rotary);
  EXPECT_EQ(effect_param_unit(rot, "amplitude_Nm", "N·m").text, "mN·m");
  EXPECT_EQ(effect_param_unit(rot, "width_rad", "rad").text, "rad");
  EXPECT_EQ(effect_param_unit(rot, "exponent", "").text, "–");
}

TEST(CaptureAxis, AnAxisLineInTheMetadataMakesThePreparedDataLinear) {
  EXPECT_EQ(prepare(sweep({{"axis", "linear"}})).axis, Axis::Linear);
  EXPECT_EQ(prepare(sweep({{"axis", "rotary"}})).axis, Axis::Rotary);
  EXPECT_EQ(prepare(sweep({})).axis, Axis::Rotary);
}

TEST(CaptureAxis, AStoredCapturesMetadataObjectCarriesTheAxis) {
  EXPECT_EQ(capture_axis(sweep({{"metadata", R"({"knob_note": "rail", "axis": "linear"})"}})), Axis::Linear);
  EXPECT_EQ(capture_axis(sweep({{"metadata", R"({"axis": ["linear", "linear"]})"}})), Axis::Linear);
  EXPECT_EQ(capture_axis(sweep({{"metadata", R"({"knob_note": "dial"})"}})), std::nullopt);
}

TEST(CaptureAxis, AnAxisOtherThanRotaryOrLinearIsRefusedNamingTheValue) {
  try {
    prepare(sweep({{"axis", "angular"}}));
    FAIL() << "an unknown axis was accepted";
  } catch (const FitDataError& e) {
    EXPECT_TRUE(contains(e.what(), "metadata 'axis' is 'angular': expected rotary or linear")) << e.what();
  }
  EXPECT_THROW(capture_axis(sweep({{"metadata", R"({"axis": 3})"}})), FitDataError);
  EXPECT_THROW(capture_axis(sweep({{"axis", "linear"}, {"axis", "rotary"}})), FitDataError);
}

TEST(CaptureAxis, TheCallersAxisAppliesOnlyWhereTheMetadataSaysNone) {
  PrepOptions linear;
  linear.axis = Axis::Linear;
  EXPECT_EQ(prepare(sweep({}), linear).axis, Axis::Linear);
  EXPECT_EQ(prepare(sweep({{"axis", "linear"}}), linear).axis, Axis::Linear);
  try {
    prepare(sweep({{"axis", "rotary"}}), linear);
    FAIL() << "a contradicting axis was accepted";
  } catch (const FitDataError& e) {
    EXPECT_TRUE(contains(e.what(), "says 'axis: rotary', not linear")) << e.what();
  }
}

TEST(LinearFit, TheJsonSaysItsAxisAndStaysSi) {
  FitData d = make_validation_data(ValidationSpec{});
  const FitResult rotary = fit_knob(d);
  d.axis = Axis::Linear;
  const FitResult linear = fit_knob(d);
  const auto j = nlohmann::json::parse(to_json(linear));
  EXPECT_EQ(j["axis"], "linear");
  EXPECT_FALSE(nlohmann::json::parse(to_json(rotary)).contains("axis"));
  // The same numbers: only the reader's units differ.
  EXPECT_EQ(j["params"]["M_acc"].get<double>(), rotary.value("M_acc"));
}

TEST(LinearFit, WarningsSpeakOfNewtonsMassAndMillimetresPerSecond) {
  FitResult r;
  r.model = ModelKind::Thesis6;
  r.axis = Axis::Linear;
  r.names = param_names(r.model);
  r.params = {-0.5, 1.0, 5.0, -2.0, 50.0, 0, 1, 0};
  r.fitted = {true, true, true, true, true, false, false, false};
  r.se.assign(8, 0.0);
  r.ci95 = {{{-0.6, -0.4}}, {{0.9, 1.1}}, {{4, 6}}, {{-3, -1}}, {{40, 60}}, {{0, 0}}, {{1, 1}}, {{0, 0}}};
  const auto w = physical_warnings(r);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_TRUE(contains(w[0], "M_acc is negative (-0.5 kg): no knob has negative mass")) << w[0];
  EXPECT_TRUE(contains(w[1], "C_vel_pos is negative (-2 N, 95 % interval [-3, -1])")) << w[1];
  EXPECT_TRUE(contains(w[1], "moving forwards (v > 0)")) << w[1];
  EXPECT_TRUE(contains(w[1], "below 40 mm/s")) << w[1];
  for (const std::string& s : w) EXPECT_FALSE(contains(s, "mN·m") || contains(s, "rad")) << s;
}

}  // namespace
}  // namespace knoblab::fit
