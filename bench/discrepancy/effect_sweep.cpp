#include "effect_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iterator>
#include <map>

#include "absorption.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/interchange/csv.hpp"
#include "knoblab/model/effect_table.hpp"
#include "sizing.hpp"

namespace knoblab::bench {

namespace {

// Captures per target at most, and how close to it a ratio counts as there.
constexpr int kMaxTries = 6;
constexpr double kClose = 1.15;  // within ×/÷ 1.15

struct Bin {
  double lo, hi;
  const char* label;
};
// Geometric bins around the targets; a case outside them is "off".
constexpr Bin kBins[] = {{0.35, 0.7, "0.5"}, {0.7, 1.4, "1"},  {1.4, 2.8, "2"},  {2.8, 5.6, "4"},
                         {5.6, 11.3, "8"},   {11.3, 22, "16"}, {22, 45, "30"}};
constexpr std::size_t kOff = std::size(kBins);

std::size_t bin_of(double ratio) {
  for (std::size_t b = 0; b < std::size(kBins); ++b)
    if (ratio >= kBins[b].lo && ratio < kBins[b].hi) return b;
  return kOff;
}

// Prepared as discovery prepares it, every row kept (a flagged row would
// shift one capture's rows against the other's).
fit::FitData prepared_all_rows(const interchange::Capture& c) {
  fit::PrepOptions o;
  o.exclude_flags = 0;
  return fit::prepare(c, o);
}

// The stick band the base fit estimates on a capture, below which discovery
// leaves rows out (analysed_rows adds its floor of 2 % of the brisk speed).
double slow_speed_of(const fit::FitData& d) {
  const fit::FitResult f = fit::fit_knob(d);
  return f.stick ? f.stick->dv : 0.0;
}

// One knob and seed's clean capture: what the effects are measured against.
struct Clean {
  fit::FitData data;
  std::vector<std::size_t> rows;
  double r = 0.0;
  std::array<double, model::kThesisParamCount> base{};  // the Eq. 6 discovery fitted to it
};

// The base model discovery fitted to the clean capture, from its result.
std::array<double, model::kThesisParamCount> base_params(const nlohmann::json& result) {
  const nlohmann::json& params = result.at("base").at("params");
  std::array<double, model::kThesisParamCount> p{};
  for (std::size_t k = 0; k < model::kThesisParamCount; ++k) p[k] = params.at(std::string(model::kThesisParamNames[k]));
  return p;
}

// A setting tried: the effect size it gave, and its capture.
struct Point {
  double setting = 0.0;
  double rms = 0.0;      // the part Eq. 6 cannot take up: what sizes the case
  double raw_rms = 0.0;  // the whole change
  interchange::Capture capture;
};

class Sizer {
 public:
  Sizer(const SweepPlant& plant, const SweepKnob& knob, const SweepEffect& effect, std::uint64_t seed,
        const Clean& clean)
      : plant_(plant), knob_(knob), effect_(effect), seed_(seed), clean_(clean) {}

  // The setting whose effect RMS comes nearest `target` (N·m), and its
  // capture; nullptr when no capture of the effect could be made.
  const Point* size(double target) {
    if (points_.empty() && !measure(effect_.start)) return nullptr;
    for (int tries = 0; tries < kMaxTries; ++tries) {
      const Point& best = *nearest(target);
      if (close(best.rms, target)) break;
      const double next = next_setting(target, best);
      if (std::any_of(points_.begin(), points_.end(), [&](const Point& p) { return p.setting == next; })) break;
      if (!measure(next)) break;
    }
    return nearest(target);
  }
  const std::string& error() const { return error_; }

 private:
  static bool close(double got, double want) { return std::abs(std::log(got / want)) < std::log(kClose); }
  static double miss(const Point& p, double target) { return std::abs(std::log(p.rms / target)); }

  const Point* nearest(double target) const {
    const Point* best = nullptr;
    for (const Point& p : points_)
      if (!best || miss(p, target) < miss(*best, target)) best = &p;
    return best;
  }

