// The pointing study's report (pointing_report.hpp): the tidy rows grouped
// (tabulate), then each figure from apps/stats. The statistics' own checks
// throw std::invalid_argument; where that means the report cannot be made
// their message is prefixed with what was being computed, and where a test
// is merely undefined on these data (every rating the same) it is left out
// with a note.
#include "knoblab/study/pointing_report.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <map>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "pointing_tables.hpp"

namespace knoblab::study {

namespace detail {

PointingTables tabulate(std::span<const PointingRow> rows, const PointingReportOptions& options) {
  PointingTables t;
  std::vector<const PointingRow*> analysed;
  for (const PointingRow& r : rows)
    if (!r.practice) analysed.push_back(&r);
  if (analysed.empty())
    throw std::invalid_argument("pointing report: no rows to analyse (" + std::to_string(rows.size()) +
                                " rows, all of them practice)");

  std::map<std::string, std::size_t> rendering_index, participant_index;
  if (!options.rendering_order.empty()) {
    for (const std::string& name : options.rendering_order) {
      if (!rendering_index.emplace(name, t.renderings.size()).second)
        throw std::invalid_argument("pointing report: the rendering order names \"" + name + "\" twice");
      t.renderings.push_back(name);
    }
  }
  for (const PointingRow* r : analysed) {
    if (!rendering_index.contains(r->rendering)) {
      if (!options.rendering_order.empty())
        throw std::invalid_argument("pointing report: rendering \"" + r->rendering +
                                    "\" of the rows is not among the levels given in the rendering order");
      rendering_index.emplace(r->rendering, t.renderings.size());
      t.renderings.push_back(r->rendering);
    }
    if (participant_index.emplace(r->participant, t.participants.size()).second) t.participants.push_back(r->participant);
  }
  const std::size_t k = t.renderings.size(), n = t.participants.size();
  t.rows_by_rendering.resize(k);
  t.times.assign(n, std::vector<std::vector<double>>(k));
  t.ratings.assign(n, std::vector<std::vector<double>>(k));

  struct Trial {
    const PointingRow* first = nullptr;
    std::vector<double> times, emg, sc;
  };
  std::map<std::tuple<std::string, unsigned, unsigned, unsigned>, std::size_t> trial_index;
  std::vector<Trial> trials;
  for (const PointingRow* r : analysed) {
    const std::size_t j = rendering_index.at(r->rendering), i = participant_index.at(r->participant);
    t.rows_by_rendering[j].push_back(r);
    t.times[i][j].push_back(r->movement_time_s);
    const auto [it, fresh] = trial_index.try_emplace(std::tuple(r->participant, r->session, r->block, r->trial), trials.size());
    if (fresh) trials.push_back({r, {}, {}, {}});
    Trial& tr = trials[it->second];
    if (tr.first->rendering != r->rendering || tr.first->rating != r->rating ||
        tr.first->amplitude_deg != r->amplitude_deg || tr.first->width_deg != r->width_deg)
      throw std::invalid_argument(std::format(
          "pointing report: the rows of participant {}'s session {}, block {}, trial {} disagree on its rendering, "
          "condition or rating",
          r->participant, r->session, r->block, r->trial));
    tr.times.push_back(r->movement_time_s);
    if (r->emg_uV) tr.emg.push_back(*r->emg_uV);
    if (r->sc_uS) tr.sc.push_back(*r->sc_uS);
  }
  t.acquisitions = analysed.size();
  for (const Trial& tr : trials) {
    PointingTrial p;
    p.participant = participant_index.at(tr.first->participant);
    p.rendering = rendering_index.at(tr.first->rendering);
    p.rating = tr.first->rating;
    p.movement_time_s = mean(tr.times);
    if (!tr.emg.empty()) p.emg_uV = mean(tr.emg);
    if (!tr.sc.empty()) p.sc_uS = mean(tr.sc);
    t.ratings[p.participant][p.rendering].push_back(p.rating);
    t.trials.push_back(p);
  }
  for (std::size_t j = 0; j < k; ++j)
    if (t.rows_by_rendering[j].empty())
      throw std::invalid_argument("pointing report: rendering \"" + t.renderings[j] +
                                  "\" of the rendering order has no analysed rows");
  for (std::size_t i = 0; i < n; ++i) {
    bool all = true;
    for (std::size_t j = 0; j < k; ++j) all = all && !t.times[i][j].empty();
    if (all) t.complete.push_back(i);
  }
  return t;
}

}  // namespace detail

namespace {

std::string deg(double v) { return std::format("{}°", v); }

// A statistic's own refusal, with what the report was computing.
template <typename F>
auto computing(const std::string& what, F f) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("pointing report: " + what + ": " + e.what());
  }
}

