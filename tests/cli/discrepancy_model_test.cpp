// Simulation versus recording: `knoblab discrepancy --model MODEL.json`
// takes the base from the model the user trusts — here the sinusoidal Eq. 6
// model of the non-sine-detents knob, its preset's own terms — and says
// what the recording has that the model lacks: the detents' shape and the
// play, with the model held as given.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "knoblab/model/models.hpp"
#include "knoblab/model/terms.hpp"
#include "knoblab/sim/presets.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;

// The knob's Eq. 6 terms and stick band in the fit's format (docs/fit.md),
// without what Eq. 6 cannot say: its detent harmonics and its play.
json sinusoidal_model(const std::string& preset) {
  const sim::KnobParams k = *sim::presets::knob(preset);
  const model::Detents<double> d = model::canonical(k.detents);
  return {{"model", "thesis6"},
          {"params",
           {{"M_acc", k.inertia.M},
            {"C_vel_neg", k.friction.C_neg},
            {"B_vel_neg", k.friction.B_neg},
            {"C_vel_pos", k.friction.C_pos},
            {"B_vel_pos", k.friction.B_pos},
            {"A_pos", d.A},
            {"P_pos", d.P},
            {"S_pos", d.S}}},
          {"stick", {{"dv", k.stick.dv}, {"D_neg", k.stick.D_neg}, {"D_pos", k.stick.D_pos}}}};
}

std::vector<std::string> named(const json& result) {
  std::vector<std::string> out;
  for (const json& f : result.at("findings")) out.push_back(f.at("effect"));
  return out;
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

TEST(DiscrepancyModel, TheNonSineKnobAgainstItsSinusoidalModelHeldFixedLacksDetentShapeAndBacklash) {
  ScratchDir dir;
  const auto at = [&](const char* name) { return (dir / name).string(); };
  const json model = sinusoidal_model("non-sine-detents");
  write_file(at("model.json"), model.dump());
  const RunResult sim = run_knoblab({"simulate", "--knob", "non-sine-detents", "--seconds", "8", "--out", at("real.csv")});
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const RunResult r = run_knoblab({"discrepancy", "--model", at("model.json"), "--input", at("real.csv"), "--json",
                                   at("r.json"), "--model-out", at("final.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("held as given"), std::string::npos) << r.out;
  const json result = json::parse(read_file(at("r.json")));
  EXPECT_EQ(result.at("base").at("source"), "given");
  const std::vector<std::string> found = named(result);
  EXPECT_TRUE(has(found, "detent_shape")) << r.out;
  EXPECT_TRUE(has(found, "backlash")) << r.out;
  // Held: the final model's Eq. 6 terms are the given ones, to the digit.
  const json final_model = json::parse(read_file(at("final.json")));
  for (const auto& [name, value] : model.at("params").items())
    EXPECT_DOUBLE_EQ(final_model.at("params").at(name).get<double>(), value.get<double>()) << name;
  EXPECT_DOUBLE_EQ(final_model.at("stick").at("D_pos").get<double>(), model.at("stick").at("D_pos").get<double>());
}

TEST(DiscrepancyModel, RefitFitsTheGivenModelsTermsToTheRecordingFirst) {
  ScratchDir dir;
  const auto at = [&](const char* name) { return (dir / name).string(); };
  json model = sinusoidal_model("moderate-detents");
  model["params"]["B_vel_pos"] = 2 * model["params"]["B_vel_pos"].get<double>();  // a model off in its damping
  write_file(at("model.json"), model.dump());
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "8", "--out", at("real.csv")}).exit_code, 0);
  const RunResult held = run_knoblab({"discrepancy", at("real.csv"), "--model", at("model.json"), "--json", at("h.json")});
  const RunResult refit = run_knoblab({"discrepancy", at("real.csv"), "--model", at("model.json"), "--refit",
                                       "--json", at("r.json"), "--model-out", at("final.json")});
  ASSERT_EQ(held.exit_code, 0) << held.err;
  ASSERT_EQ(refit.exit_code, 0) << refit.err;
  EXPECT_NE(refit.out.find("refitted from it"), std::string::npos) << refit.out;
  const json h = json::parse(read_file(at("h.json"))), r = json::parse(read_file(at("r.json")));
  EXPECT_EQ(r.at("base").at("source"), "refitted");
  // Refitted, the base finds the knob's damping and describes the recording better than the model held.
  EXPECT_LT(r.at("base").at("heldout_rmse_Nm").get<double>(), 0.8 * h.at("base").at("heldout_rmse_Nm").get<double>());
  const double B = json::parse(read_file(at("final.json"))).at("params").at("B_vel_pos");
  EXPECT_NEAR(B, sim::presets::knob("moderate-detents")->friction.B_pos, 0.2 * model["params"]["B_vel_pos"].get<double>());
}

TEST(DiscrepancyModel, ARenderModelIsABaseAndRefitWithoutAModelIsRefused) {
  ScratchDir dir;
  const auto at = [&](const char* name) { return (dir / name).string(); };
  ASSERT_EQ(run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "8", "--out", at("real.csv")}).exit_code, 0);
  ASSERT_EQ(run_knoblab({"fit", at("real.csv"), "--render-model", at("render.json")}).exit_code, 0);
  const RunResult r = run_knoblab({"discrepancy", at("real.csv"), "--model", at("render.json"), "--json", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json result = json::parse(r.out);
  EXPECT_EQ(result.at("base").at("source"), "given");
  // Eq. 14 has no detent phase: it is found, the rest held (0.70 mN·m measured; with
  // the phase held at 0 the 11 mN·m detents would leave about 8 mN·m).
  EXPECT_LT(result.at("base").at("heldout_rmse_Nm").get<double>(), 0.002) << r.out;
  const RunResult refused = run_knoblab({"discrepancy", at("real.csv"), "--refit"});
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("--refit is for a base given with --model"), std::string::npos) << refused.err;
  write_file(at("bad.json"), R"({"model": "thesis6", "params": {"M_acc": "x"}})");
  const RunResult bad = run_knoblab({"discrepancy", at("real.csv"), "--model", at("bad.json")});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.json: params: 'M_acc' is not a finite number"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace knoblab::test