  // Between the nearest settings either side of the target, a secant in
  // log–log (halfway, geometrically, when it leaves them); with the target
  // on one side only, a step from the nearest at the local slope, or at unit
  // slope in the effect's direction.
  double next_setting(double target, const Point& best) const {
    const double direction = effect_.grows_with_setting ? 1.0 : -1.0;
    const Point *under = nullptr, *over = nullptr;
    for (const Point& p : points_) {
      if (p.rms < target && (!under || p.rms > under->rms)) under = &p;
      if (p.rms >= target && (!over || p.rms < over->rms)) over = &p;
    }
    const auto slope = [](const Point& a, const Point& b) {
      return std::log(a.rms / b.rms) / std::log(a.setting / b.setting);
    };
    if (under && over) {
      const double lo = std::min(under->setting, over->setting), hi = std::max(under->setting, over->setting);
      const double k = slope(*under, *over);
      const double next = under->setting * std::pow(target / under->rms, 1.0 / k);
      return std::isfinite(next) && next > lo && next < hi ? next : std::sqrt(lo * hi);
    }
    double k = direction;
    if (points_.size() >= 2) {
      const Point* second = nullptr;
      for (const Point& p : points_)
        if (&p != &best && (!second || miss(p, target) < miss(*second, target))) second = &p;
      const double local = slope(best, *second);
      // A slope of the wrong sign or out of all proportion is noise.
      if (std::isfinite(local) && local * direction >= 0.2 && local * direction <= 5.0) k = local;
    }
    return std::clamp(best.setting * std::pow(target / best.rms, 1.0 / k), effect_.lo, effect_.hi);
  }

  const Point* measure(double setting) {
    try {
      interchange::Capture c = plant_.capture(knob_, &effect_, setting, seed_);
      const fit::FitData d = prepared_all_rows(c);
      std::vector<double> change(d.size());
      for (std::size_t i = 0; i < d.size(); ++i) change[i] = d.torque[i] - clean_.data.torque[i];
      // The rows discovery analyses on both captures: an effect can widen
      // the stick band the base fits (a Stribeck curve's excess reads as
      // stuck), and what it then hides is taken up by Eq. 7.
      std::vector<std::size_t> rows;
      const std::vector<std::size_t> moving = analysed_rows(d, slow_speed_of(d));
      std::set_intersection(clean_.rows.begin(), clean_.rows.end(), moving.begin(), moving.end(),
                            std::back_inserter(rows));
      // Floored: a setting with no effect at all still has a logarithm.
      const double raw = rms_over(change, rows);
      const double rms = std::max(unabsorbed_rms(clean_.base, clean_.data, d, rows), 1e-15);
      points_.push_back({setting, rms, raw, std::move(c)});
      return &points_.back();
    } catch (const std::exception& e) {
      error_ = e.what();
      return nullptr;
    }
  }

  const SweepPlant& plant_;
  const SweepKnob& knob_;
  const SweepEffect& effect_;
  std::uint64_t seed_;
  const Clean& clean_;
  std::deque<Point> points_;  // a deque: a Point handed out stays where it is
  std::string error_;
};

std::string mNm(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x * 1e3);
  return buf;
}

void keep_capture(const SweepOptions& opt, const interchange::Capture& c, const std::string& name) {
  if (opt.captures_dir.empty()) return;
  std::filesystem::create_directories(opt.captures_dir);
  interchange::write_csv(c, std::filesystem::path(opt.captures_dir) / (name + ".csv"));
}

}  // namespace

std::vector<double> sweep_targets(bool quick) {
  if (quick) return {1.0, 4.0, 16.0};
  return {0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 30.0};
}