PointingRendering fitts(const detail::PointingTables& t, std::size_t j, std::vector<std::string>& notes) {
  PointingRendering out;
  out.rendering = t.renderings[j];
  std::map<std::pair<double, double>, std::pair<std::vector<double>, std::vector<double>>> cells;
  std::vector<double> all_times;
  for (const PointingRow* r : t.rows_by_rendering[j]) {
    auto& [endpoints, times] = cells[{r->amplitude_deg, r->width_deg}];
    endpoints.push_back(r->endpoint_deg);
    times.push_back(r->movement_time_s);
    all_times.push_back(r->movement_time_s);
  }
  for (const auto& [aw, data] : cells) {
    const std::vector<double>& endpoints = data.first;
    const std::vector<double>& times = data.second;
    const std::string where = "rendering \"" + out.rendering + "\", A = " + deg(aw.first) + ", W = " + deg(aw.second);
    if (endpoints.size() < 2)
      throw std::invalid_argument("pointing report: " + where + " has " + std::to_string(endpoints.size()) +
                                  " end point; its effective width needs at least 2");
    PointingCell c;
    c.amplitude_deg = aw.first;
    c.width_deg = aw.second;
    c.n = endpoints.size();
    const stats::EndpointSpread spread = computing(where, [&] { return stats::endpoint_spread(endpoints); });
    const stats::EffectiveThroughput e =
        computing(where, [&] { return stats::effective_throughput(c.amplitude_deg, endpoints, times); });
    c.endpoint_mean_deg = spread.mean;
    c.endpoint_sd_deg = spread.sd;
    c.We_deg = e.effective_width;
    c.IDe_bits = e.index_of_difficulty;
    c.movement_time_s = e.mean_movement_time;
    c.throughput_bits_per_s = e.throughput;
    c.welford_id = stats::welford_index_of_difficulty(c.amplitude_deg, c.width_deg, 10);
    out.cells.push_back(c);
  }
  std::vector<double> we, ide, tp, cell_mt;
  for (const PointingCell& c : out.cells) {
    we.push_back(c.We_deg);
    ide.push_back(c.IDe_bits);
    tp.push_back(c.throughput_bits_per_s);
    cell_mt.push_back(c.movement_time_s);
  }
  out.We_deg = mean(we);
  out.IDe_bits = mean(ide);
  out.throughput_bits_per_s = mean(tp);
  out.movement_time_s = mean(all_times);
  out.acquisitions = all_times.size();
  try {
    out.fitts_line = stats::fit_line(ide, cell_mt);
  } catch (const std::invalid_argument&) {
    notes.push_back("rendering \"" + out.rendering + "\" has no Fitts line: its " + std::to_string(out.cells.size()) +
                    " cell(s) do not give two distinct IDe and movement times");
  }
  std::vector<double> ratings;
  for (const detail::PointingTrial& tr : t.trials)
    if (tr.rendering == j) ratings.push_back(tr.rating);
  out.trials = ratings.size();
  out.rating_mean = mean(ratings);
  return out;
}

}  // namespace

