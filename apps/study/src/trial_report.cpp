// The per-trial report (trial_report.hpp): the rows grouped by participant
// and level, then each figure from level_tests. A test that is undefined on
// these data (every rating the same) is left out with a note; data that
// cannot support the report at all are an error naming what is missing.
#include "knoblab/study/trial_report.hpp"

#include <algorithm>
#include <cmath>
#include <format>
#include <limits>
#include <stdexcept>
#include <utility>

namespace knoblab::study {

namespace {

constexpr const char* kSlider = "slider_";

// Names in the order the rows first give them.
void remember(std::vector<std::string>& names, const std::string& name) {
  if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
}

struct Grouped {
  std::vector<std::string> levels, participants, scales, measures;
  // [participant][level] → name → the values of its trials
  std::vector<std::vector<std::map<std::string, std::vector<double>>>> ratings, measures_by;
  std::vector<std::size_t> trials_per_level;
  std::vector<std::size_t> complete;  // participants with every level
  std::vector<const TrialRow*> analysed;
};

Grouped group(std::span<const TrialRow> rows, const TrialReportOptions& options) {
  Grouped g;
  for (const TrialRow& r : rows)
    if (!r.practice) g.analysed.push_back(&r);
  if (g.analysed.empty())
    throw std::invalid_argument("study report: no trials to analyse (" + std::to_string(rows.size()) +
                                " trials, all of them practice)");
  std::map<std::string, std::size_t> level_index, participant_index;
  for (const std::string& l : options.levels) {
    if (!level_index.emplace(l, g.levels.size()).second)
      throw std::invalid_argument("study report: the level order names \"" + l + "\" twice");
    g.levels.push_back(l);
  }
  for (const TrialRow* r : g.analysed) {
    const auto it = r->levels.find(options.factor);
    if (it == r->levels.end())
      throw std::invalid_argument(std::format("study report: participant {}'s trial {} has no level of factor \"{}\"",
                                              r->participant, r->trial, options.factor));
    if (!level_index.contains(it->second)) {
      if (!options.levels.empty())
        throw std::invalid_argument("study report: level \"" + it->second + "\" of the trials is not among the levels of " +
                                    options.factor);
      level_index.emplace(it->second, g.levels.size());
      g.levels.push_back(it->second);
    }
    if (participant_index.emplace(r->participant, g.participants.size()).second) g.participants.push_back(r->participant);
    for (const auto& [name, v] : r->ratings) remember(g.scales, name);
    for (const auto& [name, v] : r->measures) remember(g.measures, name);
  }
  const std::size_t k = g.levels.size(), n = g.participants.size();
  g.ratings.assign(n, std::vector<std::map<std::string, std::vector<double>>>(k));
  g.measures_by = g.ratings;
  g.trials_per_level.assign(k, 0);
  std::vector<std::vector<bool>> seen(n, std::vector<bool>(k, false));
  for (const TrialRow* r : g.analysed) {
    const std::size_t i = participant_index.at(r->participant), j = level_index.at(r->levels.at(options.factor));
    seen[i][j] = true;
    ++g.trials_per_level[j];
    for (const auto& [name, v] : r->ratings) g.ratings[i][j][name].push_back(v);
    for (const auto& [name, v] : r->measures) g.measures_by[i][j][name].push_back(v);
  }
  for (std::size_t j = 0; j < k; ++j)
    if (g.trials_per_level[j] == 0)
      throw std::invalid_argument("study report: level \"" + g.levels[j] + "\" of " + options.factor +
                                  " has no analysed trials");
  if (k < 2)
    throw std::invalid_argument("study report: the trials have one level of " + options.factor + " (\"" + g.levels[0] +
                                "\"); comparing levels needs at least 2");
  for (std::size_t i = 0; i < n; ++i)
    if (std::all_of(seen[i].begin(), seen[i].end(), [](bool b) { return b; })) g.complete.push_back(i);
  if (g.complete.size() < 2)
    throw std::invalid_argument(std::format("study report: comparing the levels of {} needs at least 2 participants "
                                            "with trials in every level; {} of {} have",
                                            options.factor, g.complete.size(), n));
  return g;
}

using Table = std::vector<std::vector<std::map<std::string, std::vector<double>>>>;

// Each complete participant's mean of `name` in level j, or none when one
// of them has no value of it there.
std::optional<std::vector<double>> participant_means(const Grouped& g, const Table& t, std::size_t j,
                                                     const std::string& name) {
  std::vector<double> out;
  for (const std::size_t i : g.complete) {
    const auto it = t[i][j].find(name);
    if (it == t[i][j].end()) return std::nullopt;
    out.push_back(mean(it->second));
  }
  return out;
}

std::map<std::string, double> trial_means(const Grouped& g, const Table& t, std::size_t j) {
  std::map<std::string, std::vector<double>> all;
  for (std::size_t i = 0; i < g.participants.size(); ++i)
    for (const auto& [name, v] : t[i][j]) all[name].insert(all[name].end(), v.begin(), v.end());
  std::map<std::string, double> out;
  for (const auto& [name, v] : all) out[name] = mean(v);
  return out;
}

}  // namespace

TrialReport trial_report(std::span<const TrialRow> rows, const TrialReportOptions& options) {
  const Grouped g = group(rows, options);
  const std::size_t k = g.levels.size();
  TrialReport report;
  report.factor = options.factor;
  report.trials = g.analysed.size();
  for (const std::size_t i : g.complete) report.participants.push_back(g.participants[i]);
  for (std::size_t i = 0; i < g.participants.size(); ++i)
    if (std::find(g.complete.begin(), g.complete.end(), i) == g.complete.end())
      report.notes.push_back("participant " + g.participants[i] + " is left out of the tests and intervals: not every " +
                             options.factor + " has an analysed trial of theirs");

  for (std::size_t j = 0; j < k; ++j) {
    LevelSummary s;
    s.level = g.levels[j];
    s.trials = g.trials_per_level[j];
    s.rating_mean = trial_means(g, g.ratings, j);
    s.measure_mean = trial_means(g, g.measures_by, j);
    for (const std::string& name : g.scales)
      if (auto v = participant_means(g, g.ratings, j, name)) {
        s.rating_by_participant[name] = mean_interval(*v);
        s.rating_values[name] = std::move(*v);
      }
    for (const std::string& name : g.measures)
      if (auto v = participant_means(g, g.measures_by, j, name)) {
        s.measure_by_participant[name] = mean_interval(*v);
        s.measure_values[name] = std::move(*v);
      }
    report.levels.push_back(std::move(s));
  }

  for (const std::string& scale : g.scales) {
    ScaleTests st;
    st.scale = scale;
    std::vector<std::vector<double>> medians;
    bool every = true;
    for (const std::size_t i : g.complete) {
      std::vector<double> row;
      for (std::size_t j = 0; j < k; ++j) {
        const auto it = g.ratings[i][j].find(scale);
        if (it == g.ratings[i][j].end()) {
          every = false;
          break;
        }
        row.push_back(median(it->second));
      }
      medians.push_back(std::move(row));
    }
    if (every) {
      std::vector<std::string> notes;
      st.tests = rating_tests(medians, g.levels, options.factor, notes);
      for (const std::string& n : notes) report.notes.push_back(scale + ": " + n);
    } else {
      report.notes.push_back("no tests of " + scale + ": not every participant rated it in every " + options.factor);
    }
    std::vector<double> r_emg, emg, r_sc, sc;
    for (const TrialRow* r : g.analysed) {
      const auto it = r->ratings.find(scale);
      if (it == r->ratings.end()) continue;
      if (r->emg_uV) r_emg.push_back(it->second), emg.push_back(*r->emg_uV);
      if (r->sc_uS) r_sc.push_back(it->second), sc.push_back(*r->sc_uS);
    }
    if (!emg.empty()) st.emg = spearman_or_note(r_emg, emg, scale + " with EMG", report.notes);
    if (!sc.empty()) st.sc = spearman_or_note(r_sc, sc, scale + " with SC", report.notes);
    report.scales.push_back(std::move(st));
  }

  for (std::size_t j = 0; j < k; ++j) {
    const auto ref = options.references.find(g.levels[j]);
    if (ref == options.references.end()) continue;
    for (const std::string& name : g.measures) {
      if (!name.starts_with(kSlider)) continue;
      const std::string parameter = name.substr(std::string_view(kSlider).size());
      const auto value = ref->second.find(parameter);
      const auto matched = report.levels[j].measure_by_participant.find(name);
      if (value == ref->second.end() || matched == report.levels[j].measure_by_participant.end()) continue;
      MatchEstimate m;
      m.level = g.levels[j];
      m.parameter = parameter;
      m.reference = value->second;
      m.matched = matched->second;
      if (m.reference != 0) {
        m.ratio = m.matched.mean / m.reference;
      } else {
        m.ratio = std::numeric_limits<double>::quiet_NaN();
        report.notes.push_back("knob " + m.level + " has no " + parameter + ": its matches have no ratio");
      }
      report.matches.push_back(m);
    }
  }
  return report;
}

nlohmann::json to_json(const TrialReport& r) {
  using nlohmann::json;
  json out;
  out["factor"] = r.factor;
  out["levels"] = json::array();
  for (const LevelSummary& s : r.levels) {
    json by_rating = json::object(), by_measure = json::object();
    for (const auto& [name, m] : s.rating_by_participant) by_rating[name] = to_json(m);
    for (const auto& [name, m] : s.measure_by_participant) by_measure[name] = to_json(m);
    out["levels"].push_back({{"level", s.level},
                             {"trials", s.trials},
                             {"rating_mean", s.rating_mean},
                             {"measure_mean", s.measure_mean},
                             {"rating_by_participant", by_rating},
                             {"measure_by_participant", by_measure}});
  }
  out["scales"] = json::array();
  for (const ScaleTests& st : r.scales) {
    json j = {{"scale", st.scale}, {"wilcoxon", json::array()}};
    if (st.tests.friedman)
      j["friedman"] = {{"chi_squared", st.tests.friedman->statistic},
                       {"df", st.tests.friedman->df},
                       {"p", st.tests.friedman->p},
                       {"participants", r.participants.size()}};
    for (const RatingComparison& c : st.tests.wilcoxon) {
      json w = to_json(c, r.participants.size());
      w["level"] = c.level;
      w["control"] = c.control;
      j["wilcoxon"].push_back(std::move(w));
    }
    if (st.emg) j["emg"] = to_json(*st.emg);
    if (st.sc) j["sc"] = to_json(*st.sc);
    out["scales"].push_back(std::move(j));
  }
  out["matches"] = json::array();
  for (const MatchEstimate& m : r.matches)
    out["matches"].push_back({{"level", m.level},
                              {"parameter", m.parameter},
                              {"reference", m.reference},
                              {"matched", to_json(m.matched)},
                              {"ratio", std::isfinite(m.ratio) ? json(m.ratio) : json()}});
  out["participants"] = r.participants;
  out["trials"] = r.trials;
  out["notes"] = r.notes;
  return out;
}

std::string format_trial_report(const TrialReport& r) {
  std::string s = std::format("Study report: {} participants in the tests, {} levels of {}, {} trials (practice left out)\n",
                              r.participants.size(), r.levels.size(), r.factor, r.trials);
  for (const ScaleTests& st : r.scales) {
    s += std::format("\n{} per {} (mean over trials; participants' mean with its 95 % CI)\n", st.scale, r.factor);
    for (const LevelSummary& l : r.levels) {
      const auto m = l.rating_mean.find(st.scale);
      const auto p = l.rating_by_participant.find(st.scale);
      s += "  " + pad(l.level, 16) + std::format(" {:>4} trials", l.trials);
      if (m != l.rating_mean.end()) s += std::format("  mean {:>6.3f}", m->second);
      if (p != l.rating_by_participant.end())
        s += std::format("  participants {:.3f} [{:.3f}, {:.3f}]", p->second.mean, p->second.low, p->second.high);
      s += "\n";
    }
    s += std::format("  (each participant's median per {})\n", r.factor);
    s += format_rating_tests(st.tests, r.participants.size());
    const auto corr = [&](const char* what, const std::optional<stats::CorrelationResult>& c) {
      if (c) s += std::format("  Spearman {} ρ({}) = {:.4f}, p = {}\n", what, c->n, c->r, p_text(c->p));
    };
    corr("with EMG (corrugator − depressor)", st.emg);
    corr("with SC (peak − baseline)", st.sc);
  }
  // The measures every level has, as the participants' means.
  std::vector<std::string> measures;
  for (const auto& [name, m] : r.levels.front().measure_by_participant)
    if (std::all_of(r.levels.begin(), r.levels.end(),
                    [&](const LevelSummary& l) { return l.measure_by_participant.contains(name); }))
      measures.push_back(name);
  if (!measures.empty()) {
    s += std::format("\nMeasures per {} (participants' mean with its 95 % CI)\n", r.factor);
    for (const std::string& name : measures) {
      s += "  " + name + "\n";
      for (const LevelSummary& l : r.levels) {
        const ParticipantMean& m = l.measure_by_participant.at(name);
        s += std::format("    {} {:>10.4g}  [{:.4g}, {:.4g}]\n", pad(l.level, 16), m.mean, m.low, m.high);
      }
    }
  }
  if (!r.matches.empty()) {
    s += "\nMatched against the reference knobs (participants' mean setting, SI; ratio = matched / reference)\n";
    s += "  knob             parameter          reference      matched  95 % CI                      ratio\n";
    for (const MatchEstimate& m : r.matches)
      s += std::format("  {} {} {:>10.4g} {:>12.4g}  [{:.4g}, {:.4g}]  {}\n", pad(m.level, 16), pad(m.parameter, 16),
                       m.reference, m.matched.mean, m.matched.low, m.matched.high,
                       std::isfinite(m.ratio) ? std::format("{:.3f}", m.ratio) : "–");
  }
  if (!r.notes.empty()) {
    s += "\nNotes\n";
    for (const std::string& n : r.notes) s += "  - " + n + "\n";
  }
  return s;
}

}  // namespace knoblab::study
