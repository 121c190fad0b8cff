// The researcher's loop, end to end with the real binaries: a knob
// simulated, fitted, its fit simulated and fitted again; and discrepancy's
// final model written as a model file, simulated, and rendered by hapticd
// on the sim backend (a simulated hand turning the knob) with the torque the
// model says. Deadlines only bound waits; nothing asserts how long anything took.
#include <gtest/gtest.h>

#include <numbers>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "hapticd_process.hpp"
#include "knoblab/control/telemetry_reader.hpp"
#include "knoblab/model/models.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;
using namespace std::chrono_literals;

json read_json(const std::string& path) { return json::parse(read_file(path)); }

void run_ok(const std::vector<std::string>& args) {
  const RunResult r = run_knoblab(args);
  ASSERT_EQ(r.exit_code, 0) << args.front() << ": " << r.err << r.out;
}

// Where each fitted parameter of `b` lies against `a`'s 95 % interval: the
// names outside, with by how many half-widths. Not M_acc: the fit reads it
// 3–7 % low from the accelerometer's α (its noise attenuates the regression,
// errors in variables; cli.ThesisKnobs.*), more than its interval, so each
// pass of the loop loses that again.
std::vector<std::string> outside(const json& a, const json& b) {
  std::vector<std::string> out;
  for (const auto& [name, ci] : a.at("ci95").items()) {
    if (name == "M_acc") continue;
    if (ci.is_null() || b.at("ci95").at(name).is_null()) continue;  // held: no detents
    const double lo = ci[0], hi = ci[1], v = b.at("params").at(name);
    if (v >= lo && v <= hi) continue;
    const double half = (hi - lo) / 2, mid = (hi + lo) / 2;
    out.push_back(name + " (" + std::to_string((v - mid) / half) + " half-widths)");
  }
  return out;
}

