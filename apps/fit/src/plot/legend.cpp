#include "knoblab/fit/plot/legend.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::fit::plot {

namespace {

bool draws_something(const Series& s) {
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!std::isfinite(s.x[i])) continue;
    if (s.mark == Mark::VLines) return true;
    if (i < s.y.size() && std::isfinite(s.y[i]) &&
        (s.mark != Mark::Fill || (i < s.y_low.size() && std::isfinite(s.y_low[i]))))
      return true;
  }
  return false;
}

}  // namespace

std::vector<LegendEntry> legend_entries(const Panel& panel) {
  struct Ranked {
    LegendEntry entry;
    int rank;
  };
  std::vector<Ranked> ranked;
  for (const Series& s : panel.series) {
    if (s.label.empty() || !draws_something(s)) continue;
    const bool listed = std::any_of(ranked.begin(), ranked.end(),
                                    [&](const Ranked& r) { return r.entry.label == s.label; });
    if (!listed) ranked.push_back({{s.label, s.mark, s.color, s.size_mm}, s.legend_rank});
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const Ranked& a, const Ranked& b) { return a.rank < b.rank; });
  std::vector<LegendEntry> out;
  for (Ranked& r : ranked) out.push_back(std::move(r.entry));
  return out;
}

}  // namespace knoblab::fit::plot
