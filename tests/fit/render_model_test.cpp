// Reduction of a fit to the rendering model (Eq. 14) and its file format.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "knoblab/fit/render_model.hpp"

namespace knoblab::fit {
namespace {

FitResult thesis_fit(double A, bool detents) {
  FitResult r;
  r.model = ModelKind::Thesis6;
  r.names = param_names(r.model);
  r.params = {5e-5, 2e-3, 4e-4, 1e-3, 6e-4, A, 1.0 / 12, 0.3};
  r.fitted.assign(8, true);
  r.detents = detents;
  return r;
}

TEST(RenderModel, DampingIsTheLeastSquaresMatchOfTheFittedFriction) {
  const FitResult r = thesis_fit(-0.011, true);
  const std::vector<double> omega = {-2.0, -1.0, -0.5, 0.5, 1.0, 2.0};
  const RenderModelFile m = reduce_to_render(r, omega);
  double num = 0, den = 0;
  for (double w : omega) {
    const double f = w > 0 ? 1e-3 + 6e-4 * w : -2e-3 + 4e-4 * w;
    num += f * w, den += w * w;
  }
  EXPECT_DOUBLE_EQ(m.B_vel, num / den);
  EXPECT_DOUBLE_EQ(m.M_acc, 5e-5);
  EXPECT_DOUBLE_EQ(m.A_pos, 0.011);  // |A|: Eq. 14 has no phase to carry the sign
  EXPECT_DOUBLE_EQ(m.P_pos, 1.0 / 12);
  EXPECT_FALSE(m.stick.has_value());
}

TEST(RenderModel, NoDetentsRendersNone) {
  const RenderModelFile m = reduce_to_render(thesis_fit(0.0, false), std::vector<double>{1.0});
  EXPECT_EQ(m.A_pos, 0.0);
  EXPECT_EQ(m.P_pos, 1.0);
}

TEST(RenderModel, FileRoundTripsAndIsTheLoadModelArguments) {
  FitResult r = thesis_fit(0.011, true);
  r.stick = StickBand{0.02, 0.05, 0.06, 40};
  const RenderModelFile m = reduce_to_render(r, std::vector<double>{-1.0, 1.0});
  const std::string text = to_json(m);
  const auto j = nlohmann::json::parse(text);
  EXPECT_EQ(j["model"], "render4");
  std::vector<std::string> keys;
  for (const auto& [k, v] : j["params"].items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"A_pos", "B_vel", "D_neg", "D_pos", "M_acc", "P_pos", "dv"}));
  const RenderModelFile back = parse_render_model(text);
  EXPECT_EQ(back.M_acc, m.M_acc);
  EXPECT_EQ(back.B_vel, m.B_vel);
  EXPECT_EQ(back.A_pos, m.A_pos);
  EXPECT_EQ(back.P_pos, m.P_pos);
  ASSERT_TRUE(back.stick.has_value());
  EXPECT_EQ(back.stick->dv, 0.02);
  EXPECT_EQ(back.stick->D_pos, 0.06);
}

TEST(RenderModel, MalformedFilesNameTheProblem) {
  auto message = [](const std::string& text) {
    try {
      parse_render_model(text);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("{").find("not JSON"), std::string::npos);
  EXPECT_NE(message(R"({"model":"thesis6","params":{}})").find("render4"), std::string::npos);
  EXPECT_NE(message(R"({"model":"render4","params":{"B_vel":0,"A_pos":0,"P_pos":1}})").find("M_acc"),
            std::string::npos);
  EXPECT_NE(message(R"({"model":"render4","params":{"M_acc":"x","B_vel":0,"A_pos":0,"P_pos":1}})")
                .find("M_acc"),
            std::string::npos);
  EXPECT_NE(message(R"({"model":"render4","params":{"M_acc":0,"B_vel":0,"A_pos":0,"P_pos":1,"K":1}})")
                .find("'K'"),
            std::string::npos);
  EXPECT_NE(message(R"({"model":"render4","params":{"M_acc":0,"B_vel":0,"A_pos":0,"P_pos":1,"dv":1}})")
                .find("all or none"),
            std::string::npos);
}

}  // namespace
}  // namespace knoblab::fit
