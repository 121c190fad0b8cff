// --format, --size and --dpi on fit and discrepancy: the files they choose,
// the PNG's pixels, and the errors for what they refuse.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "process.hpp"

namespace knoblab::test {
namespace {

namespace fs = std::filesystem;

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(s[at + k]);
  return v;
}

class ReportFigures : public ::testing::Test {
 protected:
  void SetUp() override {
    csv_ = (dir_ / "knob.csv").string();
    const RunResult sim = run_knoblab({"simulate", "--knob", "moderate-detents", "--seconds", "3", "--out", csv_});
    ASSERT_EQ(sim.exit_code, 0) << sim.err;
  }
  ScratchDir dir_;
  std::string csv_;
};

TEST_F(ReportFigures, FormatSizeAndDpiChooseTheFilesAndThePngsPixels) {
  const auto report = dir_ / "report";
  const RunResult r = run_knoblab({"fit", "--input", csv_, "--report", report.string(), "--format", "png",
                                   "--size", "100x80mm", "--dpi", "127"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // 4 PNGs, 4 CSVs, fit.json, render_model.json
  EXPECT_NE(r.out.find("report: 10 files in"), std::string::npos) << r.out;
  EXPECT_NE(read_file(report / "render_model.json").find("\"model\": \"render4\""), std::string::npos);
  for (const char* stem : {"torque_position", "torque_velocity", "torque_time", "ci_torque"}) {
    const std::string png = read_file(report / (std::string(stem) + ".png"));
    ASSERT_GT(png.size(), 24u) << stem;
    EXPECT_EQ(be32(png, 16), 500u) << stem;  // 100 mm at 127 dpi
    EXPECT_EQ(be32(png, 20), 400u) << stem;
    EXPECT_TRUE(fs::is_regular_file(report / (std::string(stem) + ".csv"))) << stem;
    EXPECT_FALSE(fs::exists(report / (std::string(stem) + ".pdf"))) << stem;
    EXPECT_FALSE(fs::exists(report / (std::string(stem) + ".svg"))) << stem;
  }
}

TEST_F(ReportFigures, BadFigureOptionsAreRefusedBeforeAnythingIsDone) {
  const auto report = dir_ / "report";
  struct Bad {
    std::vector<std::string> args;
    std::string says;
  };
  const Bad bad[] = {
      {{"--format", "pdf,jpeg"}, "unknown figure format 'jpeg' (known: pdf, svg, png"},
      {{"--size", "160x100"}, "figure size '160x100': expected WIDTHxHEIGHT or WIDTH with a unit mm, cm or in"},
      {{"--size", "2000x100mm"}, "figure width 2000 mm is outside 40…1000 mm"},
      {{"--dpi", "high"}, "--dpi: not an integer: 'high'"},
      {{"--dpi", "2000", "--size", "300mm"}, "over the PNG limit of 16384 px"},
  };
  for (const char* command : {"fit", "discrepancy"}) {
    for (const Bad& b : bad) {
      std::vector<std::string> args{command, "--input", csv_, "--report", report.string()};
      args.insert(args.end(), b.args.begin(), b.args.end());
      const RunResult r = run_knoblab(args);
      EXPECT_EQ(r.exit_code, 2) << command << " " << b.args.front() << ": " << r.err;
      EXPECT_NE(r.err.find(b.says), std::string::npos) << command << ": " << r.err;
      EXPECT_FALSE(fs::exists(report)) << command;
    }
    const RunResult r = run_knoblab({command, "--input", csv_, "--dpi", "300"});
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find("--dpi needs --report DIR"), std::string::npos) << r.err;
  }
}

TEST_F(ReportFigures, AFormatThisPlplotCannotDrawIsRefusedBeforeTheFit) {
  // A PLplot built with only the PNG and SVG cairo drivers (as the Yocto
  // image's once was): its driver directory, cut down.
  const fs::path drivers = dir_ / "drivers";
  fs::create_directories(drivers);
  fs::create_symlink(fs::path(KNOBLAB_PLPLOT_DRVDIR) / "cairo.so", drivers / "cairo.so");
  std::string info;
  for (const std::string& line : {std::string("svgcairo:Cairo SVG Driver:0:cairo:104:svgcairo\n"),
                                  std::string("pngcairo:Cairo PNG Driver:0:cairo:105:pngcairo\n")})
    info += line;
  write_file(drivers / "cairo.driver_info", info);
  ::setenv("PLPLOT_DRV_DIR", drivers.c_str(), 1);
  const auto report = dir_ / "report";
  RunResult r = run_knoblab({"fit", "--input", csv_, "--report", report.string()});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no pdfcairo driver (its cairo drivers: svgcairo, pngcairo): leave pdf out of --format"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.out.find("rmse"), std::string::npos) << "the fit did not run: " << r.out;
  EXPECT_FALSE(fs::exists(report));
  r = run_knoblab({"discrepancy", "--input", csv_, "--report", report.string(), "--format", "svg,png"});
  ::unsetenv("PLPLOT_DRV_DIR");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(report / "whiteness.svg"));
  EXPECT_FALSE(fs::exists(report / "whiteness.pdf"));
}

}  // namespace
}  // namespace knoblab::test
