// A review plot's touch: a tap finds the plotted point under the finger,
// zoom and pan move the view about the finger, and "whole figure" comes back.
#include <gtest/gtest.h>

#include "figure_view.hpp"

namespace knoblab::ui {
namespace {

constexpr const char* kCsv =
    "panel,series,position_deg,torque_mNm\n"
    "position_part,fitted_position,-10,-5\n"
    "position_part,fitted_position,0,0\n"
    "position_part,fitted_position,10,5\n"
    "residual,raw_residual,0,0.1\n";

TEST(FigureView, ATapGivesTheValuesOfThePlottedPointUnderTheFinger) {
  FigureView v;
  v.setSize(QSizeF(800, 400));
  v.setCsv(kCsv);
  ASSERT_TRUE(v.error().isEmpty()) << v.error().toStdString();
  EXPECT_EQ(v.panel(), "position_part");  // the first panel
  EXPECT_EQ(v.points(), 3);
  EXPECT_EQ(v.panels(), (QStringList{"position_part", "residual"}));
  // The view spans the data (padded): the middle vertex sits mid-plot.
  const QString mid = v.valueAt(v.width() / 2 + 25, v.height() / 2 - 10);
  EXPECT_TRUE(mid.startsWith("position (°) 0, torque (mN·m) 0")) << mid.toStdString();
  EXPECT_EQ(v.valueAt(5, 5), "") << "far from every point";
}

TEST(FigureView, ZoomAndPanMoveTheViewAndWholeFigureBringsItBack) {
  FigureView v;
  v.setSize(QSizeF(800, 400));
  v.setCsv(kCsv);
  const QString before = v.valueAt(v.width() - 10, 10);  // the top right vertex (10°, 5 mN·m)
  ASSERT_FALSE(before.isEmpty());
  v.zoomAt(4.0, v.width() / 2, v.height() / 2);  // about the middle: (10, 5) leaves the view
  EXPECT_EQ(v.valueAt(v.width() - 10, 10), "");
  v.resetView();
  EXPECT_EQ(v.valueAt(v.width() - 10, 10), before);
  v.panBy(-200, 0);  // dragged left: what was at the right edge is 200 px further left
  EXPECT_EQ(v.valueAt(v.width() - 210, 10), before);
}

TEST(FigureView, AMalformedFigureShowsWhyInsteadOfAPlot) {
  FigureView v;
  v.setCsv("not,a,figure\n");
  EXPECT_TRUE(v.error().contains("line 1")) << v.error().toStdString();
  EXPECT_EQ(v.points(), 0);
}

}  // namespace
}  // namespace knoblab::ui
