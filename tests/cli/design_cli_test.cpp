// knoblab design: a design checked as hapticd would, its render model out and
// back, and the fan knob played on the simulated knob: the capture shows its
// four detents and both walls.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "knoblab/design/design_json.hpp"
#include "knoblab/design/edits.hpp"
#include "knoblab/design/templates.hpp"
#include "knoblab/hapticd/render_controller.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/model/render_stability.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

using ::testing::HasSubstr;

const std::string kFanKnob = std::string(KNOBLAB_EXAMPLES_DIR) + "/designs/fan-knob.json";
constexpr double kDeg = std::numbers::pi / 180.0;

TEST(DesignCli, TheFanKnobChecksAsADesignHapticdWouldPlay) {
  const RunResult r = run_knoblab({"design", "check", kFanKnob});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\"fan knob\""));
  EXPECT_THAT(r.out, HasSubstr("position     1 line(s), 3 tile(s)"));
  EXPECT_THAT(r.out, HasSubstr("hapticd would play it."));
}

TEST(DesignCli, ATimeLineOfTilesThatLoopsChecksAsADesignHapticdWouldPlay) {
  ScratchDir dir;
  design::Design d = design::read_design(kFanKnob);
  const design::Tile pulse{"pulse", {{{0.0, 0.0}, {0.05, 0.02}, {0.1, 0.0}}, false}, design::Channel::Time};
  design::place_tile(d, design::Channel::Time, 0, pulse, 0.0, 0.1);
  design::place_tile(d, design::Channel::Time, 0, pulse, 0.5, 0.6);
  design::set_time_loop(d, true);
  const auto file = (dir / "pulses.json").string();
  design::write_design(file, d);
  const RunResult r = run_knoblab({"design", "check", file});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("time         1 line(s), 2 tile(s)"));
  EXPECT_THAT(r.out, HasSubstr("hapticd would play it."));
}

