// knoblab discrepancy on real recordings: the ODrive gimbal motor
// (../shared/datasets/odrive-cogging), turned once round at 0.1 rev/s under
// velocity control without anti-cogging. Its cogging has components near
// 7, 12, 14, 28, 36 and 84 cycles per revolution (the dataset's README).
// Trained on one recording, scored on another it did not see; time stamps
// from the host PC are irregular (1.5–4.7 ms).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "odrive_data.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

nlohmann::json discrepancy(const ScratchDir& dir, const std::string& train, const std::string& held,
                           std::string* out) {
  for (const std::string& name : {train, held}) {
    const RunResult c = run_knoblab(odrive_args(odrive_dir() / "slow2" / (name + ".mat"), dir / (name + ".csv")));
    EXPECT_EQ(c.exit_code, 0) << c.err;
  }
  const RunResult r = run_knoblab({"discrepancy", "--input", (dir / (train + ".csv")).string(), "--heldout",
                                   (dir / (held + ".csv")).string(), "--max-findings", "8", "--json",
                                   (dir / "r.json").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  *out = r.out;
  std::ifstream f(dir / "r.json");
  return nlohmann::json::parse(f);
}

TEST(OdriveDiscrepancy, CoggingHarmonicsNamedWithTheirCyclesPerRevAndAnUnseenRecordingFitsBetter) {
  REQUIRE_DATASET();
  ScratchDir dir;
  std::string out;
  const nlohmann::json r = discrepancy(dir, "nocomp_0", "nocomp_1", &out);
  EXPECT_NE(out.find("resampled"), std::string::npos) << out;  // irregular stamps noticed

  // The base model's detent term takes the strongest component, 7 per rev.
  EXPECT_NEAR(1.0 / r["base"]["params"]["P_pos"].get<double>(), 7.0, 0.1);
  bool shape = false, twelve = false;
  for (const auto& f : r["findings"]) {
    const auto& p = f["params"];
    if (f["effect"] == "detent_shape") {
      shape = true;  // its 2nd and 4th harmonics: 14 and 28 per rev, each ≈ 10 mN·m
      EXPECT_NEAR(p["h2_cycles_per_rev"].get<double>(), 14.0, 0.2);
      EXPECT_NEAR(p["h4_cycles_per_rev"].get<double>(), 28.0, 0.4);
      EXPECT_GT(p["h2_amplitude_Nm"].get<double>(), 0.005);
      EXPECT_GT(p["h4_amplitude_Nm"].get<double>(), 0.005);
    }
    if (f["effect"] == "periodic_torque" && std::abs(p["cycles_per_rev"].get<double>() - 12.0) < 0.3) twelve = true;
    EXPECT_LT(f["heldout_rmse_after_Nm"].get<double>(), f["heldout_rmse_before_Nm"].get<double>());
  }
  EXPECT_TRUE(shape) << r["findings"].dump(1);
  EXPECT_TRUE(twelve) << r["findings"].dump(1);
  // On the recording the fit did not see: 14 → 7 mN·m when measured.
  EXPECT_LT(r["final"]["heldout_rmse_Nm"].get<double>(), 0.7 * r["base"]["heldout_rmse_Nm"].get<double>());
  // The base model's viscous term comes out negative for the direction the
  // motor never turned, and integrated at the host's 435 Hz it runs away:
  // the forward view says "not available" (null), not 10⁷ mrad.
  for (const char* m : {"base", "final"}) {
    const auto& fw = r[m]["forward_rmse_rad"];
    EXPECT_TRUE(fw.is_null() || fw.get<double>() < 0.05) << m << ": " << fw;
  }
}

TEST(OdriveDiscrepancy, WithAntiCoggingTheCurrentCarriesTheSameMapAndThe36PerRevComponent) {
  // Anti-cogging feed-forward cancels cogging in the motion, so the current
  // that does it carries the cogging map; the smoother motion lets the
  // weaker 36-per-revolution component through as well.
  REQUIRE_DATASET();
  ScratchDir dir;
  std::string out;
  const nlohmann::json r = discrepancy(dir, "comp_0", "comp_1", &out);
  bool twelve = false, thirty_six = false;
  for (const auto& f : r["findings"]) {
    if (f["effect"] != "periodic_torque") continue;
    const double c = f["params"]["cycles_per_rev"].get<double>();
    twelve = twelve || std::abs(c - 12.0) < 0.3;
    thirty_six = thirty_six || std::abs(c - 36.0) < 0.5;
  }
  EXPECT_TRUE(twelve && thirty_six) << out;
  EXPECT_LT(r["final"]["heldout_rmse_Nm"].get<double>(), 0.5 * r["base"]["heldout_rmse_Nm"].get<double>());
}

TEST(OdriveDiscrepancy, OneRecordingAloneIsHeldOutInBlocksFineEnoughToInterleaveItsAngles) {
  // One slow revolution passes each angle once: held out in 32 time blocks,
  // the training would never see 16 stretches of angle, and its angles,
  // sampled 16 times per revolution, alias the cogging (28/rev reads as 12).
  // Discovery cuts such a recording finer (JSON "blocks") and the cogging
  // is found without a second recording.
  REQUIRE_DATASET();
  ScratchDir dir;
  const RunResult c = run_knoblab(odrive_args(odrive_dir() / "slow2" / "nocomp_0.mat", dir / "n0.csv"));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const RunResult r = run_knoblab({"discrepancy", "--input", (dir / "n0.csv").string(), "--max-findings", "8",
                                   "--json", (dir / "r.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream f(dir / "r.json");
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_GT(j["blocks"].get<int>(), 32);
  bool shape = false, twelve = false;
  for (const auto& finding : j["findings"]) {
    shape = shape || finding["effect"] == "detent_shape";
    twelve = twelve || (finding["effect"] == "periodic_torque" &&
                        std::abs(finding["params"]["cycles_per_rev"].get<double>() - 12.0) < 0.3);
  }
  EXPECT_TRUE(shape && twelve) << r.out;
  EXPECT_LT(j["final"]["heldout_rmse_Nm"].get<double>(), 0.8 * j["base"]["heldout_rmse_Nm"].get<double>());
}

}  // namespace
}  // namespace knoblab::test