PointingReport pointing_report(std::span<const PointingRow> rows, const PointingReportOptions& options) {
  const detail::PointingTables t = detail::tabulate(rows, options);
  const std::size_t k = t.renderings.size();
  if (k < 2)
    throw std::invalid_argument("pointing report: the rows have one rendering (\"" + t.renderings.front() +
                                "\"); comparing renderings needs at least 2");
  PointingReport report;
  report.trials = t.trials.size();
  report.acquisitions = t.acquisitions;
  for (std::size_t j = 0; j < k; ++j) report.renderings.push_back(fitts(t, j, report.notes));

  // Participants with every rendering: the ANOVA's and the rating tests' cases.
  for (std::size_t i = 0; i < t.participants.size(); ++i) {
    if (std::find(t.complete.begin(), t.complete.end(), i) != t.complete.end()) {
      report.participants.push_back(t.participants[i]);
      continue;
    }
    std::string missing;
    for (std::size_t j = 0; j < k; ++j)
      if (t.times[i][j].empty()) missing += (missing.empty() ? "" : ", ") + t.renderings[j];
    report.notes.push_back("participant " + t.participants[i] +
                           " is left out of the ANOVA and the rating tests: no analysed trials with " + missing);
  }
  if (t.complete.size() < 3) {
    std::string who;
    for (const std::size_t i : t.complete) who += (who.empty() ? ": " : ", ") + t.participants[i];
    throw std::invalid_argument("pointing report: the movement-time ANOVA needs at least 3 participants with trials "
                                "in every rendering (the Huynh–Feldt correction is undefined for 2); " +
                                std::to_string(t.complete.size()) + " have" + who);
  }

  std::vector<std::vector<double>> mt, medians;
  for (const std::size_t i : t.complete) {
    std::vector<double> m, md;
    for (std::size_t j = 0; j < k; ++j) {
      m.push_back(mean(t.times[i][j]));
      md.push_back(median(t.ratings[i][j]));
    }
    mt.push_back(std::move(m));
    medians.push_back(std::move(md));
  }
  report.anova_movement_time = computing("the movement-time ANOVA", [&] { return stats::rm_anova(mt); });
  for (std::size_t j = 0; j < k; ++j) {
    std::vector<double> times, ratings;
    for (std::size_t c = 0; c < t.complete.size(); ++c) {
      times.push_back(mt[c][j]);
      ratings.push_back(mean(t.ratings[t.complete[c]][j]));
    }
    report.renderings[j].movement_time_by_participant = mean_interval(times);
    report.renderings[j].rating_by_participant = mean_interval(ratings);
  }

  RatingTests tests = rating_tests(medians, t.renderings, "rendering", report.notes);
  report.friedman_rating = tests.friedman;
  report.wilcoxon_rating = std::move(tests.wilcoxon);

  std::vector<double> trial_mt, trial_rating, emg_rating, emg, sc_rating, sc;
  for (const detail::PointingTrial& tr : t.trials) {
    trial_mt.push_back(tr.movement_time_s);
    trial_rating.push_back(tr.rating);
    if (tr.emg_uV) emg_rating.push_back(tr.rating), emg.push_back(*tr.emg_uV);
    if (tr.sc_uS) sc_rating.push_back(tr.rating), sc.push_back(*tr.sc_uS);
  }
  const auto correlate = [&](const std::vector<double>& a, const std::vector<double>& b, const std::string& what) {
    return spearman_or_note(a, b, what, report.notes);
  };
  report.correlations.movement_time_rating = correlate(trial_mt, trial_rating, "movement time with rating");
  if (!emg.empty()) report.correlations.rating_emg = correlate(emg_rating, emg, "rating with EMG");
  if (!sc.empty()) report.correlations.rating_sc = correlate(sc_rating, sc, "rating with SC");
  return report;
}