TEST(DesignCli, AMalformedDesignIsRefusedNamingTheFileAndTheKey) {
  ScratchDir dir;
  nlohmann::json j = nlohmann::json::parse(read_file(kFanKnob));
  j["channels"]["position"]["lines"][0]["tiles"][0]["from"] = "left";
  std::ofstream(dir / "bad.json") << j.dump();
  const RunResult r = run_knoblab({"design", "check", (dir / "bad.json").string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("bad.json: channels.position.lines[0].tiles[0].from: expected a number, got \"left\""));
}

TEST(DesignCli, AnExportedRenderModelImportsBackToADesignThatExportsTheSame) {
  ScratchDir dir;
  const auto model = (dir / "model.json").string(), back = (dir / "back.json").string(),
             again = (dir / "again.json").string();
  ASSERT_EQ(run_knoblab({"design", "export", kFanKnob, "--out", model}).exit_code, 0);
  const RunResult r = run_knoblab({"design", "import", model, "--out", back, "--name", "fan knob"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(run_knoblab({"design", "export", back, "--out", again}).exit_code, 0);
  EXPECT_EQ(nlohmann::json::parse(read_file(again)), nlohmann::json::parse(read_file(model)));
}

// The recorded torque binned by angle on the way across (θ rising).
struct Profile {
  std::vector<double> theta, torque;
};

Profile rising_profile(const interchange::Capture& c, double bin) {
  const double lo = *std::min_element(c.theta.begin(), c.theta.end());
  const double hi = *std::max_element(c.theta.begin(), c.theta.end());
  const auto n = static_cast<std::size_t>((hi - lo) / bin) + 1;
  std::vector<double> sum(n, 0.0), count(n, 0.0);
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!(c.omega[i] > 0.05)) continue;
    const auto k = static_cast<std::size_t>((c.theta[i] - lo) / bin);
    sum[k] += c.torque[i];
    count[k] += 1;
  }
  Profile p;
  for (std::size_t k = 0; k < n; ++k)
    if (count[k] > 0) {
      p.theta.push_back(lo + (static_cast<double>(k) + 0.5) * bin);
      p.torque.push_back(sum[k] / count[k]);
    }
  return p;
}

TEST(DesignCli, TheFanKnobPlayedOnTheSimulatedKnobShowsFourDetentsAndBothWallsInTheRecordedTorque) {
  ScratchDir dir;
  const auto csv = (dir / "fan.csv").string();
  const RunResult r = run_knoblab({"design", "render", kFanKnob, "--seconds", "16", "--rate", "5000", "--out", csv});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const interchange::Capture c = interchange::read_csv(csv);
  EXPECT_EQ(c.size(), 16u * 5000u);
  // The hand reached both walls: the knob went beyond ±60° but was held
  // back from the hand's target, 94° out, by the walls' 120 mN·m.
  const double lo = *std::min_element(c.theta.begin(), c.theta.end());
  const double hi = *std::max_element(c.theta.begin(), c.theta.end());
  EXPECT_LT(lo, -65 * kDeg);
  EXPECT_GT(lo, -92 * kDeg);
  EXPECT_GT(hi, 65 * kDeg);
  EXPECT_LT(hi, 92 * kDeg);

  const Profile p = rising_profile(c, 0.5 * kDeg);
  // The torque sensor reads the motor's push on the knob, the opposite of
  // the torque the design resists with: a detent rests where the reading
  // falls through zero. One near each setting, none elsewhere between the walls.
  std::vector<double> rests;
  for (std::size_t k = 1; k < p.theta.size(); ++k)
    if (std::abs(p.theta[k]) < 58 * kDeg && p.torque[k - 1] > 0 && p.torque[k] <= 0) rests.push_back(p.theta[k]);
  // Turning, the knob's own friction and damping shift the crossings a little.
  ASSERT_EQ(rests.size(), 4u) << "rests found: " << ::testing::PrintToString(rests);
  const double settings[] = {-45, -15, 15, 45};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(rests[i] / kDeg, settings[i], 3.0) << i;
  // The walls: beyond ±60° the motor pushes back far harder than any
  // detent's 10 mN·m, towards the middle.
  double wall_hi = 0.0, wall_lo = 0.0;
  for (std::size_t k = 0; k < p.theta.size(); ++k) {
    if (p.theta[k] > 62 * kDeg) wall_hi = std::min(wall_hi, p.torque[k]);
    if (p.theta[k] < -62 * kDeg) wall_lo = std::max(wall_lo, p.torque[k]);
  }
  EXPECT_LT(wall_hi, -0.08);
  EXPECT_GT(wall_lo, 0.08);
  // Nothing rang: the command stayed inside the torque limit's 12 V.
  EXPECT_LT(*std::max_element(c.command.begin(), c.command.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }),
            11.0);
}

