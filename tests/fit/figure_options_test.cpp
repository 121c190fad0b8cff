// The figure options' grammar and limits: --format, --size, --dpi.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "knoblab/fit/plot/figure_options.hpp"

namespace knoblab::fit::plot {
namespace {

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(FigureOptions, DefaultIsAllThreeFormatsAt300DpiAndSixteenCentimetresWide) {
  const FigureOptions opt;
  EXPECT_EQ(opt.formats, (std::vector<Format>{Format::Pdf, Format::Svg, Format::Png}));
  EXPECT_EQ(opt.dpi, 300);
  EXPECT_EQ(opt.width_mm, 160.0);
  EXPECT_EQ(opt.height_mm, 0.0);
  EXPECT_NO_THROW(validate(opt));
}

TEST(FigureOptions, FormatsAreParsedInTheOrderGivenAndUnknownOnesNamed) {
  EXPECT_EQ(parse_formats("png,pdf"), (std::vector<Format>{Format::Png, Format::Pdf}));
  EXPECT_EQ(parse_formats("svg"), (std::vector<Format>{Format::Svg}));
  const std::string bad = error_of([] { parse_formats("pdf,jpeg"); });
  EXPECT_NE(bad.find("'jpeg'"), std::string::npos) << bad;
  EXPECT_NE(bad.find("pdf, svg, png"), std::string::npos) << bad;
  EXPECT_NE(error_of([] { parse_formats("png,png"); }).find("twice"), std::string::npos);
  EXPECT_NE(error_of([] { parse_formats(""); }), "");
  EXPECT_NE(error_of([] { parse_formats("pdf,"); }), "");
}

TEST(FigureOptions, SizesAreReadInMillimetresCentimetresOrInchesWithOrWithoutAHeight) {
  FigureOptions opt;
  parse_size("160x100mm", opt);
  EXPECT_DOUBLE_EQ(opt.width_mm, 160.0);
  EXPECT_DOUBLE_EQ(opt.height_mm, 100.0);
  parse_size("16.5x9cm", opt);
  EXPECT_DOUBLE_EQ(opt.width_mm, 165.0);
  EXPECT_DOUBLE_EQ(opt.height_mm, 90.0);
  parse_size("6.5x4in", opt);
  EXPECT_DOUBLE_EQ(opt.width_mm, 165.1);
  EXPECT_DOUBLE_EQ(opt.height_mm, 101.6);
  parse_size("120mm", opt);
  EXPECT_DOUBLE_EQ(opt.width_mm, 120.0);
  EXPECT_EQ(opt.height_mm, 0.0);
  for (const char* bad : {"160x100", "160x100px", "x100mm", "160xmm", "-3x4mm", "0x4mm", "1e400mm", "160 x 100mm"}) {
    const std::string e = error_of([&] { parse_size(bad, opt); });
    EXPECT_NE(e.find(std::string("'") + bad + "'"), std::string::npos) << bad << ": " << e;
    EXPECT_NE(e.find("160x100mm"), std::string::npos) << "names an example: " << e;
  }
}

TEST(FigureOptions, SizesResolutionsAndPixelCountsOutsideTheLimitsAreRefused) {
  FigureOptions opt;
  opt.width_mm = 30.0;
  EXPECT_NE(error_of([&] { validate(opt); }).find("width 30 mm"), std::string::npos);
  opt = {};
  opt.height_mm = 1200.0;
  EXPECT_NE(error_of([&] { validate(opt); }).find("height 1200 mm"), std::string::npos);
  opt = {};
  opt.dpi = 20;
  EXPECT_NE(error_of([&] { validate(opt); }).find("20 dpi"), std::string::npos);
  opt = {};
  opt.width_mm = 500.0;
  opt.dpi = 1200;  // 23622 px
  const std::string e = error_of([&] { validate(opt); });
  EXPECT_NE(e.find("23622 px"), std::string::npos) << e;
  EXPECT_NE(e.find("16384"), std::string::npos) << e;
  opt = {};
  opt.formats.clear();
  EXPECT_NE(error_of([&] { validate(opt); }), "");
}

TEST(FigureOptions, PixelsAreThePrintedSizeAtTheResolution) {
  EXPECT_EQ(pixels(160.0, 300), 1890);
  EXPECT_EQ(pixels(25.4, 72), 72);
  EXPECT_EQ(pixels(100.0, 150), 591);
}

TEST(FigureOptions, DefaultHeightGrowsWithTheRowsOfPanelsAndTheWidth) {
  EXPECT_DOUBLE_EQ(default_height_mm(1, 160.0), 95.0);
  EXPECT_DOUBLE_EQ(default_height_mm(3, 160.0), 175.0);
  EXPECT_DOUBLE_EQ(default_height_mm(2, 80.0), 67.5);
}

}  // namespace
}  // namespace knoblab::fit::plot