nlohmann::json to_json(const PointingReport& r) {
  nlohmann::json out;
  out["renderings"] = nlohmann::json::array();
  for (const PointingRendering& g : r.renderings) {
    nlohmann::json cells = nlohmann::json::array();
    for (const PointingCell& c : g.cells)
      cells.push_back({{"amplitude_deg", c.amplitude_deg},
                       {"width_deg", c.width_deg},
                       {"n", c.n},
                       {"We_deg", c.We_deg},
                       {"IDe_bits", c.IDe_bits},
                       {"throughput_bits_per_s", c.throughput_bits_per_s},
                       {"movement_time_s", c.movement_time_s},
                       {"welford_id", c.welford_id},
                       {"endpoint_mean_deg", c.endpoint_mean_deg},
                       {"endpoint_sd_deg", c.endpoint_sd_deg}});
    nlohmann::json j = {{"rendering", g.rendering},
                        {"We_deg", g.We_deg},
                        {"IDe_bits", g.IDe_bits},
                        {"throughput_bits_per_s", g.throughput_bits_per_s},
                        {"movement_time_s", g.movement_time_s},
                        {"rating_mean", g.rating_mean},
                        {"trials", g.trials},
                        {"acquisitions", g.acquisitions},
                        {"movement_time_by_participant", to_json(g.movement_time_by_participant)},
                        {"rating_by_participant", to_json(g.rating_by_participant)},
                        {"cells", std::move(cells)}};
    if (g.fitts_line)
      j["fitts_line"] = {{"intercept_s", g.fitts_line->intercept},
                         {"slope_s_per_bit", g.fitts_line->slope},
                         {"r_squared", g.fitts_line->r_squared}};
    out["renderings"].push_back(std::move(j));
  }
  const stats::RmAnovaResult& a = r.anova_movement_time;
  out["anova_movement_time"] = {{"F", a.f},
                                {"df1", a.df1},
                                {"df2", a.df2},
                                {"p", a.p},
                                {"p_gg", a.p_gg},
                                {"epsilon_gg", a.epsilon_gg},
                                {"p_hf", a.p_hf},
                                {"epsilon_hf", a.epsilon_hf},
                                {"partial_eta_squared", a.partial_eta_squared},
                                {"participants", a.subjects}};
  if (r.friedman_rating)
    out["friedman_rating"] = {{"chi_squared", r.friedman_rating->statistic},
                              {"df", r.friedman_rating->df},
                              {"p", r.friedman_rating->p},
                              {"participants", r.participants.size()}};
  out["wilcoxon_rating"] = nlohmann::json::array();
  for (const RatingComparison& c : r.wilcoxon_rating) {
    nlohmann::json j = to_json(c, r.participants.size());
    j["rendering"] = c.level;
    j["control"] = c.control;
    out["wilcoxon_rating"].push_back(std::move(j));
  }
  out["correlations"] = nlohmann::json::object();
  if (r.correlations.movement_time_rating)
    out["correlations"]["movement_time_rating"] = to_json(*r.correlations.movement_time_rating);
  if (r.correlations.rating_emg) out["correlations"]["rating_emg"] = to_json(*r.correlations.rating_emg);
  if (r.correlations.rating_sc) out["correlations"]["rating_sc"] = to_json(*r.correlations.rating_sc);
  out["participants"] = r.participants;
  out["trials"] = r.trials;
  out["acquisitions"] = r.acquisitions;
  out["notes"] = r.notes;
  return out;
}

