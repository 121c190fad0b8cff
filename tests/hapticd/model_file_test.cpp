// Model files as load_model's arguments (hapticd --model, knoblab ctl
// load_model FILE), and the effects in them as the renderer takes them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <numbers>
#include <string>

#include "knoblab/control/schema.hpp"
#include "knoblab/hapticd/control_handler.hpp"
#include "knoblab/hapticd/model_file.hpp"
#include "knoblab/hapticd/render_effects.hpp"

namespace knoblab::hapticd {
namespace {

using nlohmann::json;

// As knoblab discrepancy --model-out writes one (docs/discrepancy.md).
json model_file(json effects) {
  return {{"model", "thesis6"},
          {"params", {{"M_acc", 5e-5}, {"C_vel_neg", 0.001}, {"B_vel_neg", 5e-4}, {"C_vel_pos", 0.001},
                      {"B_vel_pos", 5e-4}, {"A_pos", 0.011}, {"P_pos", 0.0833}, {"S_pos", 0.4}}},
          {"stick", {{"dv", 0.02}, {"D_neg", 0.012}, {"D_pos", 0.013}}},
          {"effects", std::move(effects)},
          {"render", {{"M_acc", 5e-5}, {"B_vel", 9e-4}, {"A_pos", 0.011}, {"P_pos", 0.0833},
                      {"dv", 0.02}, {"D_neg", 0.012}, {"D_pos", 0.013}}},
          {"source", {{"command", "knoblab discrepancy"}}}};
}

json effect(const char* id, json params) { return {{"effect", id}, {"params", std::move(params)}}; }

TEST(ModelFile, ADiscrepancyModelBecomesLoadModelArgumentsTheSchemaAccepts) {
  const json args = load_model_args(
      model_file({effect("gravity", {{"amplitude_Nm", 0.004}, {"phase_rad", 1.2}}),
                  effect("periodic_torque",
                         {{"amplitude_Nm", 0.001}, {"period_rad", 0.36316811075498007}, {"cycles_per_rev", 17.3}, {"phase_rad", 0.3}}),
                  effect("periodic_torque", {{"amplitude_Nm", 0.0005}, {"period_rad", 0.02 * 2 * std::numbers::pi}, {"phase_rad", 0.0}}),
                  effect("stribeck", {{"static_excess_Nm", 0.002}, {"stribeck_velocity_rad_s", 0.1}})}),
      "m.json");
  EXPECT_EQ(args.at("B_vel"), 9e-4);  // the render model, not the thesis6 params
  EXPECT_EQ(args.at("effects").at("periodic_torque").size(), 2u);
  // The value derived beside the period is not an argument.
  EXPECT_FALSE(args.at("effects").at("periodic_torque")[0].contains("cycles_per_rev"));
  const auto& spec = control::command_spec(control::Command::load_model);
  const auto problem = control::validate_args(args, spec.args);
  EXPECT_FALSE(problem) << problem->key << " " << problem->problem;
  const RenderParams p = render_params_from_args(args, {}, false);
  EXPECT_TRUE(p.stick);
  EXPECT_EQ(p.effects.gravity.A, 0.004);
  EXPECT_EQ(p.effects.gravity.phase, 1.2);
  ASSERT_EQ(p.effects.periodic_count, 2u);
  EXPECT_DOUBLE_EQ(p.effects.periodic[1].P, 0.02);  // A·sin(2πθ/period_rad + φ) = A·sin(θ/P + S)
  EXPECT_EQ(p.effects.stribeck.v_s, 0.1);
  EXPECT_FALSE(render_params_problem(p, SafetyLimits{}));
}

// A design's rendered wall, as discrepancy fits it: a stiff ramp that holds
// at a torque. hapticd renders it holding there, not climbing on.
TEST(ModelFile, AWallThatTopsOutIsRenderedHoldingAtItsMaximumTorque) {
  const json args = load_model_args(
      model_file({effect("endstop", {{"position_rad", 1.07}, {"stiffness_Nm_per_rad", 1.2}, {"max_torque_Nm", 0.114}})}),
      "fan.json");
  const auto problem = control::validate_args(args, control::command_spec(control::Command::load_model).args);
  EXPECT_FALSE(problem) << problem->key << " " << problem->problem;
  const RenderParams p = render_params_from_args(args, {}, false);
  EXPECT_FALSE(render_params_problem(p, SafetyLimits{}));
  EXPECT_NEAR(p.effects.held(1.07 + 0.05, 0.0), 1.2 * 0.05, 1e-12);  // on the ramp
  EXPECT_DOUBLE_EQ(p.effects.held(1.07 + 0.5, 0.0), 0.114);          // K·depth would be 0.6 N·m
  EXPECT_DOUBLE_EQ(p.effects.held(-1.07 - 0.5, 0.0), -0.114);
  // Without a maximum it is a mechanical stop: it climbs on (the supervisor clips it).
  const RenderParams stop = render_params_from_args(
      load_model_args(model_file({effect("endstop", {{"position_rad", 1.07}, {"stiffness_Nm_per_rad", 1.2}})}), "m.json"),
      {}, false);
  EXPECT_DOUBLE_EQ(stop.effects.held(1.07 + 0.5, 0.0), 0.6);
}

TEST(ModelFile, AWallThatTopsOutBeyondTheTorqueLimitIsRefusedNamingItsKey) {
  const RenderParams p = render_params_from_args(
      load_model_args(model_file({effect("endstop", {{"position_rad", 1.0}, {"stiffness_Nm_per_rad", 5.0}, {"max_torque_Nm", 0.3}})}),
                      "m.json"),
      {}, false);
  const auto problem = render_params_problem(p, SafetyLimits{});
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->key, "effects.endstop.max_torque_Nm");
  EXPECT_NE(problem->message.find("300 mN·m is beyond the device's torque limit of 180 mN·m"), std::string::npos)
      << problem->message;
}

TEST(ModelFile, EffectsTheRendererCannotRenderAreRefusedEachNamedWithWhy) {
  try {
    load_model_args(model_file({effect("gravity", {{"amplitude_Nm", 0.004}}), effect("backlash", {{"width_rad", 0.003}}),
                                effect("time_delay", {{"delay_s", 0.001}})}),
                    "m.json");
    FAIL() << "rendered a model with backlash and a delay";
  } catch (const ModelFileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("m.json"), std::string::npos) << what;
    EXPECT_NE(what.find("cannot render backlash ("), std::string::npos) << what;
    EXPECT_NE(what.find("and time_delay ("), std::string::npos) << what;
    EXPECT_NE(what.find("Remove them from \"effects\""), std::string::npos) << what;
    EXPECT_EQ(what.find("gravity"), std::string::npos) << what;
  }
}