void run_sweep(const SweepPlant& plant, const SweepOptions& opt, const std::function<void(const SweepCase&)>& done) {
  const std::vector<SweepEffect> effects = plant.effects();
  for (int seed = 1; seed <= opt.seeds; ++seed) {
    for (const SweepKnob& knob : sweep_knobs(opt.quick)) {
      if (!opt.knob.empty() && opt.knob != knob.name) continue;
      SweepCase base;
      base.plant = plant.name();
      base.knob = knob.name;
      base.seed = static_cast<std::uint64_t>(seed);
      // The clean knob first: its residual sizes the effects.
      Clean clean;
      SweepCase c0 = base;
      c0.truth = knob.truth;
      try {
        const interchange::Capture capture = plant.capture(knob, nullptr, 0.0, base.seed);
        keep_capture(opt, capture, knob.name + "-clean-" + std::to_string(seed));
        c0.analysis = analyse(capture);
        clean.data = prepared_all_rows(capture);
        // The rows discovery analysed: faster than its fitted stick band
        // (which can be wider than the knob's own).
        const nlohmann::json result = nlohmann::json::parse(c0.analysis.json);
        clean.rows = analysed_rows(clean.data, result.at("slow_speed_rad_s"));
        clean.r = c0.analysis.before;
        clean.base = base_params(result);
        c0.r_Nm = clean.r;
      } catch (const std::exception& e) {
        c0.error = e.what();
      }
      done(c0);
      // The spring-return knob is a case by itself, nothing concealed in it.
      if (!c0.error.empty() || knob.truth != "none") continue;
      for (const SweepEffect& e : effects) {
        if ((e.needs_detents && !knob.detents()) || (!opt.only.empty() && opt.only != e.id)) continue;
        Sizer sizer(plant, knob, e, base.seed, clean);
        std::vector<double> used;
        for (const double target : opt.targets) {
          SweepCase c = base;
          c.truth = e.id;
          c.target = target;
          c.r_Nm = clean.r;
          const Point* p = sizer.size(target * clean.r);
          if (!p) {
            c.error = "no capture: " + sizer.error();
            done(c);
            break;
          }
          // A target the range cannot reach lands on a setting already run.
          if (std::find(used.begin(), used.end(), p->setting) != used.end()) continue;
          used.push_back(p->setting);
          c.setting = p->setting;
          c.spec = plant.describe(e, p->setting);
          c.effect_rms_Nm = p->rms;
          c.raw_rms_Nm = p->raw_rms;
          c.ratio = p->rms / clean.r;
          try {
            keep_capture(opt, p->capture,
                         knob.name + "-" + e.id + "-" + model::shortest_number(target) + "-" + std::to_string(seed));
            c.analysis = analyse(p->capture);
          } catch (const std::exception& ex) {
            c.error = ex.what();
          }
          done(c);
        }
      }
    }
  }
}