std::string format_pointing_report(const PointingReport& r) {
  std::string s;
  s += std::format("Pointing report: {} participants in the tests, {} renderings, {} trials, {} acquisitions "
                   "(practice left out)\n",
                   r.participants.size(), r.renderings.size(), r.trials, r.acquisitions);
  s += "\nFitts' law per rendering (We = 4.133·SD of the end points, IDe = log2(A/We + 1), TP = IDe / mean MT;\n"
       "'all': We, IDe and TP the means over the cells, MT over the acquisitions; ID = Welford's\n"
       "log10(A/W + 0.5) with the nominal W, as Table 27)\n";
  for (const PointingRendering& g : r.renderings) {
    s += std::format("\n{}: {} trials, mean rating {:.2f}\n", g.rendering, g.trials, g.rating_mean);
    s += "     A (°)     W (°)      n    MT (s)    SD (°)    We (°)  IDe (bits)  TP (bits/s)   ID (Welford)\n";
    for (const PointingCell& c : g.cells)
      s += std::format("{:>10} {:>9} {:>6} {:>9.4f} {:>9.3f} {:>9.3f} {:>11.3f} {:>12.3f} {:>14.3f}\n",
                       std::format("{}", c.amplitude_deg), std::format("{}", c.width_deg), c.n, c.movement_time_s,
                       c.endpoint_sd_deg, c.We_deg, c.IDe_bits, c.throughput_bits_per_s, c.welford_id);
    s += std::format("{:>10} {:>9} {:>6} {:>9.4f} {:>9} {:>9.3f} {:>11.3f} {:>12.3f}\n", "all", "", g.acquisitions,
                     g.movement_time_s, "", g.We_deg, g.IDe_bits, g.throughput_bits_per_s);
    if (g.fitts_line)
      s += std::format("  Fitts line through the cells: MT = {:.4f} s + {:.4f} s/bit × IDe, r² = {:.3f}\n",
                       g.fitts_line->intercept, g.fitts_line->slope, g.fitts_line->r_squared);
  }
  const stats::RmAnovaResult& a = r.anova_movement_time;
  s += std::format("\nMovement time over renderings: repeated-measures ANOVA on each participant's mean ({} "
                   "participants)\n",
                   a.subjects);
  s += "  source           SS        df          MS          F          p\n";
  s += std::format("  rendering {:>10.5f} {:>9} {:>11.6f} {:>10.3f} {:>10}\n", a.ss_conditions, std::format("{}", a.df1),
                   a.ss_conditions / a.df1, a.f, p_text(a.p));
  s += std::format("  error     {:>10.5f} {:>9} {:>11.6f}\n", a.ss_error, std::format("{}", a.df2), a.ss_error / a.df2);
  s += std::format("  Greenhouse–Geisser ε = {:.4f}: F({:.2f}, {:.2f}), p = {}\n", a.epsilon_gg, a.epsilon_gg * a.df1,
                   a.epsilon_gg * a.df2, p_text(a.p_gg));
  const double hf = std::min(1.0, a.epsilon_hf);
  s += std::format("  Huynh–Feldt ε = {:.4f}: F({:.2f}, {:.2f}), p = {}\n", a.epsilon_hf, hf * a.df1, hf * a.df2,
                   p_text(a.p_hf));
  s += std::format("  partial η² = {:.3f}\n", a.partial_eta_squared);
  s += std::format("  {:<16} {:>11}   {}\n", "rendering", "mean MT (s)", "95 % CI over participants");
  for (const PointingRendering& g : r.renderings) {
    const ParticipantMean& m = g.movement_time_by_participant;
    s += std::format("  {} {:>11.4f}   [{:.4f}, {:.4f}]\n", pad(g.rendering, 16), m.mean, m.low, m.high);
  }

  s += "\nRatings (each participant's median per rendering)\n";
  s += format_rating_tests({r.friedman_rating, r.wilcoxon_rating}, r.participants.size());
  s += "\nSpearman correlations over trials\n";
  const auto corr = [&](const char* what, const std::optional<stats::CorrelationResult>& c) {
    if (c) s += std::format("  {} ρ({}) = {:.4f}, p = {}\n", pad(what, 28), c->n, c->r, p_text(c->p));
  };
  corr("movement time with rating", r.correlations.movement_time_rating);
  corr("rating with EMG", r.correlations.rating_emg);
  corr("rating with SC", r.correlations.rating_sc);
  if (!r.notes.empty()) {
    s += "\nNotes\n";
    for (const std::string& n : r.notes) s += "  - " + n + "\n";
  }
  return s;
}

}  // namespace knoblab::study