TEST(ModelFile, SimulatesOldNamesAreRefusedNamingTheTablesOnes) {
  try {
    load_model_args(model_file({effect("stribeck", {{"excess", 0.002}, {"v_s", 0.1}})}), "m.json");
    FAIL() << "took simulate's old names";
  } catch (const ModelFileError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("m.json: effects[0]: "), std::string::npos) << what;
    EXPECT_NE(what.find("static_excess_Nm"), std::string::npos) << what;
  }
}

TEST(ModelFile, AnUnknownEffectIsRefusedListingTheKnownOnes) {
  try {
    load_model_args(model_file({effect("magnetism", {{"amplitude_Nm", 0.1}})}), "m.json");
    FAIL();
  } catch (const ModelFileError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown effect 'magnetism' (known: offset, gravity"), std::string::npos)
        << e.what();
  }
}

TEST(ModelFile, AFitResultWithoutARenderModelIsRefusedSayingWhatToWrite) {
  json fit = model_file(json::array());
  fit.erase("render");
  fit.erase("effects");
  try {
    load_model_args(fit, "fit.json");
    FAIL();
  } catch (const ModelFileError& e) {
    EXPECT_NE(std::string(e.what()).find("knoblab fit --render-model"), std::string::npos) << e.what();
  }
}

TEST(ModelFile, ARenderModelFilesParamsAreTheArguments) {
  const json render = {{"model", "render4"}, {"params", {{"M_acc", 5e-5}, {"B_vel", 9e-4}, {"A_pos", 0.011}, {"P_pos", 0.0833}}}};
  EXPECT_EQ(load_model_args(render, "r.json"), render.at("params"));
}

TEST(RenderEffects, ATermBeyondTheTorqueLimitIsRefusedNamingItsKey) {
  model::EffectSet<double> e;
  e.periodic[0].A = 0.001;
  e.periodic[1].A = -0.5;
  e.periodic_count = 2;
  const auto problem = effects_problem(e, SafetyLimits{});
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->key, "effects.periodic_torque[1].amplitude_Nm");
  EXPECT_NE(problem->message.find("beyond the device's torque limit"), std::string::npos);
  e.periodic[1].A = 0.05;
  EXPECT_FALSE(effects_problem(e, SafetyLimits{}));
}

TEST(RenderEffects, SetParamsWithoutEffectsKeepsThemAndLoadModelClearsThem) {
  RenderParams p;
  p.effects.offset.tau0 = 0.01;
  EXPECT_EQ(render_params_from_args({{"B_vel", 0.001}}, p, true).effects.offset.tau0, 0.01);
  EXPECT_EQ(render_params_from_args({{"M_acc", 0}, {"B_vel", 0.001}, {"A_pos", 0}, {"P_pos", 1}}, p, false)
                .effects.offset.tau0,
            0.0);
}

}  // namespace
}  // namespace knoblab::hapticd
