// knoblab compare end to end: simulated captures of the same knob and of
// another, a capture's stored fit, fit and model files, and the report.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "png_image.hpp"
#include "process.hpp"

namespace knoblab::test {
namespace {

using nlohmann::json;

// Three 5 s captures made once: two of moderate-detents (noise seeds 1 and
// 2), one of high-friction.
class Captures : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir;
    for (const auto& [name, knob, seed] : {std::tuple{"md1.csv", "moderate-detents", "1"},
                                           std::tuple{"md2.csv", "moderate-detents", "2"},
                                           std::tuple{"hf.csv", "high-friction", "1"}}) {
      const RunResult r = run_knoblab({"simulate", "--knob", knob, "--seed", seed, "--out", path(name)});
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string path(const std::string& name) { return (*dir_ / name).string(); }

  static json compare(std::vector<std::string> args) {
    args.insert(args.begin(), "compare");
    args.insert(args.end(), {"--json", "-"});
    const RunResult r = run_knoblab(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return json::parse(r.out, nullptr, false);
  }
  static json row(const json& j, const std::string& name) {
    for (const json& p : j.at("params"))
      if (p.at("name") == name) return p;
    throw std::runtime_error("no row " + name + " in " + j.dump());
  }

  static ScratchDir* dir_;
};
ScratchDir* Captures::dir_ = nullptr;

TEST_F(Captures, TwoCapturesOfOneKnobOverlapEverywhereAndAnotherKnobIsApart) {
  const json same = compare({path("md1.csv"), path("md2.csv")});
  ASSERT_TRUE(same.is_object());
  EXPECT_TRUE(same.at("apart").empty()) << same.dump(1);
  EXPECT_EQ(row(same, "C_vel_pos").at("overlap"), true);
  EXPECT_TRUE(row(same, "M_acc").at("a").at("ci95").is_array());
  const json other = compare({path("md1.csv"), path("hf.csv")});
  const json c = row(other, "C_vel_pos");
  EXPECT_EQ(c.at("overlap"), false) << other.dump(1);
  // SI in the JSON: high-friction's Coulomb level is tens of mN·m.
  EXPECT_GT(c.at("b").at("value").get<double>(), 10 * c.at("a").at("value").get<double>());
}

TEST_F(Captures, TheTableStatesItsUnitsAndNamesWhatIsApart) {
  const RunResult r = run_knoblab({"compare", path("md1.csv"), path("hf.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("A: md1.csv (fitted now)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mN·m/(rad/s²)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("apart: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("C_vel_pos"), std::string::npos) << r.out;
}

TEST_F(Captures, AFitResultsIntervalsJudgeAModelFilesValues) {
  ASSERT_EQ(run_knoblab({"fit", "--input", path("md1.csv"), "--json", path("md1.fit.json")}).exit_code, 0);
  // A model file has values only: judged by whether they lie inside the fit's intervals.
  json model = json::parse(read_file(path("md1.fit.json")));
  json file = {{"model", "thesis6"}, {"params", model.at("params")}, {"stick", model.at("stick")},
               {"effects", json::array({{{"effect", "gravity"}, {"params", {{"amplitude_Nm", 0.002}}}}})}};
  file["params"]["C_vel_pos"] = model.at("ci95").at("C_vel_pos")[1].get<double>() * 2;
  write_file(path("model.json"), file.dump());
  const json j = compare({path("md1.fit.json"), path("model.json")});
  EXPECT_EQ(j.at("a").at("origin"), "fit result");
  EXPECT_EQ(j.at("b").at("origin"), "model file");
  EXPECT_EQ(row(j, "M_acc").at("overlap"), true);
  EXPECT_EQ(row(j, "C_vel_pos").at("overlap"), false);
  EXPECT_TRUE(row(j, "gravity.amplitude_Nm").at("overlap").is_null());  // only B has it, without an interval
  EXPECT_TRUE(row(j, "gravity.amplitude_Nm").at("a").is_null());
}

TEST_F(Captures, AStoredCaptureIsComparedByItsStoredFit) {
  const std::string db = path("lab.sqlite");
  ASSERT_EQ(run_knoblab({"import", path("md2.csv"), "--db", db}).exit_code, 0);
  ASSERT_EQ(run_knoblab({"fit", "--capture", "1", "--db", db}).exit_code, 0);
  const json j = compare({"1", path("md1.csv"), "--db", db});
  EXPECT_EQ(j.at("a").at("origin"), "stored fit 1") << j.dump(1);
  EXPECT_TRUE(j.at("apart").empty()) << j.dump(1);
  const RunResult no_db = run_knoblab({"compare", "1", path("md1.csv")});
  EXPECT_EQ(no_db.exit_code, 2);
  EXPECT_NE(no_db.err.find("a capture id needs --db FILE"), std::string::npos) << no_db.err;
}

TEST_F(Captures, TheReportOverlaysBothKnobsInTheirColours) {
  const std::string dir = path("report");
  const RunResult r = run_knoblab({"compare", path("md1.csv"), path("hf.csv"), "--report", dir});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"torque_position", "torque_velocity"}) {
    const testing::Image img = testing::decode_png(dir + "/" + name + ".png");
    std::size_t blue = 0, orange = 0;
    for (std::uint32_t y = 0; y < img.height; ++y)
      for (std::uint32_t x = 0; x < img.width; ++x) {
        const auto c = img.at(x, y);
        blue += c[0] < 70 && c[1] > 90 && c[1] < 150 && c[2] > 150 ? 1 : 0;     // A's line (31, 119, 180)
        orange += c[0] > 220 && c[1] > 95 && c[1] < 160 && c[2] < 60 ? 1 : 0;  // B's line (255, 127, 14)
      }
    EXPECT_GT(blue, 500u) << name;
    EXPECT_GT(orange, 500u) << name;
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + name + ".svg")) << name;
  }
}

}  // namespace
}  // namespace knoblab::test