TEST(Loop, AFitSimulatedAndFittedAgainLiesInsideTheFirstFitsIntervals) {
  ScratchDir dir;
  const auto at = [&](const char* name) { return (dir / name).string(); };
  run_ok({"simulate", "--knob", "moderate-detents", "--out", at("a.csv")});
  run_ok({"fit", "--input", at("a.csv"), "--json", at("a.fit.json")});
  run_ok({"simulate", "--params", at("a.fit.json"), "--seed", "2", "--out", at("b.csv")});
  run_ok({"fit", "--input", at("b.csv"), "--json", at("b.fit.json")});
  const json a = read_json(at("a.fit.json")), b = read_json(at("b.fit.json"));
  ASSERT_TRUE(a.at("detents").at("present").get<bool>());
  EXPECT_EQ(outside(a, b), std::vector<std::string>{}) << "second fit against the first's intervals";
  EXPECT_EQ(outside(b, a), std::vector<std::string>{}) << "first fit against the second's intervals";
  // M_acc: the second fit a few per cent under the first (3.2 % measured).
  const double ratio = b.at("params").at("M_acc").get<double>() / a.at("params").at("M_acc").get<double>();
  const json& m = a.at("ci95").at("M_acc");
  const double half = (m[1].get<double>() - m[0].get<double>()) / 2 / a.at("params").at("M_acc").get<double>();
  EXPECT_GT(ratio, 0.90);
  EXPECT_LT(ratio, 1.0 + half);
  // knoblab compare says the same.
  const RunResult c = run_knoblab({"compare", at("a.fit.json"), at("b.fit.json"), "--json", "-"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_TRUE(json::parse(c.out).at("apart").empty()) << c.out;
}

// The renderer's torque for one telemetry record, from the model file's
// render model and effects through the model core (as hapticd renders it,
// its virtual mass at rest). `with_effects` false: the bare Eq. 14.
double rendered(const json& file, const control::TelemetryRecord& r, bool with_effects) {
  const json& p = file.at("render");
  model::RenderModel<double> m;
  m.B_vel = p.at("B_vel");
  m.detents.A = p.at("A_pos");
  m.detents.P = p.at("P_pos");
  if (p.contains("dv")) {
    m.stick_enabled = true;
    m.stick = {p.at("dv").get<double>(), p.at("D_neg").get<double>(), p.at("D_pos").get<double>()};
  }
  if (with_effects) {
    for (const json& e : file.at("effects")) {
      if (e.at("effect") != "periodic_torque") continue;
      model::Detents<double>& w = m.effects.periodic[m.effects.periodic_count++];
      w.A = e.at("params").at("amplitude_Nm");
      w.P = e.at("params").at("period_rad").get<double>() / (2 * std::numbers::pi);
      w.S = e.at("params").at("phase_rad");
    }
  }
  return m.torque({r.theta, r.omega, 0.0}, r.torque);
}

TEST(Loop, DiscrepancysModelFileSimulatesAndRendersInHapticdWithItsEffect) {
  ScratchDir dir;
  const auto at = [&](const char* name) { return (dir / name).string(); };
  // 4 mN·m of cogging at 17.3 cycles/rev beside the 11 mN·m detents.
  run_ok({"simulate", "--knob", "moderate-detents", "--seconds", "8", "--effects",
          "periodic_torque:amplitude_Nm=0.004,period_rad=0.36316811075498007,phase_rad=0.3", "--out", at("cogged.csv")});
  run_ok({"discrepancy", "--input", at("cogged.csv"), "--model-out", at("model.json")});
  const json file = read_json(at("model.json"));
  ASSERT_EQ(file.at("effects").size(), 1u) << file.dump(1);
  const json& cog = file.at("effects")[0];
  ASSERT_EQ(cog.at("effect"), "periodic_torque") << file.dump(1);
  EXPECT_NEAR(2 * std::numbers::pi / cog.at("params").at("period_rad").get<double>(), 1.0 / 0.0578, 0.3);
  EXPECT_NEAR(std::abs(cog.at("params").at("amplitude_Nm").get<double>()), 0.004, 0.0008);

  // The model file simulates, its effect in the plant.
  run_ok({"simulate", "--params", at("model.json"), "--seconds", "2", "--out", at("again.csv")});
  EXPECT_NE(read_file(at("again.csv")).find("# effects: periodic_torque:"), std::string::npos);

  // hapticd renders it: on the sim backend a hand turns the knob on the
  // device (the camera's moderate-detents knob) back and forth, and the
  // motor pushes back with the model's torque.
  write_file(at("daq.json"), R"({"backend": "sim", "knob": "moderate-detents",
      "hand": {"amplitude_rad": 0.6, "frequency_hz": 0.5, "stiffness": 1.0}})");
  const std::string shm = "/knoblab-loop-test-" + std::to_string(::getpid());
  Hapticd d(shm, {"--daq-config", at("daq.json")});
  ASSERT_TRUE(d.ready()) << d.log();
  const RunResult load = run_knoblab({"ctl", "--socket", d.socket(), "load_model", at("model.json")});
  ASSERT_EQ(load.exit_code, 0) << load.err;
  ASSERT_EQ(run_knoblab({"ctl", "--socket", d.socket(), "set_mode", "mode=render"}).exit_code, 0);
  control::TelemetryReader reader(shm, control::TelemetryReader::Start::newest);
  std::vector<control::TelemetryRecord> records, batch(256);
  // One turn of the hand (2 s), from the knob's first upward zero crossing
  // after render mode's first 0.3 s (the model's parameters ramp in over
  // 50 ms, the filters settle): a window fixed in simulated time (render
  // mode's t) and in the hand's phase. Records counted from whenever the
  // test got to set the mode put the window at another phase on a loaded
  // host, and the figures below moved with it (1.25 against 1.2 mN·m).
  constexpr double kSettle_s = 0.3, kHandPeriod_s = 2.0;
  double t0 = -1.0, last_theta = 0.0;
  bool have_last = false, turned = false;
  ASSERT_TRUE(eventually([&] {
    for (auto got = reader.read(batch); got.count > 0 && !turned; got = reader.read(batch))
      for (std::size_t i = 0; i < got.count && !turned; ++i) {
        const control::TelemetryRecord& r = batch[i];
        if (r.mode != 1 || r.t < kSettle_s) {
          have_last = false;
          continue;
        }
        if (t0 < 0.0) {
          if (have_last && last_theta < 0.0 && r.theta >= 0.0) t0 = r.t;
          last_theta = r.theta;
          have_last = true;
          if (t0 < 0.0) continue;
        }
        if (r.t >= t0 + kHandPeriod_s) turned = true;
        else records.push_back(r);
      }
    return turned;
  })) << records.size() << " render-mode records of a turn\n" << d.log();

  // Each record's commanded torque is the model's at its θ, θ̇ (what is
  // left is the virtual mass's inertia torque, not in the telemetry); the
  // sensor between motor and knob reads the motor's push, −τ. The cogging
  // the model adds is there at its size (regressed on, slope 1), and
  // leaving it out would be seen.
  double sxy = 0, sxx = 0, cmd_with = 0, cmd_without = 0, sensed_with = 0, sensed_without = 0, moved = 0;
  for (const control::TelemetryRecord& r : records) {
    const double with = rendered(file, r, true), without = rendered(file, r, false);
    cmd_with += (r.command - with) * (r.command - with);
    cmd_without += (r.command - without) * (r.command - without);
    sensed_with += (r.torque + with) * (r.torque + with);
    sensed_without += (r.torque + without) * (r.torque + without);
    sxy += (r.command - without) * (with - without);
    sxx += (with - without) * (with - without);
    moved = std::max(moved, std::abs(r.theta));
  }
  const auto rms = [n = static_cast<double>(records.size())](double sum) { return std::sqrt(sum / n); };
  std::printf("a turn rendered: %zu records; command off the model %.3f mN·m RMS (%.3f without the cogging), "
              "sensed %.3f (%.3f)\n",
              records.size(), 1e3 * rms(cmd_with), 1e3 * rms(cmd_without), 1e3 * rms(sensed_with),
              1e3 * rms(sensed_without));
  EXPECT_GT(moved, 0.5) << "the hand turned the knob";
  EXPECT_LT(rms(cmd_with), 1.2e-3) << "commanded torque off the model, RMS N·m";
  EXPECT_LT(rms(cmd_with), 0.5 * rms(cmd_without)) << "without the cogging the model is further off";
  EXPECT_LT(rms(sensed_with), 1.2e-3) << "sensed torque off the model, RMS N·m";
  EXPECT_LT(rms(sensed_with), 0.5 * rms(sensed_without));
  ASSERT_GT(sxx, 0.0);
  EXPECT_NEAR(sxy / sxx, 1.0, 0.15) << "the cogging rendered at its size";
}

TEST(Loop, AModelWithEffectsTheRendererCannotRenderIsRefusedBeforeSending) {
  ScratchDir dir;
  const std::string path = (dir / "m.json").string();
  write_file(path, R"({"model": "thesis6", "params": {"M_acc": 5e-5, "B_vel_pos": 5e-4, "B_vel_neg": 5e-4},
      "render": {"M_acc": 5e-5, "B_vel": 5e-4, "A_pos": 0, "P_pos": 1},
      "effects": [{"effect": "backlash", "params": {"width_rad": 0.003}}]})");
  // No hapticd at this socket: the refusal comes first (exit 2, not 3).
  const RunResult r = run_knoblab({"ctl", "--socket", (dir / "none.sock").string(), "load_model", path});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("hapticd cannot render backlash ("), std::string::npos) << r.err;
  // simulate takes it (the plant has play).
  const RunResult s = run_knoblab({"simulate", "--params", path, "--seconds", "1", "--out", (dir / "s.csv").string()});
  EXPECT_EQ(s.exit_code, 0) << s.err;
}

}  // namespace
}  // namespace knoblab::test