void print_sweep_summary(const std::string& plant, double torque_noise, const std::vector<SweepCase>& cases) {
  std::printf("\n%s plant: effect-size sweep\n", plant.c_str());
  std::map<std::string, std::vector<double>> r_by_knob;
  for (const SweepCase& c : cases)
    if (c.clean() && c.truth == "none" && c.error.empty()) r_by_knob[c.knob].push_back(c.r_Nm);
  std::printf("r, the clean knob's held-out residual RMS (mN·m; torque noise %s):", mNm(torque_noise).c_str());
  for (const auto& [knob, rs] : r_by_knob) {
    std::printf(" %s", knob.c_str());
    for (const double r : rs) std::printf(" %s", mNm(r).c_str());
  }
  std::printf("\n\nnamed right (first finding) / cases, by effect size (effect RMS / r)\n%-18s", "effect");
  for (const Bin& b : kBins) std::printf(" %7s", b.label);
  std::printf(" %7s %9s\n", "off", "all");
  std::vector<std::string> order;
  for (const SweepCase& c : cases)
    if (!c.clean() && std::find(order.begin(), order.end(), c.truth) == order.end()) order.push_back(c.truth);
  order.push_back("all");
  for (const std::string& effect : order) {
    std::vector<int> right(kOff + 1), n(kOff + 1);
    int all_right = 0, all_n = 0;
    for (const SweepCase& c : cases) {
      if (c.clean() || (effect != "all" && c.truth != effect)) continue;
      const std::size_t b = bin_of(c.ratio);
      const bool named = c.error.empty() && c.analysis.named == c.truth;
      ++n[b];
      right[b] += named ? 1 : 0;
      ++all_n;
      all_right += named ? 1 : 0;
    }
    std::printf("%-18s", effect.c_str());
    for (std::size_t b = 0; b <= kOff; ++b) {
      char cell[16] = "-";
      if (n[b] > 0) std::snprintf(cell, sizeof cell, "%d/%d", right[b], n[b]);
      std::printf(" %7s", cell);
    }
    std::printf(" %4d/%-4d\n", all_right, all_n);
  }
  int clean = 0, quiet = 0, errors = 0;
  std::vector<double> seconds;
  for (const SweepCase& c : cases) {
    if (!c.error.empty()) {
      ++errors;
      continue;
    }
    seconds.push_back(c.analysis.seconds);
    if (c.clean() && c.truth == "none") {
      ++clean;
      quiet += c.analysis.named == "none" ? 1 : 0;
    }
    if (c.clean() && c.truth != "none")
      std::printf("%s knob (%s by itself): named %s%s\n", c.knob.c_str(), c.truth.c_str(), c.analysis.named.c_str(),
                  c.analysis.tentative.empty() ? "" : (" (tentative " + c.analysis.tentative + ")").c_str());
  }
  std::printf("clean knobs without a finding: %d of %d (false alarms %.0f %%)\n", quiet, clean,
              clean > 0 ? 100.0 * (clean - quiet) / clean : 0.0);
  if (errors > 0) std::printf("cases without an analysis (capture failed): %d\n", errors);
  if (!seconds.empty()) {
    std::sort(seconds.begin(), seconds.end());
    std::printf("analysis (prepare + discover, 8 s at 5 kHz): median %.2f s, slowest %.2f s over %zu cases\n",
                seconds[seconds.size() / 2], seconds.back(), seconds.size());
  }
}

nlohmann::json sweep_case_json(const SweepCase& c) {
  nlohmann::json j = {{"plant", c.plant}, {"knob", c.knob}, {"concealed", c.truth},
                      {"seed", c.seed},   {"effects", c.spec}, {"r_Nm", c.r_Nm}};
  if (!c.clean()) {
    j["setting"] = c.setting;
    j["target_ratio"] = c.target;
    j["effect_rms_Nm"] = c.effect_rms_Nm;
    j["raw_effect_rms_Nm"] = c.raw_rms_Nm;
    j["ratio"] = c.ratio;
    j["raw_ratio"] = c.raw_rms_Nm / c.r_Nm;
  }
  if (!c.error.empty()) {
    j["error"] = c.error;
    return j;
  }
  j["named"] = c.analysis.named;
  j["tentative"] = c.analysis.tentative;
  j["seconds"] = c.analysis.seconds;
  j["result"] = nlohmann::json::parse(c.analysis.json);
  return j;
}

nlohmann::json sweep_summary_json(const std::vector<SweepCase>& cases) {
  const auto count = [](nlohmann::json& j, const std::string& key, int by) {
    j[key] = (j.contains(key) ? j[key].get<int>() : 0) + by;
  };
  nlohmann::json j = nlohmann::json::object();
  for (const SweepCase& c : cases) {
    if (c.clean()) {
      nlohmann::json& k = j[c.plant]["clean"][c.knob];
      count(k, "cases", 1);
      count(k, "named_" + (c.error.empty() ? c.analysis.named : std::string("error")), 1);
      continue;
    }
    const std::size_t b = bin_of(c.ratio);
    nlohmann::json& cell = j[c.plant]["effects"][c.truth][b == kOff ? "off" : kBins[b].label];
    count(cell, "cases", 1);
    count(cell, "named_right", c.error.empty() && c.analysis.named == c.truth ? 1 : 0);
  }
  return j;
}

}  // namespace knoblab::bench
