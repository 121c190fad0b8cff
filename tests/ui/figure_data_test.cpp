// The report figures' CSV as the review screens read it.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "figure_data.hpp"

namespace knoblab::ui {
namespace {

constexpr const char* kCsv =
    "panel,series,position_deg,torque_mNm,torque_lower_mNm\n"
    "total,raw_torque,0.5,1.0,\n"
    "total,raw_torque,0.1,2.0,\n"
    "total,fitted_torque,3.0,1.5,\n"
    "total,fitted_torque,1.0,1.4,\n"
    "position_part,fitted_position,-1.0,-2.0,\n"
    "position_part,fitted_position,0.0,0.0,\n"
    "position_part,fitted_position,1.0,2.0,\n"
    "residual,band,-1.0,0.5,-0.5\n"
    "residual,band,1.0,0.6,-0.6\n"
    "residual,stick_limit,0.2,,\n";

TEST(FigureData, SeriesAreGroupedByPanelAndDrawnAsTheirDataSays) {
  const FigureData f = parse_figure_csv(kCsv);
  EXPECT_EQ(f.x_column, "position_deg");
  EXPECT_EQ(f.y_column, "torque_mNm");
  EXPECT_EQ(f.panels, (std::vector<std::string>{"total", "position_part", "residual"}));
  ASSERT_EQ(f.series.size(), 5u);
  EXPECT_EQ(f.series[0].kind, FigureSeries::Kind::Points);  // raw data
  EXPECT_EQ(f.series[1].kind, FigureSeries::Kind::Points);  // not ordered along x
  EXPECT_EQ(f.series[2].kind, FigureSeries::Kind::Line);
  EXPECT_EQ(f.series[2].y, (std::vector<double>{-2.0, 0.0, 2.0}));
  EXPECT_EQ(f.series[3].kind, FigureSeries::Kind::Band);
  EXPECT_EQ(f.series[3].y_low, (std::vector<double>{-0.5, -0.6}));
  EXPECT_TRUE(std::isnan(f.series[4].y[0])) << "an empty cell is a value that is not finite";
}

TEST(FigureData, AMalformedFigureIsRefusedNamingTheLine) {
  const auto refused = [](const std::string& csv, const std::string& why) {
    try {
      parse_figure_csv(csv);
      ADD_FAILURE() << "accepted: " << csv;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refused("", "empty");
  refused("x,y\n1,2\n", "line 1 is not");
  refused("panel,series,t_s,torque_mNm\np,s,1\n", "line 2 has 3 cells, not 4");
  refused("panel,series,t_s,torque_mNm\np,s,1,2\np,s,one,2\n", "line 3 holds a value that is not a number");
}

TEST(FigureData, AxisLabelsSayTheirUnits) {
  EXPECT_EQ(axis_label("position_deg"), "position (°)");
  EXPECT_EQ(axis_label("velocity_deg_per_s"), "velocity (°/s)");
  EXPECT_EQ(axis_label("residual_mNm"), "residual (mN·m)");
  EXPECT_EQ(axis_label("time_s"), "time (s)");
  EXPECT_EQ(axis_label("correlation"), "correlation");
}

}  // namespace
}  // namespace knoblab::ui
