#include "knoblab/hapticd/tiles_json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "short_number.hpp"

namespace knoblab::hapticd {

namespace {

using detail::short_number;
using nlohmann::json;
using model::CubicSpline;

// A curve is checked where it acts: this many points across the tile's
// range, plus every knot (a cubic can dip between knots).
constexpr int kCheckPoints = 2048;

struct Bad {
  ParamProblem problem;
};

[[noreturn]] void fail(const std::string& key, const std::string& message) { throw Bad{{key, key + ": " + message}}; }

CubicSpline spline_from(const json& j, const std::string& key) {
  const auto x = j.at("x").get<std::vector<double>>();
  const auto y = j.at("y").get<std::vector<double>>();
  if (x.size() != y.size())
    fail(key, "x has " + std::to_string(x.size()) + " knots but y has " + std::to_string(y.size()) + " values");
  try {
    return CubicSpline(x, y, j.value("periodic", false) ? model::SplineBoundary::kPeriodic
                                                        : model::SplineBoundary::kNatural);
  } catch (const std::invalid_argument& e) {
    std::string why = e.what();
    if (const auto colon = why.find(": "); colon != std::string::npos) why.erase(0, colon + 2);  // "CubicSpline: "
    fail(key, why);
  }
}

// Where on [lo, hi] to evaluate a curve.
std::vector<double> check_points(const CubicSpline& f, double lo, double hi) {
  std::vector<double> at;
  at.reserve(kCheckPoints + f.knots().size() + 1);
  for (int i = 0; i <= kCheckPoints; ++i) at.push_back(lo + (hi - lo) * i / kCheckPoints);
  for (const double k : f.knots())
    if (k >= lo && k <= hi) at.push_back(k);
  return at;
}

// Damping and mass below zero push energy into the hand.
void require_non_negative(const CubicSpline& f, double lo, double hi, const std::string& key, const char* what) {
  for (const double s : check_points(f, lo, hi))
    if (const double v = f(s); v < 0.0)
      fail(key, std::string(what) + " is " + short_number(v) + " at " + short_number(s) +
                    ": below zero it would feed energy into the knob");
}

// The three curves of a tile, each optional, checked on [lo, hi].
template <typename Tile>
void read_terms(const json& j, const std::string& key, double lo, double hi, Tile& tile) {
  if (j.contains("f_pos")) tile.f_pos = spline_from(j.at("f_pos"), key + ".f_pos");
  if (j.contains("f_vel")) {
    tile.f_vel = spline_from(j.at("f_vel"), key + ".f_vel");
    require_non_negative(*tile.f_vel, lo, hi, key + ".f_vel", "the damping");
  }
  if (j.contains("f_acc")) {
    tile.f_acc = spline_from(j.at("f_acc"), key + ".f_acc");
    require_non_negative(*tile.f_acc, lo, hi, key + ".f_acc", "the mass");
  }
}

model::PositionTile position_tile(const json& j, const std::string& key, const SafetyLimits& limits) {
  model::PositionTile tile;
  tile.theta_min = j.at("theta_min").get<double>();
  tile.theta_max = j.at("theta_max").get<double>();
  if (!(tile.theta_max > tile.theta_min))
    fail(key + ".theta_max", "must be more than theta_min (" + short_number(tile.theta_min) + " rad)");
  read_terms(j, key, tile.theta_min, tile.theta_max, tile);
  // Eq. 19's spring term depends on θ only, so its peak is known before it
  // plays; one the supervisor would clip would not feel as designed.
  if (tile.f_pos)
    for (const double th : check_points(*tile.f_pos, tile.theta_min, tile.theta_max))
      if (const double tau = (*tile.f_pos)(th) * th; std::abs(tau) > limits.torque_limit_Nm)
        fail(key + ".f_pos", "its torque f_pos(θ)·θ reaches " + short_number(tau * 1e3) + " mN·m at θ = " +
                                 short_number(th) + " rad, beyond the device's torque limit of " +
                                 short_number(limits.torque_limit_Nm * 1e3) + " mN·m");
  return tile;
}

model::TimeTile time_tile(const json& j, const std::string& key) {
  model::TimeTile tile;
  tile.duration = j.at("duration").get<double>();
  tile.loop = j.value("loop", false);
  read_terms(j, key, 0.0, tile.duration, tile);
  return tile;
}

}  // namespace

std::variant<std::unique_ptr<TileSet>, ParamProblem> tiles_from_json(const json& args, const SafetyLimits& limits) {
  auto set = std::make_unique<TileSet>();
  try {
    if (args.contains("position")) {
      const json& list = args.at("position");
      for (std::size_t i = 0; i < list.size(); ++i)
        set->position.push_back(position_tile(list[i], "position[" + std::to_string(i) + "]", limits));
    }
    if (args.contains("time")) {
      const json& list = args.at("time");
      for (std::size_t i = 0; i < list.size(); ++i)
        set->time.push_back(time_tile(list[i], "time[" + std::to_string(i) + "]"));
    }
  } catch (const Bad& b) {
    return b.problem;
  }
  return set;
}

}  // namespace knoblab::hapticd
