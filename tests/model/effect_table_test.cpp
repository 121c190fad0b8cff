// The effect library's one table (knoblab/model/effect_table.hpp): its rows
// hold together, specs are checked against it, a params object as
// discrepancy reports it goes back into a spec, and docs/discrepancy.md shows
// it as it is.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "knoblab/model/effect_json.hpp"
#include "knoblab/model/effect_table.hpp"

namespace knoblab::model {
namespace {

std::string refusal(const auto& make) {
  try {
    make();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

// A value inside the parameter's range, different for each parameter.
double inside(const EffectParam& p, int k) {
  const double lo = std::isfinite(p.lo) ? p.lo : 0.0;
  const double hi = std::isfinite(p.hi) ? p.hi : lo + 10.0;
  return lo + (hi - lo) * (0.1 + 0.05 * k);
}

TEST(EffectTable, EachRowSitsAtItsEffectAndIdsAreUnique) {
  std::set<std::string_view> ids;
  for (const Effect e : kAllEffects) {
    EXPECT_EQ(effect_row(e).effect, e) << effect_row(e).id;
    EXPECT_EQ(find_effect(effect_row(e).id), &effect_row(e));
    EXPECT_TRUE(ids.insert(effect_row(e).id).second) << effect_row(e).id;
  }
  EXPECT_EQ(effect_table().size(), kAllEffects.size());
  EXPECT_EQ(find_effect("cogging"), nullptr);
}

TEST(EffectTable, DefaultsLieInTheirRangesAndEveryCrossReferenceNamesAParameter) {
  for (const EffectRow& r : effect_table()) {
    bool sized = false;
    std::set<std::string_view> names;
    for (const EffectParam& p : r.params) {
      EXPECT_TRUE(names.insert(p.name).second) << r.id << "." << p.name;
      if (p.settable() && std::isfinite(p.fallback) && p.role != Role::Size) {
        EXPECT_TRUE(p.in_range(p.fallback)) << r.id << "." << p.name;
      }
      if (p.role == Role::Alternative) {
        ASSERT_NE(r.param(p.other), nullptr) << r.id << "." << p.name;
        EXPECT_TRUE(r.param(p.other)->settable()) << r.id << "." << p.name;
      }
      if (p.role == Role::Reported && !p.other.empty()) {
        EXPECT_NE(r.param(p.other), nullptr) << r.id << "." << p.name;
      }
      sized = sized || p.role == Role::Size;
    }
    EXPECT_TRUE(sized) << r.id << " has no parameter that gives it a size";
  }
}

TEST(EffectTable, OutOfRangeValuesAreRefusedNamingTheParameterAndItsRange) {
  EXPECT_NE(refusal([] { parse_effect_spec("stribeck:static_excess_Nm=0.002,stribeck_velocity_rad_s=0"); })
                .find("effect 'stribeck': stribeck_velocity_rad_s must be > 0 rad/s, not 0"),
            std::string::npos);
  EXPECT_NE(refusal([] { parse_effect_spec("periodic_torque:amplitude_Nm=0.001,period_rad=-1"); })
                .find("period_rad must be > 0 rad, not -1"),
            std::string::npos);
  EXPECT_NE(refusal([] { parse_effect_spec("nonlinear_damping:coefficient=0.1,exponent=0"); })
                .find("exponent must be > 0, not 0"),
            std::string::npos);
  EXPECT_NE(refusal([] { parse_effect_spec("gravity:amplitude_Nm=0.1,amplitude_Nm=0.2"); })
                .find("amplitude_Nm is given twice"),
            std::string::npos);
}

TEST(EffectTable, ASpecReadsItsValueOrTheDefaultAndPrintsBackInTheTablesOrder) {
  const EffectSpec s = parse_effect_spec("periodic_torque:phase_rad=0.3,amplitude_Nm=0.001");
  EXPECT_EQ(s.text(), "periodic_torque:amplitude_Nm=0.001,phase_rad=0.3");
  EXPECT_DOUBLE_EQ(s.value("period_rad"), 2 * 3.141592653589793);
  EXPECT_FALSE(s.has("period_rad"));
  EXPECT_THROW(static_cast<void>(s.value("P")), std::logic_error);  // not the table's: a programming error
  EXPECT_TRUE(std::isnan(parse_effect_spec("compliance:stiffness_Nm_per_rad=5").value("damping_Nm_s_per_rad")));
}

// A user asks for what they name; a report carries derived values beside it.
TEST(EffectTable, AReportedOnlyValueIsRefusedInTextSayingWhatToGiveInstead) {
  EXPECT_NE(refusal([] { parse_effect_spec("periodic_torque:amplitude_Nm=0.001,cycles_per_rev=17.3"); })
                .find("effect 'periodic_torque': cycles_per_rev is reported, not set (2π / period_rad); give "
                      "period_rad"),
            std::string::npos);
  EXPECT_NE(refusal([] { parse_effect_spec("detent_shape:a2_Nm=0.001,h2_amplitude_Nm=0.001"); })
                .find("h2_amplitude_Nm is reported, not set"),
            std::string::npos);
}

TEST(EffectTable, EveryParamsObjectDiscrepancyReportsGoesBackAsASpec) {
  for (const EffectRow& r : effect_table()) {
    NamedValues reported;
    int k = 0;
    for (const EffectParam& p : r.params)
      if (p.reported) reported.emplace_back(std::string(p.name), inside(p, k++));
    const EffectSpec s = effect_from_params(r.id, reported);
    for (const EffectParam& p : r.params) {
      // Set: what discrepancy fits. Left out: what it derives from them, and
      // an alternative beside the parameter it stands for.
      const bool kept = p.reported && (p.role == Role::Size || p.role == Role::Optional || p.role == Role::Required);
      EXPECT_EQ(s.has(p.name), kept) << r.id << "." << p.name;
    }
    for (const auto& [name, v] : s.params) {
      for (const auto& [n, given] : reported)
        if (n == name) {
          EXPECT_EQ(v, given) << r.id << "." << name;
        }
    }
    EXPECT_EQ(parse_effect_spec(s.text()).params, s.params) << s.text();
  }
}

TEST(EffectTable, InAReportAnAlternativeYieldsToItsParameterAndStandsForItAlone) {
  // Beside its parameter it only restates it, even out of range (no inertia
  // to ring with: 0 Hz).
  const EffectSpec both = effect_from_params(
      "compliance",
      {{"stiffness_Nm_per_rad", 40.0}, {"damping_Nm_s_per_rad", 0.01}, {"frequency_hz", 0.0}, {"zeta", 0.0}});
  EXPECT_EQ(both.text(), "compliance:stiffness_Nm_per_rad=40,damping_Nm_s_per_rad=0.01");
  const EffectSpec s = effect_from_params("compliance", {{"frequency_hz", 50.0}, {"zeta", 2.0}});
  EXPECT_TRUE(s.has("frequency_hz"));
  EXPECT_TRUE(s.has("zeta"));
  EXPECT_FALSE(s.has("stiffness_Nm_per_rad"));
  EXPECT_NE(refusal([] { effect_from_params("compliance", {{"zeta", 2.0}}); })
                .find("needs one of stiffness_Nm_per_rad, frequency_hz"),
            std::string::npos);
  EXPECT_NE(refusal([] { effect_from_params("stribeck", {{"static_excess_Nm", 0.1}, {"v_s", 1.0}}); })
                .find("has no parameter 'v_s'"),
            std::string::npos);
}

TEST(EffectTable, ReportedValuesTakeTheTablesNamesInItsOrder) {
  const NamedValues v = reported_values(Effect::PeriodicTorque, {0.001, 0.36, 17.4, 0.3});
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0].first, "amplitude_Nm");
  EXPECT_EQ(v[1].first, "period_rad");
  EXPECT_EQ(v[2].first, "cycles_per_rev");
  EXPECT_EQ(v[3].first, "phase_rad");
  // endstop's damping is the simulator's alone: position, stiffness and
  // the torque it tops out at.
  const NamedValues stop = reported_values(Effect::Endstop, {0.9, 3.0, 0.12});
  ASSERT_EQ(stop.size(), 3u);
  EXPECT_EQ(stop[2].first, "max_torque_Nm");
  EXPECT_THROW(reported_values(Effect::Endstop, {0.9, 3.0}), std::logic_error);
  // Without max_torque_Nm a stop climbs on, as a mechanical one does.
  EXPECT_EQ(parse_effect_spec("endstop:position_rad=1,stiffness_Nm_per_rad=2").value("max_torque_Nm"), kInf);
  EXPECT_THROW(parse_effect_spec("endstop:position_rad=1,stiffness_Nm_per_rad=2,max_torque_Nm=0"),
               std::invalid_argument);
}

TEST(EffectTable, ASpecGoesToJsonAndBackAndBadJsonNamesTheField) {
  const EffectSpec s = parse_effect_spec("stribeck:static_excess_Nm=0.004,stribeck_velocity_rad_s=0.5");
  const nlohmann::ordered_json j = effect_json(s);
  EXPECT_EQ(j.dump(), R"({"effect":"stribeck","params":{"static_excess_Nm":0.004,"stribeck_velocity_rad_s":0.5}})");
  EXPECT_EQ(effect_from_json(nlohmann::json::parse(j.dump())).params, s.params);
  // A finding as discrepancy writes it: its other fields are no parameters.
  const auto finding = nlohmann::json::parse(
      R"({"effect": "periodic_torque", "confidence": 0.9, "params": {"amplitude_Nm": 0.001,
          "period_rad": 0.36, "cycles_per_rev": 17.45, "phase_rad": 0.3}})");
  EXPECT_EQ(effect_from_json(finding).text(), "periodic_torque:amplitude_Nm=0.001,period_rad=0.36,phase_rad=0.3");
  EXPECT_NE(refusal([] { effect_from_json("stribeck", nlohmann::json::parse(R"({"static_excess_Nm": "4 mN·m"})")); })
                .find("effect 'stribeck': params.static_excess_Nm must be a number, not \"4 mN·m\""),
            std::string::npos);
  EXPECT_NE(refusal([] { effect_from_json(nlohmann::json::parse(R"({"params": {}})")); }).find("\"effect\""),
            std::string::npos);
}