// The fan knob rendered, then read back as knoblab discrepancy reads any
// knob: Eq. 6 (inertia, friction, detents) and what it lacks. The torque it
// takes to turn the rendered knob (--torque knob) is what Eq. 6 describes;
// the walls' 120 mN·m outbid the detents' 10 mN·m in the base's first search
// (a once-per-revolution "detent" of 96 mN·m), so the detents are found
// between the walls with the walls taken out, and the walls come back as an
// end stop that tops out, as the wall template does.
TEST(DesignCli, AFitOfTheFanKnobsRecordingFindsItsFourDetentsAndBothWalls) {
  ScratchDir dir;
  const auto csv = (dir / "fan.csv").string(), out = (dir / "fan.json").string();
  const RunResult r = run_knoblab(
      {"design", "render", kFanKnob, "--seconds", "4", "--rate", "5000", "--torque", "knob", "--out", csv});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunResult fit = run_knoblab({"discrepancy", csv, "--json", out});
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  const nlohmann::json j = nlohmann::json::parse(read_file(out));
  const nlohmann::json& p = j.at("final").at("params");

  // The detents: 12 per revolution at the template's 10 mN·m, A·sin(θ/P + S).
  const double A = p.at("A_pos").get<double>(), P = p.at("P_pos").get<double>(), S = p.at("S_pos").get<double>();
  EXPECT_NEAR(1.0 / P, 12.0, 0.2) << "detents per revolution\n" << j.dump(1);
  EXPECT_NEAR(std::abs(A), 0.010, 0.003) << "N·m";
  // Each rests where the torque rises through zero: near Off, Lo, Med and
  // Hi, and nowhere else between the walls.
  std::vector<double> rests;
  const auto tau = [&](double th) { return A * std::sin(th / P + S); };
  for (double th = -60 * kDeg; th < 60 * kDeg; th += 0.1 * kDeg)
    if (tau(th) < 0 && tau(th + 0.1 * kDeg) >= 0) rests.push_back(th + 0.05 * kDeg);
  ASSERT_EQ(rests.size(), 4u) << ::testing::PrintToString(rests);
  const double settings[] = {-45, -15, 15, 45};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(rests[i] / kDeg, settings[i], 3.0) << i;

  // The walls: an end stop at ±60°, both ways, that tops out near the
  // template's 120 mN·m, and the held-out error it takes away.
  const nlohmann::json* stop = nullptr;
  for (const nlohmann::json& f : j.at("findings"))
    if (f.at("effect") == "endstop") stop = &f;
  ASSERT_NE(stop, nullptr) << j.dump(1);
  const nlohmann::json& q = stop->at("params");
  EXPECT_NEAR(q.at("position_rad").get<double>() / kDeg, 60.0, 3.0);
  EXPECT_GT(q.at("stiffness_Nm_per_rad").get<double>(), 0.4);
  ASSERT_TRUE(q.contains("max_torque_Nm")) << q.dump();
  EXPECT_NEAR(q.at("max_torque_Nm").get<double>(), 0.120, 0.015);
  EXPECT_LT(stop->at("heldout_rmse_after_Nm").get<double>(), 0.2 * stop->at("heldout_rmse_before_Nm").get<double>());
  EXPECT_LT(j.at("final").at("heldout_rmse_Nm").get<double>(), 0.010) << "N·m";
}

// A spring through 0 of stiffness K over ±0.12 N·m: the stiffest thing a
// design holds, so the one the loop's stable region bounds.
std::string spring_design(const ScratchDir& dir, const std::string& name, double K) {
  const double a = 0.12 / K;
  design::Design d = design::new_design(name);
  design::place_tile(d, design::Channel::Position, 0,
                     design::Tile{"spring", {{{-a, -0.12}, {0.0, 0.0}, {a, 0.12}}, false}, design::Channel::Position}, -a, a);
  const auto file = (dir / (name + ".json")).string();
  design::write_design(file, d);
  return file;
}

TEST(DesignCli, ADesignStifferThanTheLoopRendersStablyIsRefusedWithTheReasonAndOneJustInsideRendersWithoutRinging) {
  ScratchDir dir;
  constexpr double kRate = 5000;
  const double k_max = model::max_stiffness(hapticd::RenderController::loop_dynamics(kRate), 0.0);
  ASSERT_GT(k_max, 10.0);

  const std::string beyond = spring_design(dir, "beyond", 1.2 * k_max);
  const RunResult refused = run_knoblab({"design", "render", beyond, "--seconds", "2", "--rate", "5000", "--out",
                                         (dir / "beyond.csv").string()});
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, HasSubstr("hapticd would refuse this design: position[0].torque: its stiffness reaches"));
  EXPECT_THAT(refused.err, HasSubstr("beyond the 5 kHz loop's stable"));
  EXPECT_FALSE(std::filesystem::exists(dir / "beyond.csv"));

  const std::string inside = spring_design(dir, "inside", 0.9 * k_max);
  const auto csv = (dir / "inside.csv").string();
  const RunResult played = run_knoblab({"design", "render", inside, "--seconds", "4", "--rate", "5000", "--out", csv});
  ASSERT_EQ(played.exit_code, 0) << played.err;
  const interchange::Capture c = interchange::read_csv(csv);
  // The hand turns across the spring's ±0.12 N·m in seconds: the knob moves
  // by fractions of a milliradian, slowly. Ringing would swing it at
  // hundreds of hertz, far faster.
  double fastest = 0.0;
  for (const double w : c.omega) fastest = std::max(fastest, std::abs(w));
  EXPECT_LT(fastest, 0.05) << "rad/s";
}

}  // namespace
}  // namespace knoblab::test
