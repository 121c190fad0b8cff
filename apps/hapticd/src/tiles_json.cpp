#include "knoblab/hapticd/tiles_json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/model/render_stability.hpp"
#include "short_number.hpp"
#include "stable_range.hpp"

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

// The three curves of Eq. 19/20, each optional, checked on [lo, hi].
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

// A torque curve's peak on [lo, hi] (evaluated by `f`), refused past the
// limit: the supervisor would clip it, and it would not feel as designed.
template <typename Eval>
void require_within_torque_limit(const CubicSpline& curve, Eval f, double lo, double hi, const std::string& key,
                                 const char* variable, const char* unit, const SafetyLimits& limits) {
  for (const double x : check_points(curve, lo, hi))
    if (const double tau = f(x); std::abs(tau) > limits.torque_limit_Nm)
      fail(key, std::string("its torque reaches ") + short_number(tau * 1e3) + " mN·m at " + variable + " = " +
                    short_number(x) + " " + unit + ", beyond the device's torque limit of " +
                    short_number(limits.torque_limit_Nm * 1e3) + " mN·m");
}

void require_mass_in_range(const CubicSpline& m, double lo, double hi, const std::string& key) {
  require_non_negative(m, lo, hi, key, "the mass");
  for (const double th : check_points(m, lo, hi))
    if (const double v = m(th); v > kMaxTileMass)
      fail(key, "the mass reaches " + short_number(v * 1e3) + " mN·m/(rad/s²) at θ = " + short_number(th) +
                    " rad, beyond the renderer's " + short_number(kMaxTileMass * 1e3) +
                    " mN·m/(rad/s²) (thesis Table 9)");
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
  if (j.contains("torque")) {
    tile.torque_of_angle = spline_from(j.at("torque"), key + ".torque");
    const CubicSpline& g = *tile.torque_of_angle;
    require_within_torque_limit(g, [&](double th) { return g(th); }, tile.theta_min, tile.theta_max,
                                key + ".torque", "θ", "rad", limits);
  }
  if (j.contains("torque_of_velocity")) {
    tile.torque_of_velocity = spline_from(j.at("torque_of_velocity"), key + ".torque_of_velocity");
    const CubicSpline& g = *tile.torque_of_velocity;
    // Any speed up to the velocity limit can happen (beyond it the
    // supervisor latches), and the curve goes on straight past its knots.
    const double v = limits.velocity_limit_rad_s;
    require_within_torque_limit(g, [&](double w) { return model::evaluate_straight_ends(g, w); }, -v, v,
                                key + ".torque_of_velocity", "θ̇", "rad/s", limits);
  }
  if (j.contains("mass")) {
    tile.mass = spline_from(j.at("mass"), key + ".mass");
    require_mass_in_range(*tile.mass, tile.theta_min, tile.theta_max, key + ".mass");
  }
  return tile;
}

model::TimeTile time_tile(const json& j, const std::string& key, const SafetyLimits& limits) {
  model::TimeTile tile;
  tile.start = j.value("start", 0.0);
  tile.duration = j.at("duration").get<double>();
  tile.loop = j.value("loop", false);
  tile.period = j.value("period", 0.0);
  if (tile.period > 0.0 && tile.period < tile.start + tile.duration)
    fail(key + ".period", "must be at least start + duration (" + short_number(tile.start + tile.duration) +
                              " s): a tile cannot repeat before it has ended");
  read_terms(j, key, 0.0, tile.duration, tile);
  if (j.contains("torque")) {
    tile.torque_of_time = spline_from(j.at("torque"), key + ".torque");
    const CubicSpline& g = *tile.torque_of_time;
    require_within_torque_limit(g, [&](double t) { return g(t); }, 0.0, tile.duration, key + ".torque", "t", "s",
                                limits);
  }
  return tile;
}

std::string loop_name(const model::LoopDynamics& d) {
  return d.rate_hz >= 1000.0 ? short_number(d.rate_hz / 1000.0) + " kHz loop" : short_number(d.rate_hz) + " Hz loop";
}