// docs/discrepancy.md's effect table is this one (rewritten with
// KNOBLAB_UPDATE_EFFECT_DOC=1, as docs/protocol.md's command reference is).
TEST(EffectTable, TheDiscrepancyDocumentShowsTheTable) {
  const std::string begin = "<!-- BEGIN GENERATED: effect table (effect_table_markdown) -->\n";
  const std::string end = "<!-- END GENERATED -->";
  std::ifstream in(KNOBLAB_DISCREPANCY_DOC);
  ASSERT_TRUE(in) << "cannot read " << KNOBLAB_DISCREPANCY_DOC;
  std::stringstream ss;
  ss << in.rdbuf();
  std::string doc = ss.str();
  const auto b = doc.find(begin);
  ASSERT_NE(b, std::string::npos) << "marker missing: " << begin;
  const auto e = doc.find(end, b);
  ASSERT_NE(e, std::string::npos) << "marker missing: " << end;
  const std::string current = doc.substr(b + begin.size(), e - b - begin.size());
  const std::string wanted = "\n" + effect_table_markdown() + "\n";
  if (current != wanted && std::getenv("KNOBLAB_UPDATE_EFFECT_DOC")) {
    doc.replace(b + begin.size(), e - b - begin.size(), wanted);
    std::ofstream(KNOBLAB_DISCREPANCY_DOC) << doc;
    GTEST_SKIP() << "rewrote the effect table in " << KNOBLAB_DISCREPANCY_DOC;
  }
  EXPECT_EQ(current, wanted) << "docs/discrepancy.md is out of step with the effect table; "
                                "rerun this test with KNOBLAB_UPDATE_EFFECT_DOC=1";
}

}  // namespace
}  // namespace knoblab::model