namespace knoblab::test {
namespace {

TEST(Loop, DiscrepancysModelFileIsFittedToAnotherCaptureOfTheKnobAndSimulatesAgain) {
  ScratchDir dir;
  const auto at = [&](const char* name) { return (dir / name).string(); };
  const std::string stribeck = "stribeck:static_excess_Nm=0.004,stribeck_velocity_rad_s=0.5";
  run_ok({"simulate", "--knob", "moderate-detents", "--seconds", "8", "--effects", stribeck, "--out", at("a.csv")});
  run_ok({"discrepancy", "--input", at("a.csv"), "--model-out", at("model.json")});
  run_ok({"simulate", "--knob", "moderate-detents", "--seconds", "8", "--seed", "5", "--effects", stribeck, "--out",
          at("b.csv")});
  const RunResult r = run_knoblab({"fit", at("b.csv"), "--model", at("model.json"), "--json", at("refit.json")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("stribeck.static_excess_Nm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mN·m"), std::string::npos) << r.out;

  // The refitted Stribeck term: the first capture's finding inside its
  // interval (two recordings of one knob agree), and near the truth. Not the
  // truth inside it: discovery reads the excess about 7 % high on this rig
  // (4.27–4.30 mN·m over seeds 5–7, and 4.27 in discrepancy's own finding),
  // a bias both share, larger than an 8 s capture's interval.
  const json refit = read_json(at("refit.json"));
  const json model = read_json(at("model.json"));
  const json* found = nullptr;
  const json* first = nullptr;
  std::size_t e = 0;
  for (std::size_t i = 0; i < refit.at("effects").size(); ++i)
    if (refit.at("effects")[i].at("effect") == "stribeck") found = &refit.at("effects")[i], e = i;
  for (const json& f : model.at("effects"))
    if (f.at("effect") == "stribeck") first = &f;
  ASSERT_NE(found, nullptr) << refit.dump(1);
  ASSERT_NE(first, nullptr) << model.dump(1);
  const json& ci = refit.at("ci95").at("effects")[e].at("params");
  for (const auto& [name, truth] : {std::pair<std::string, double>{"static_excess_Nm", 0.004},
                                    {"stribeck_velocity_rad_s", 0.5}}) {
    const double v = found->at("params").at(name), half = ci.at(name), was = first->at("params").at(name);
    EXPECT_LE(std::abs(v - was), half) << name << " " << v << " ± " << half << ", first capture " << was;
    EXPECT_NEAR(v, truth, 0.1 * truth) << name;
  }
  EXPECT_EQ(refit.at("source").at("model"), at("model.json"));
  // A model file again: simulate takes it.
  run_ok({"simulate", "--params", at("refit.json"), "--seconds", "2", "--out", at("c.csv")});
  EXPECT_NE(read_file(at("c.csv")).find("# effects: stribeck:"), std::string::npos);
}

TEST(Loop, FittingAModelFileRefusesTheThesisFitsOptionsAndAMissingFile) {
  ScratchDir dir;
  const auto at = [&](const char* name) { return (dir / name).string(); };
  run_ok({"simulate", "--knob", "moderate-detents", "--seconds", "2", "--out", at("a.csv")});
  write_file(at("model.json"), R"({"model": "thesis6", "params": {"M_acc": 5e-5}, "effects": []})");
  const RunResult report = run_knoblab({"fit", at("a.csv"), "--model", at("model.json"), "--report", at("r")});
  EXPECT_EQ(report.exit_code, 2);
  EXPECT_NE(report.err.find("--report is for the thesis model"), std::string::npos) << report.err;
  const RunResult missing = run_knoblab({"fit", at("a.csv"), "--model", at("nosuch.json")});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no file"), std::string::npos) << missing.err;
  write_file(at("bad.json"), R"({"params": {"M_acc": 5e-5}, "effects": [{"effect": "stribeck", "params": {}}]})");
  const RunResult bad = run_knoblab({"fit", at("a.csv"), "--model", at("bad.json")});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.json: effects[0]"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace knoblab::test