// The tiles together as the loop sees them, linearised (render_stability.hpp):
// at every θ of every position tile's span, the stiffness of all torque and
// f_pos curves acting there and the damping of all f_vel and
// torque_of_velocity curves (the latter at their least and their greatest
// slope up to the velocity limit), overlapping tiles added up. Outside the
// stable region the knob would buzz or ring: refused, naming the curve that
// contributes most of what is too much, and the mass is summed as well.
void check_stability(const TileSet& set, const SafetyLimits& limits, const model::LoopStability& loop) {
  const std::size_t n = set.position.size();
  std::vector<std::pair<double, double>> slopes(n);
  for (std::size_t i = 0; i < n; ++i) slopes[i] = set.position[i].velocity_slope_range(limits.velocity_limit_rad_s);
  const auto key_of = [](std::size_t i) { return "position[" + std::to_string(i) + "]"; };
  // One eigenvalue problem per (K, B) took 0.3–0.7 s for a curved tile and
  // seconds for a design, longer than a client waits for its reply. Along a
  // tile one of K and B usually holds still while the other changes at every
  // point (a stiffness curve over constant damping, a damping curve without
  // stiffness), so a value of either met often gets its stable range of the
  // other once, by bisection (50–80 eigenvalue problems); points inside it
  // with margin need no test of their own. Until then, and where both
  // change, each point is tested on its own.
  constexpr int kTestsBeforeRange = 24;
  std::map<double, StableRange> k_by_damping, b_by_stiffness;
  std::map<double, int> tests_at_b, tests_at_k;
  const auto stiffness_range = [&](double B) {
    StableRange in;
    // The falling side of a detent is a negative stiffness: how steep a fall renders.
    if (loop.renders_stably(0.0, B)) in = {loop.min_stiffness(B), loop.max_stiffness(B)};
    return in;
  };
  const auto damping_range = [&](double K) {
    StableRange in;
    if (loop.renders_stably(K, 0.0)) in = {loop.min_damping(K), loop.max_damping(K)};
    return in;
  };
  const auto stable = [&](double K, double B) {
    const auto test = [&] { return loop.renders_stably(K, B); };
    if (auto it = k_by_damping.find(B); it != k_by_damping.end()) return it->second.holds(K, test);
    if (auto it = b_by_stiffness.find(K); it != b_by_stiffness.end()) return it->second.holds(B, test);
    if (++tests_at_b[B] > kTestsBeforeRange)
      return k_by_damping.emplace(B, stiffness_range(B)).first->second.holds(K, test);
    if (++tests_at_k[K] > kTestsBeforeRange)
      return b_by_stiffness.emplace(K, damping_range(K)).first->second.holds(B, test);
    return test();
  };
  for (std::size_t i = 0; i < n; ++i) {
    const model::PositionTile& tile = set.position[i];
    std::vector<double> at = check_points(CubicSpline{}, tile.theta_min, tile.theta_max);
    for (const model::PositionTile& other : set.position)  // where the sum changes
      for (const double edge : {other.theta_min, other.theta_max})
        if (tile.contains(edge)) at.push_back(edge);
    for (const auto* c : {&tile.torque_of_angle, &tile.f_pos, &tile.f_vel, &tile.mass})
      if (*c)
        for (const double k : (*c)->knots())
          if (tile.contains(k)) at.push_back(k);
    for (const double th : at) {
      double K = 0.0, B = 0.0, B_lo = 0.0, B_hi = 0.0, mass = 0.0;
      int contributors = 0;
      for (std::size_t j = 0; j < n; ++j) {
        const model::PositionTile& t = set.position[j];
        if (!t.contains(th)) continue;
        ++contributors;
        K += t.stiffness_at(th);
        B += t.damping_at(th);
        B_lo += slopes[j].first;
        B_hi += slopes[j].second;
        mass += t.mass_at(th);
      }
      const std::string together = contributors > 1 ? " (the tiles there together)" : "";
      if (mass > kMaxTileMass) {
        std::size_t heaviest = i;
        for (std::size_t j = 0; j < n; ++j)
          if (set.position[j].mass_at(th) > set.position[heaviest].mass_at(th)) heaviest = j;
        fail(key_of(heaviest) + ".mass", "the mass reaches " + short_number(mass * 1e3) + " mN·m/(rad/s²) at θ = " +
                                             short_number(th) + " rad" + together + ", beyond the renderer's " +
                                             short_number(kMaxTileMass * 1e3) + " mN·m/(rad/s²) (thesis Table 9)");
      }
      const int sides = B_lo == B_hi ? 1 : 2;  // the same B twice: once
      for (int side = 0; side < sides; ++side) {
        const double Bv = side == 0 ? B + B_hi : B + B_lo;
        if (stable(K, Bv)) continue;
        const double K_max = loop.max_stiffness(Bv);
        if (std::isfinite(K_max) && K > K_max) {  // too stiff: blame the stiffest curve there
          std::size_t j_best = i;
          double best = 0.0;
          std::string curve = "torque";
          for (std::size_t j = 0; j < n; ++j) {
            const model::PositionTile& t = set.position[j];
            if (!t.contains(th)) continue;
            if (t.torque_of_angle && t.torque_of_angle->derivative(th) > best)
              best = t.torque_of_angle->derivative(th), j_best = j, curve = "torque";
            if (t.f_pos) {
              const double k = (*t.f_pos)(th) + t.f_pos->derivative(th) * th;
              if (k > best) best = k, j_best = j, curve = "f_pos";
            }
          }
          fail(key_of(j_best) + "." + curve,
               "its stiffness reaches " + short_number(K) + " N·m/rad at θ = " + short_number(th) + " rad" + together +
                   ", beyond the " + loop_name(loop.dynamics()) + "'s stable " + short_number(K_max) +
                   " N·m/rad with " + short_number(Bv) + " N·m·s/rad damping there");
        }
        // Otherwise the damping: too much for the filtered velocity's lag,
        // or a down-slope steeper than the grip's own damping.
        const bool too_high = side == 0 && Bv > 0.0;
        const double edge = too_high ? loop.max_damping(K) : loop.min_damping(K);
        std::size_t j_best = i;
        double best = -1.0;
        std::string curve = "f_vel";
        for (std::size_t j = 0; j < n; ++j) {
          const model::PositionTile& t = set.position[j];
          if (!t.contains(th)) continue;
          const double fv = t.damping_at(th), gv = too_high ? slopes[j].second : -slopes[j].first;
          if (t.f_vel && std::abs(fv) > best) best = std::abs(fv), j_best = j, curve = "f_vel";
          if (t.torque_of_velocity && gv > best) best = gv, j_best = j, curve = "torque_of_velocity";
        }
        std::string bound = std::isfinite(edge) ? "the " + loop_name(loop.dynamics()) + "'s stable " +
                                                      short_number(edge) + " N·m·s/rad"
                                                : "anything the " + loop_name(loop.dynamics()) + " renders stably";
        fail(key_of(j_best) + "." + curve,
             std::string("its damping ") + (too_high ? "reaches " : "falls to ") + short_number(Bv) +
                 " N·m·s/rad at θ = " + short_number(th) + " rad" + together + ", " +
                 (too_high ? "beyond " : "below ") + bound + " with " + short_number(K) +
                 " N·m/rad stiffness there" +
                 (too_high ? "" : ": a down-slope steeper than the grip's own damping makes the knob ring"));
      }
    }
  }
}

}  // namespace

std::variant<std::unique_ptr<TileSet>, ParamProblem> tiles_from_json(const json& args, const SafetyLimits& limits,
                                                                     const model::LoopDynamics& loop) {
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
        set->time.push_back(time_tile(list[i], "time[" + std::to_string(i) + "]", limits));
    }
    check_stability(*set, limits, model::LoopStability(loop));
  } catch (const Bad& b) {
    return b.problem;
  }
  return set;
}

}  // namespace knoblab::hapticd
